// Prism layers across MPI ranks (run under mpiexec -np 1..4): the exchange
// of the layer kernel (mpiLayerExchange) and the global numbers of layer
// points (globalPointNumbering::addLayerPoints), on a real coarse mesh (a
// cube), partitioned and refined as stages 2-3 do, its surface bent
// smoothly so that no two points' normals are alike. Every rank also
// builds the one-part surface and grows its layers serially
// (noLayerExchange): the serial twin each rank compares its points with,
// by barycentric id, bit for bit.

#include "mpiTestMain.H"
#include "globalNumbering.H"
#include "mpiLayerExchange.H"
#include "partitionedCube.H"
#include "layerStage.H"
#include "wallLayers.H"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <stdlib.h>

using namespace pmsh;

namespace
{

const int levels = 2;

struct layeredCase
:
    test::partitionedSurface
{
    FineSurface whole;      // the one-part surface: the serial twin
    std::map<barycentricId, label> wholeIndex;
};

// A smooth bend of the cube's faces, a function of the point's bits alone
// (so the same on every rank), small against the fine edges (1/16)
void bend(FineSurface& s)
{
    for (point3& x : s.points)
    {
        const point3 y = x;
        x[0] += 0.006*std::sin(5*y[1] + 1)*std::cos(3*y[2]);
        x[1] += 0.006*std::sin(4*y[2] + 2)*std::cos(3*y[0]);
        x[2] += 0.006*std::sin(6*y[0] + 3)*std::cos(2*y[1]);
    }
}

// Built once per process: the master's coarse mesh, as pmshFoam does
const layeredCase& theCase()
{
    static layeredCase c = []
    {
        layeredCase c{test::partitionedCube(4, levels), {}, {}};
        const std::vector<label> onePart(c.coarse.nCells(), 0);
        c.whole = refineSurface
        (
            c.coarse, partitionSurface(c.coarse, onePart, 0),
            boundaryEdgeSurfaces(c.coarse), nullptr, levels
        );
        bend(c.part);
        bend(c.whole);
        for (label p = 0; p < label(c.whole.ids.size()); ++p)
        {
            c.wholeIndex[c.whole.ids[p]] = p;
        }
        return c;
    }();
    return c;
}

// The layered walls: the cube's three low sides (they meet at a corner),
// the others unlayered, so stacks also slide along unlayered walls
std::map<label, layerSpecification> walls(int nLayers, double first, double ratio)
{
    layerSpecification s;
    s.nLayers = nLayers;
    s.firstLayerThickness = first;
    s.expansionRatio = ratio;
    s.minThickness = 0.1*first;
    return {{0, s}, {2, s}, {4, s}};
}

wallLayers grow
(
    const FineSurface& s,
    const std::map<label, layerSpecification>& specs,
    layerExchange& exchange
)
{
    return growWallLayers({s.points, s.ids, s.triangles, s.region, s.piece, specs, nullptr}, exchange);
}

bool sameBits(const void* a, const void* b, std::size_t n)
{
    return std::memcmp(a, b, n) == 0;
}

// Triangle t's contribution: its area vector from its points in id order
// (the same bits on every rank holding it), tagged with its region
keyedContribution contributionOf(const FineSurface& s, label t)
{
    std::array<label, 3> f = s.triangles[t];
    std::sort(f.begin(), f.end(), [&](label a, label b) { return s.ids[a] < s.ids[b]; });
    const vector3 area = cross(s.points[f[1]] - s.points[f[0]], s.points[f[2]] - s.points[f[0]]);
    return {{s.ids[f[0]], s.ids[f[1]], s.ids[f[2]]}, s.region[t], area};
}

// Per point, the contributions of its wall triangles (an interface
// triangle is in two parts: it contributes nothing), sorted by (tag, key);
// and the least |area| of them
void stars
(
    const FineSurface& s,
    std::vector<std::vector<keyedContribution>>& star,
    std::vector<double>& least
)
{
    star.assign(s.points.size(), {});
    least.assign(s.points.size(), std::numeric_limits<double>::infinity());
    for (label t = 0; t < label(s.triangles.size()); ++t)
    {
        if (s.region[t] < 0)
        {
            continue;
        }
        const keyedContribution c = contributionOf(s, t);
        for (const label p : s.triangles[t])
        {
            star[p].push_back(c);
            least[p] = std::min(least[p], std::sqrt(magSqr(c.value)));
        }
    }
}

void sortStar(std::vector<keyedContribution>& star)
{
    std::sort
    (
        star.begin(), star.end(),
        [](const keyedContribution& a, const keyedContribution& b)
        {
            return a.tag != b.tag ? a.tag < b.tag : a.key < b.key;
        }
    );
}

// The ranks holding the surface point with this id
std::vector<int> holdersOf(const layeredCase& c, const barycentricId& id)
{
    static const coarsePointCells pointCells(theCase().coarse);
    return holderRanks(id, pointCells, c.cellPart);
}


// One point's layers as bits, and who has them
struct pointLayers
{
    barycentricId id;
    int nLayers;
    double thickness;
    vector3 direction;
};

std::vector<pointLayers> layerRecords(const FineSurface& s, const wallLayers& layers)
{
    std::vector<pointLayers> r;
    for (label p = 0; p < label(s.points.size()); ++p)
    {
        r.push_back({s.ids[p], layers.nLayers[p], layers.thickness[p], layers.direction[p]});
    }
    return r;
}

// The serial twin's layers of a part's point; none for a point inside the
// domain (on a partition interface only)
pointLayers serialOf(const layeredCase& c, const std::vector<pointLayers>& serial, const barycentricId& id)
{
    const auto it = c.wholeIndex.find(id);
    return it != c.wholeIndex.end() ? serial[it->second] : pointLayers{id, 0, 0, {0, 0, 0}};
}

// The point's layers agree with the serial twin's, bit for bit
::testing::AssertionResult sameAsSerial(const pointLayers& a, const pointLayers& one)
{
    if
    (
        a.nLayers != one.nLayers
     || !sameBits(&a.thickness, &one.thickness, sizeof(double))
     || !sameBits(&a.direction, &one.direction, sizeof(vector3))
    )
    {
        return ::testing::AssertionFailure()
            << "point " << a.id << ": " << a.nLayers << " layers, thickness "
            << a.thickness << " against " << one.nLayers << ", " << one.thickness;
    }
    return ::testing::AssertionSuccess();
}

// Every holder of a point has the same bits: each rank's records
// compared on the master (collective)
void expectHoldersAgree(const std::vector<pointLayers>& ours)
{
    const auto all = test::gatherOnMaster(ours);
    if (!test::world().master())
    {
        return;
    }
    std::map<barycentricId, pointLayers> byId;
    label nCompared = 0, nDiffer = 0;
    for (const auto& rank : all)
    {
        for (const pointLayers& r : rank)
        {
            auto [it, inserted] = byId.emplace(r.id, r);
            if (!inserted)
            {
                ++nCompared;
                const ::testing::AssertionResult same = sameAsSerial(r, it->second);
                if (!same && ++nDiffer <= 5)
                {
                    ADD_FAILURE() << "holders differ: " << same.message();
                }
            }
        }
    }
    EXPECT_EQ(nDiffer, 0) << "of " << nCompared << " shared points";
    if (all.size() > 1)
    {
        EXPECT_GT(nCompared, 0);
    }
}

// Per point of a part: edge rings from the nearest partition-interface
// point (0 on the interface; large where there is none)
std::vector<int> ringsFromInterface(const FineSurface& s)
{
    std::vector<int> rings(s.points.size(), std::numeric_limits<int>::max());
    std::vector<label> front;
    for (label t = 0; t < label(s.triangles.size()); ++t)
    {
        for (const label p : s.triangles[t])
        {
            if (s.region[t] < 0 && rings[p] != 0)
            {
                rings[p] = 0;
                front.push_back(p);
            }
        }
    }
    std::vector<std::vector<label>> neighbours(s.points.size());
    for (const triVerts& f : s.triangles)
    {
        for (int i = 0; i < 3; ++i)
        {
            neighbours[f[i]].push_back(f[(i + 1) % 3]);
            neighbours[f[(i + 1) % 3]].push_back(f[i]);
        }
    }
    for (int ring = 1; !front.empty(); ++ring)
    {
        std::vector<label> next;
        for (const label p : front)
        {
            for (const label q : neighbours[p])
            {
                if (rings[q] > ring)
                {
                    rings[q] = ring;
                    next.push_back(q);
                }
            }
        }
        front.swap(next);
    }
    return rings;
}

// Wall layers grown on this rank's part through the MPI exchange and on
// the serial twin (noLayerExchange), with their points' records
struct grownTwins
{
    wallLayers mine;
    wallLayers one;
    std::vector<pointLayers> ours;
    std::vector<pointLayers> ref;
};

grownTwins growTwins(const std::map<label, layerSpecification>& specs)
{
    const layeredCase& c = theCase();
    mpiLayerExchange exchange(test::world(), c.coarse, c.cellPart, levels);
    noLayerExchange serial;
    grownTwins g;
    g.mine = grow(c.part, specs, exchange);
    g.one = grow(c.whole, specs, serial);
    g.ours = layerRecords(c.part, g.mine);
    g.ref = layerRecords(c.whole, g.one);
    return g;
}

} // End anonymous namespace


TEST(parallelLayers, exchangeGivesEveryHolderTheWholeStarAndItsMinimum)
{
    const Communicator& comm = test::world();
    const layeredCase& c = theCase();

    // Every surface point is passed, shared or not: the exchange leaves
    // a point held by this rank alone as it is
    std::vector<std::vector<keyedContribution>> star;
    std::vector<double> least;
    stars(c.part, star, least);
    mpiLayerExchange exchange(comm, c.coarse, c.cellPart, levels);
    EXPECT_TRUE(exchange.packed());
    exchange.gatherContributions(c.part.ids, star);
    exchange.minimum(c.part.ids, least);
    exchange.minimum(c.part.ids, least);     // again, through the cached plan
    if (comm.size() > 1)
    {
        EXPECT_GT(comm.sum(std::int64_t(exchange.nShared())), 0);
    }

    std::vector<std::vector<keyedContribution>> wholeStar;
    std::vector<double> wholeLeast;
    stars(c.whole, wholeStar, wholeLeast);
    label nDiffer = 0;
    // A point inside the domain (on an interface only) has no wall star
    wholeStar.emplace_back();
    wholeLeast.push_back(std::numeric_limits<double>::infinity());
    for (label p = 0; p < label(c.part.points.size()); ++p)
    {
        const auto it = c.wholeIndex.find(c.part.ids[p]);
        const label q = it != c.wholeIndex.end() ? it->second : label(wholeStar.size()) - 1;
        if (it != c.wholeIndex.end())
        {
            ASSERT_TRUE(sameBits(&c.part.points[p], &c.whole.points[q], sizeof(point3)));
        }
        sortStar(star[p]);
        sortStar(wholeStar[q]);
        bool same = star[p].size() == wholeStar[q].size()
            && sameBits(&least[p], &wholeLeast[q], sizeof(double));
        for (std::size_t i = 0; same && i < star[p].size(); ++i)
        {
            same = star[p][i].key == wholeStar[q][i].key && star[p][i].tag == wholeStar[q][i].tag
                && sameBits(&star[p][i].value, &wholeStar[q][i].value, sizeof(vector3));
        }
        if (!same && ++nDiffer <= 5)
        {
            ADD_FAILURE() << "point " << c.part.ids[p] << " has " << star[p].size()
                << " contributions, least " << least[p] << "; its whole star "
                << wholeStar[q].size() << ", least " << wholeLeast[q];
        }
    }
    EXPECT_EQ(nDiffer, 0) << "of " << c.part.points.size() << " points";
    EXPECT_TRUE(exchange.anyRank(comm.rank() == comm.size() - 1));
    EXPECT_FALSE(exchange.anyRank(false));
}


TEST(parallelLayers, thinLayersAreTheSerialLayersBitForBitOnEveryRank)
{
    // Thin against the triangles: no lifted interface triangle limits them,
    // so nothing depends on the partition
    const Communicator& comm = test::world();
    const layeredCase& c = theCase();
    const grownTwins g = growTwins(walls(3, 0.001, 1.2));
    EXPECT_EQ(comm.sum(std::int64_t(g.mine.stats.nInterfaceLimited)), 0);

    label nLayered = 0, nDiffer = 0;
    for (const pointLayers& r : g.ours)
    {
        nLayered += r.nLayers > 0;
        const ::testing::AssertionResult same = sameAsSerial(r, serialOf(c, g.ref, r.id));
        if (!same && ++nDiffer <= 5)
        {
            ADD_FAILURE() << same.message();
        }
    }
    EXPECT_EQ(nDiffer, 0) << "of " << g.ours.size() << " points";
    EXPECT_GT(comm.sum(std::int64_t(nLayered)), 0);
    expectHoldersAgree(g.ours);
}


TEST(parallelLayers, thickLayersAgreeOnEveryHolderAndAwayFromInterfacesWithSerial)
{
    // As thick as a fine edge: lifted interface triangles may limit them
    // at P > 1 (the one partition-dependent limit, wallLayers.H); every
    // holder still has the same bits, and points far from any interface
    // the serial ones
    const Communicator& comm = test::world();
    const layeredCase& c = theCase();
    const grownTwins g = growTwins(walls(4, 0.012, 1.3));
    ASSERT_GT(g.one.stats.nInvalidLimited + g.one.stats.nFeatureLimited, 0);
    // The sharp edges thin alike at any P, and the ranks' figures, summed,
    // count each of those points once, also where two ranks hold it
    ASSERT_GT(g.one.stats.nFeatureLimited, 0);
    EXPECT_EQ(comm.sum(std::int64_t(g.mine.stats.nFeatureLimited)), g.one.stats.nFeatureLimited);

    const std::vector<int> rings = ringsFromInterface(c.part);
    label nFar = 0, nDiffer = 0;
    for (label p = 0; p < label(g.ours.size()); ++p)
    {
        if (rings[p] < 8)
        {
            continue;
        }
        ++nFar;
        const ::testing::AssertionResult same =
            sameAsSerial(g.ours[p], serialOf(c, g.ref, g.ours[p].id));
        if (!same && ++nDiffer <= 5)
        {
            ADD_FAILURE() << same.message() << " (" << rings[p] << " rings from an interface)";
        }
    }
    EXPECT_EQ(nDiffer, 0) << "of " << nFar << " points far from interfaces";
    EXPECT_GT(comm.sum(std::int64_t(nFar)), 0);
    expectHoldersAgree(g.ours);
}


namespace
{

// A local point's name, the same on every rank that has it: a surface
// point's id and level -1, a layer point's id and level, an interior
// point's (-1 - rank, index)
struct numberRecord
{
    std::array<long long, 7> key;
    long long number;
};

std::array<long long, 7> keyOf(const barycentricId& id, int level)
{
    return {id.vertex[0], id.weight[0], id.vertex[1], id.weight[1], id.vertex[2], id.weight[2], level};
}

// Number the part's points (its surface points, then 5 interior points,
// then the layer points) and check on the master, from every rank's
// records, that each name has one number, and that the numbers of the
// distinct names are exactly 0..nGlobal-1; nGlobal is the sum of nOwned.
void expectLayerNumbers
(
    const layeredCase& c,
    const std::vector<std::pair<label, int>>& layerPoints
)
{
    const Communicator& comm = test::world();
    const label nSurface = label(c.part.points.size());
    const label nLocal = nSurface + 5;
    globalPointNumbering numbering(comm, c.coarse, c.cellPart, c.part, nLocal);
    const std::vector<label> ordinary = numbering.globalIds();
    const label nOrdinary = numbering.nGlobal();
    numbering.addLayerPoints(comm, c.coarse, c.cellPart, c.part.ids, layerPoints);

    const std::vector<label>& numbers = numbering.globalIds();
    ASSERT_EQ(numbers.size(), std::size_t(nLocal) + layerPoints.size());
    EXPECT_TRUE(std::equal(ordinary.begin(), ordinary.end(), numbers.begin()))
        << "the ordinary points' numbers changed";
    EXPECT_EQ(comm.sum(std::int64_t(numbering.nOwned())), std::int64_t(numbering.nGlobal()));

    std::vector<numberRecord> mine;
    for (label p = 0; p < label(numbers.size()); ++p)
    {
        std::array<long long, 7> key{-1 - comm.rank(), p, 0, 0, 0, 0, -2};
        if (p < nSurface)
        {
            key = keyOf(c.part.ids[p], -1);
        }
        else if (p >= nLocal)
        {
            const auto [q, k] = layerPoints[p - nLocal];
            key = keyOf(c.part.ids[q], k);
            // Layer points come after every ordinary point
            EXPECT_GE(numbers[p], nOrdinary);
        }
        mine.push_back({key, numbers[p]});
    }
    const auto all = test::gatherOnMaster(mine);
    if (!comm.master())
    {
        return;
    }
    std::map<std::array<long long, 7>, long long> numberOf;
    label nDiffer = 0;
    for (const auto& rank : all)
    {
        for (const numberRecord& r : rank)
        {
            const auto [it, inserted] = numberOf.emplace(r.key, r.number);
            if (!inserted && it->second != r.number && ++nDiffer <= 5)
            {
                ADD_FAILURE() << "point (" << r.key[0] << " ... level " << r.key[6]
                    << ") numbered " << it->second << " and " << r.number;
            }
        }
    }
    EXPECT_EQ(nDiffer, 0);
    std::set<long long> distinct;
    for (const auto& [key, number] : numberOf)
    {
        EXPECT_TRUE(number >= 0 && number < numbering.nGlobal()) << "number " << number;
        distinct.insert(number);
    }
    EXPECT_EQ(distinct.size(), numberOf.size()) << "two points share a number";
    EXPECT_EQ(label(numberOf.size()), numbering.nGlobal());
}

} // End anonymous namespace


TEST(parallelLayers, layerPointsOfRealLayersGetOneNumberOnEveryRankThatUsesThem)
{
    // The levels below the top that this rank's prisms and side quads use
    const Communicator& comm = test::world();
    const layeredCase& c = theCase();
    mpiLayerExchange exchange(comm, c.coarse, c.cellPart, levels);
    const wallLayers layers = grow(c.part, walls(3, 0.001, 1.2), exchange);
    std::set<std::pair<label, int>> used;
    auto use = [&](const layerPointRef& r)
    {
        if (r.level < layers.nLayers[r.point])
        {
            used.insert({r.point, r.level});
        }
    };
    for (const auto& prism : layers.prisms)
    {
        std::for_each(prism.begin(), prism.end(), use);
    }
    for (const layerSideFace& f : layers.sideFaces)
    {
        std::for_each(f.points.begin(), f.points.end(), use);
    }
    EXPECT_GT(comm.sum(std::int64_t(used.size())), 0);
    expectLayerNumbers(c, {used.begin(), used.end()});
}


TEST(parallelLayers, layerPointsUsedByOnlySomeHoldersNotTheOwner)
{
    // Every surface point with levels 0..2, used by: level 0 every holder;
    // level 1 every holder but the point's owner (all if it has one);
    // level 2 its highest holder alone. Listed in reverse, as a caller may
    const Communicator& comm = test::world();
    const int me = comm.rank();
    const layeredCase& c = theCase();
    std::vector<std::pair<label, int>> layerPoints;
    label nWithoutOwner = 0;
    for (label p = label(c.part.points.size()) - 1; p >= 0; --p)
    {
        const std::vector<int> holders = holdersOf(c, c.part.ids[p]);
        const bool shared = holders.size() > 1;
        layerPoints.push_back({p, 0});
        if (!shared || ownerRank(c.part.ids[p], holders) != me)
        {
            layerPoints.push_back({p, 1});
            nWithoutOwner += shared;
        }
        if (holders.back() == me)
        {
            layerPoints.push_back({p, 2});
        }
    }
    if (comm.size() > 1)
    {
        EXPECT_GT(comm.sum(std::int64_t(nWithoutOwner)), 0);
    }
    expectLayerNumbers(c, layerPoints);
}


TEST(parallelLayers, aRankWithoutLayerPointsTakesPartInTheNumbering)
{
    // Only the last rank has layer points: the others make the same
    // collective calls with none
    const Communicator& comm = test::world();
    const layeredCase& c = theCase();
    std::vector<std::pair<label, int>> layerPoints;
    if (comm.rank() == comm.size() - 1)
    {
        for (label p = 0; p < label(c.part.points.size()); p += 3)
        {
            layerPoints.push_back({p, 0});
        }
    }
    expectLayerNumbers(c, layerPoints);
}


// * * * * * * * * * * * * * Where stacks thinned * * * * * * * * * * * * * //

namespace
{

//- A rank's thinned points for writeThinnedLayers: n of its own (coarse
//  vertex ids from 1000*(rank + 1)) and one every rank holds (id 1), each
//  with its reason: point i's is 1 + i % 4, the shared one's 4.
void thinnedPointsOfRank(int rank, int n, wallLayers& layers, FineSurface& surface)
{
    surface.points.clear();
    surface.ids.clear();
    layers.thinnedBy.clear();
    for (int i = 0; i < n; ++i)
    {
        surface.points.push_back({double(rank), double(i), 0});
        surface.ids.push_back(barycentricId(1000*(rank + 1) + i, 1, 0, 0, 0, 0));
        layers.thinnedBy.push_back(layerThinning(1 + i % 4));
    }
    surface.points.push_back({-1, -1, -1});
    surface.ids.push_back(barycentricId(1, 1, 0, 0, 0, 0));
    layers.thinnedBy.push_back(layerThinning::partitionInterface);
    // An unthinned point is not written
    surface.points.push_back({-2, -2, -2});
    surface.ids.push_back(barycentricId(2, 1, 0, 0, 0, 0));
    layers.thinnedBy.push_back(layerThinning::none);
}

//- The thinnedBy of every point of a thinnedLayers.vtk, by its position
std::map<std::array<double, 3>, int> readThinnedLayers(const std::string& file)
{
    std::ifstream is(file);
    std::string word;
    std::size_t n = 0;
    while (is >> word && word != "POINTS") {}
    is >> n >> word;
    std::vector<std::array<double, 3>> x(n);
    for (auto& p : x) is >> p[0] >> p[1] >> p[2];
    while (is >> word && word != "default") {}
    std::map<std::array<double, 3>, int> why;
    for (const auto& p : x) is >> why[p];
    EXPECT_TRUE(bool(is)) << file;
    return why;
}

//- A scratch directory of the master's, known to every rank
std::string sharedScratchDirectory(const Communicator& comm)
{
    std::vector<char> dir(256, 0);
    if (comm.master())
    {
        char name[] = "/tmp/pmshThinnedLayersXXXXXX";
        const char* made = mkdtemp(name);
        EXPECT_NE(made, nullptr);
        std::strncpy(dir.data(), made ? made : "/tmp", dir.size() - 1);
    }
    comm.broadcast(dir);
    return dir.data();
}

} // End anonymous namespace


TEST(parallelLayers, thinnedPointsOfEveryRankAreWrittenOnceWithTheirReasonAndAStaleFileGoes)
{
    const Communicator& comm = test::world();
    const std::string dir = sharedScratchDirectory(comm);
    const std::string file = dir + "/postProcessing/pmshFoam/thinnedLayers.vtk";
    wallLayers layers;
    FineSurface surface;
    const int n = 10;
    thinnedPointsOfRank(comm.rank(), n, layers, surface);

    const label written = writeThinnedLayers(comm, layers, surface, file);
    if (comm.master())
    {
        EXPECT_EQ(written, n*comm.size() + 1);
        const auto why = readThinnedLayers(file);
        EXPECT_EQ(label(why.size()), written);
        for (int r = 0; r < comm.size(); ++r)
        {
            for (int i = 0; i < n; ++i)
            {
                const std::array<double, 3> x{double(r), double(i), 0};
                ASSERT_TRUE(why.count(x)) << "rank " << r << " point " << i;
                EXPECT_EQ(why.at(x), 1 + i % 4);
            }
        }
        EXPECT_EQ(why.at({-1, -1, -1}), 4);
        EXPECT_FALSE(why.count({-2, -2, -2}));
    }
    else
    {
        EXPECT_EQ(written, 0);
    }

    // Above the cap, every k-th of each rank's: at most the cap in all
    const label sampled = writeThinnedLayers(comm, layers, surface, file, 4*comm.size());
    if (comm.master())
    {
        EXPECT_GT(sampled, 0);
        EXPECT_LE(sampled, 4*comm.size());
        EXPECT_EQ(label(readThinnedLayers(file).size()), sampled);
    }

    // Nothing thinned: the file of the run before goes
    std::fill(layers.thinnedBy.begin(), layers.thinnedBy.end(), layerThinning::none);
    EXPECT_EQ(writeThinnedLayers(comm, layers, surface, file), 0);
    comm.masterWorksOthersSleep([&]
    {
        EXPECT_FALSE(std::filesystem::exists(file));
        std::filesystem::remove_all(dir);
    });
}
