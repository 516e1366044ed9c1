// Stage 6 on a layered mesh across MPI ranks (run under mpiexec -np 1..8):
// the cube's tets dealt out evenly in slabs of x, with six layers of
// prisms on its xMin and yMin sides, so the rank holding xMin has the
// surplus that prism layers give a rank holding much wall. Afterwards the
// ranks are within 5 % of the mean, every tet and prism is held once, every
// stack is on one rank with the tet on its top, each rank's cells and
// faces fit, the processor triangles and quads of two ranks are the same
// faces, and the physical boundary is all there. Serially nothing moves.

#include "mpiTestMain.H"
#include "coarseMesh.H"
#include "cubeMesh.H"
#include "fineCellBalance.H"
#include "meshPatch.H"
#include "mixedFaceMatching.H"

#include <mpi.h>

#include <algorithm>
#include <map>
#include <set>

using namespace pmsh;

namespace
{

constexpr int nLayers = 6;
constexpr double layerThickness = 0.02;
const std::vector<label> layeredPatches = {0, 2};    // xMin, yMin
constexpr label layerSidesRegion = 6;                // the stacks' open sides

using sortedKey = std::array<label, 6>;
using processorKey4 = std::array<label, 4>;     // processorKeyOf's

template<std::size_t N>
sortedKey keyOf(const std::array<label, N>& verts, const std::vector<label>& globalIds)
{
    sortedKey k;
    k.fill(-1);
    for (std::size_t i = 0; i < N; ++i) k[i] = globalIds[verts[i]];
    std::sort(k.begin(), k.begin() + N);
    return k;
}


// The layered cube as a whole: cube points, then per layered patch and
// level 1..nLayers a copy of every cube point moved out of the patch
struct layeredCube
{
    CoarseMesh cube;
    std::vector<faceNeighbours> neighbours;

    struct stack
    {
        label patch;
        triVerts wall;          //!< the cube's face, outward
        label topTet;           //!< the cube's tet on it
        std::array<label, 3> sideNeighbour;     //!< stack across each edge, or -1
    };
    std::vector<stack> stacks;

    explicit layeredCube(int n)
    :
        cube(test::cubeMesh(n)),
        neighbours(coarseFaceNeighbours(cube))
    {
        for (label t = 0; t < cube.nCells(); ++t)
        {
            for (int f = 0; f < 4; ++f)
            {
                const label nbr = neighbours[t][f];
                if (!isBoundaryNeighbour(nbr)) continue;
                const coarseBoundaryFace& b = cube.boundary[boundaryFaceOf(nbr)];
                if (std::count(layeredPatches.begin(), layeredPatches.end(), b.patch))
                {
                    stacks.push_back({b.patch, outwardTetFaces(cube.tets[t])[f], t, {-1, -1, -1}});
                }
            }
        }
        // Neighbouring stacks of one patch share an edge of their walls
        std::map<std::array<label, 3>, label> edgeOwner;
        for (label s = 0; s < label(stacks.size()); ++s)
        {
            for (int e = 0; e < 3; ++e)
            {
                const std::array<label, 3> key = edgeKey(s, e);
                const auto it = edgeOwner.find(key);
                if (it == edgeOwner.end())
                {
                    edgeOwner[key] = s;
                }
                else
                {
                    stacks[s].sideNeighbour[e] = it->second;
                    stacks[it->second].sideNeighbour[edgeIndex(it->second, key)] = s;
                }
            }
        }
    }

    // Edge e of stack s's prism base (a, c, b): the edges of the prism's
    // quads 4, 3 and 2 in prismFace order (c0-c1, c1-c2, c0-c2)
    std::array<label, 2> edge(label s, int e) const
    {
        const triVerts& w = stacks[s].wall;
        const std::array<label, 3> base{w[0], w[2], w[1]};
        static const int ends[3][2] = {{0, 1}, {1, 2}, {0, 2}};
        return {base[ends[e][0]], base[ends[e][1]]};
    }

    std::array<label, 3> edgeKey(label s, int e) const
    {
        const auto ab = edge(s, e);
        return {stacks[s].patch, std::min(ab[0], ab[1]), std::max(ab[0], ab[1])};
    }

    int edgeIndex(label s, const std::array<label, 3>& key) const
    {
        for (int e = 0; e < 3; ++e)
        {
            if (edgeKey(s, e) == key) return e;
        }
        return -1;
    }

    label nCubePoints() const { return cube.nPoints(); }

    //- The global id of cube point p lifted to level (0: p itself)
    label liftedId(label patch, int level, label p) const
    {
        if (level == 0) return p;
        const label k = label(std::find(layeredPatches.begin(), layeredPatches.end(), patch) - layeredPatches.begin());
        return nCubePoints()*(1 + k*nLayers + level - 1) + p;
    }

    point3 liftedPoint(label patch, int level, label p) const
    {
        point3 x = cube.points[p];
        x[patch/2] -= level*layerThickness;     // out of the xMin or yMin side
        return x;
    }

    //- Prism k (0 at the cube) of stack s, by global ids, OpenFOAM's order:
    //  the base (c0 c1 c2) at level k + 1, the top at level k
    std::array<label, 6> prism(label s, int k) const
    {
        const triVerts& w = stacks[s].wall;
        const std::array<label, 3> base{w[0], w[2], w[1]};
        std::array<label, 6> c;
        for (int i = 0; i < 3; ++i)
        {
            c[i] = liftedId(stacks[s].patch, k + 1, base[i]);
            c[3 + i] = liftedId(stacks[s].patch, k, base[i]);
        }
        return c;
    }

    point3 pointOf(label g) const
    {
        if (g < nCubePoints()) return cube.points[g];
        const label k = (g/nCubePoints() - 1)/nLayers;
        const int level = int((g/nCubePoints() - 1) % nLayers) + 1;
        return liftedPoint(layeredPatches[k], level, g % nCubePoints());
    }
};


// Tets dealt out in P slabs of x; each stack with the tet on its top.
// This rank's share as after stage 5: global point numbers, its boundary
// (physical triangles and quads, and those on processor faces)
rankTets evenTetsLayeredShare(const layeredCube& m, std::vector<int>& tetOwner)
{
    const Communicator& comm = test::world();
    const int P = comm.size();
    const CoarseMesh& cube = m.cube;
    tetOwner.assign(cube.nCells(), 0);
    for (label t = 0; t < cube.nCells(); ++t)
    {
        double x = 0;
        for (label p : cube.tets[t]) x += 0.25*cube.points[p][0];
        tetOwner[t] = std::min(P - 1, int(x*P));
    }
    const auto stackOwner = [&](label s) { return tetOwner[m.stacks[s].topTet]; };
    const auto regionTo = [&](int owner, label physical)
    {
        return owner == comm.rank() ? physical : interfaceRegion(owner);
    };

    rankTets mine;
    std::map<label, label> local;
    auto pointOf = [&](label g)
    {
        const auto it = local.emplace(g, label(mine.points.size()));
        if (it.second)
        {
            mine.points.push_back(m.pointOf(g));
            mine.globalIds.push_back(g);
        }
        return it.first->second;
    };

    for (label t = 0; t < cube.nCells(); ++t)
    {
        if (tetOwner[t] != comm.rank()) continue;
        const tetVerts& c = cube.tets[t];
        mine.tets.push_back({pointOf(c[0]), pointOf(c[1]), pointOf(c[2]), pointOf(c[3])});
        const auto faces = outwardTetFaces(mine.tets.back());
        for (int f = 0; f < 4; ++f)
        {
            const label nbr = m.neighbours[t][f];
            if (isBoundaryNeighbour(nbr))
            {
                const label patch = cube.boundary[boundaryFaceOf(nbr)].patch;
                if (std::count(layeredPatches.begin(), layeredPatches.end(), patch))
                {
                    continue;       // a stack's top, on this rank
                }
                mine.triangles.push_back(faces[f]);
                mine.region.push_back(patch);
            }
            else if (tetOwner[nbr] != comm.rank())
            {
                mine.triangles.push_back(faces[f]);
                mine.region.push_back(interfaceRegion(tetOwner[nbr]));
            }
        }
    }

    for (label s = 0; s < label(m.stacks.size()); ++s)
    {
        if (stackOwner(s) != comm.rank()) continue;
        for (int k = 0; k < nLayers; ++k)
        {
            const std::array<label, 6> g = m.prism(s, k);
            prismVerts c;
            for (int i = 0; i < 6; ++i) c[i] = pointOf(g[i]);
            mine.prisms.push_back(c);
            quadVerts f;
            if (k == nLayers - 1)
            {
                prismFace(c, 0, f);
                mine.triangles.push_back({f[0], f[1], f[2]});
                mine.region.push_back(m.stacks[s].patch);
            }
            // Quads 4, 3, 2 on edges 0, 1, 2 (layeredCube::edge)
            for (int e = 0; e < 3; ++e)
            {
                const label across = m.stacks[s].sideNeighbour[e];
                if (across >= 0 && stackOwner(across) == comm.rank()) continue;
                prismFace(c, 4 - e, f);
                mine.quads.push_back(f);
                mine.quadRegion.push_back
                (
                    across < 0 ? layerSidesRegion : regionTo(stackOwner(across), 0)
                );
            }
        }
    }
    return mine;
}

} // End anonymous namespace


TEST(parallelFineBalance, layeredStacksMoveWholeWithTheirTopTetRanksEndWithinFivePercent)
{
    const Communicator& comm = test::world();
    const layeredCube m(8);
    std::vector<int> tetOwner;
    rankTets mine = evenTetsLayeredShare(m, tetOwner);
    const double nCells = double(m.cube.nCells() + nLayers*m.stacks.size());

    const fineBalanceStats stats = balanceFineCells(comm, mine, 0.01);
    if (comm.size() > 1)
    {
        // The prisms are the surplus of the xMin slab's rank
        EXPECT_GT(stats.before, 1.15);
        EXPECT_GT(stats.moved, 0);
    }
    EXPECT_LE(stats.after, 1.05);
    const std::vector<double> counts =
        comm.allGather(double(mine.tets.size() + mine.prisms.size()));
    double total = 0;
    for (double c : counts) total += c;
    EXPECT_EQ(total, nCells);
    EXPECT_NEAR(*std::max_element(counts.begin(), counts.end())/(total/comm.size()), stats.after, 1e-12);

    // Every tet and prism on exactly one rank, by its global points; the
    // cells of every stack and its top tet on one rank
    std::map<sortedKey, label> cellIndex;
    std::vector<label> stackOfCell;
    std::vector<label> identity(m.cube.nPoints());
    for (label p = 0; p < label(identity.size()); ++p) identity[p] = p;
    for (label t = 0; t < m.cube.nCells(); ++t)
    {
        cellIndex[keyOf(m.cube.tets[t], identity)] = t;
        stackOfCell.push_back(-1);
    }
    for (label s = 0; s < label(m.stacks.size()); ++s)
    {
        stackOfCell[m.stacks[s].topTet] = s;
        for (int k = 0; k < nLayers; ++k)
        {
            std::array<label, 6> g = m.prism(s, k);
            std::sort(g.begin(), g.end());
            cellIndex[g] = label(stackOfCell.size());
            stackOfCell.push_back(s);
        }
    }
    std::vector<int> held(stackOfCell.size(), 0);
    std::vector<int> stackCellsHere(m.stacks.size(), 0);
    const auto hold = [&](const sortedKey& k)
    {
        const auto it = cellIndex.find(k);
        ASSERT_NE(it, cellIndex.end()) << "a cell that is not the layered cube's";
        ++held[it->second];
        if (stackOfCell[it->second] >= 0) ++stackCellsHere[stackOfCell[it->second]];
    };
    for (const tetVerts& t : mine.tets)
    {
        hold(keyOf(t, mine.globalIds));
        EXPECT_GT(tetVolume6(mine.points[t[0]], mine.points[t[1]], mine.points[t[2]], mine.points[t[3]]), 0);
    }
    for (const prismVerts& p : mine.prisms)
    {
        hold(keyOf(p, mine.globalIds));
        // The points travelled with their coordinates: the base is the
        // top moved out of the cube by one layer
        for (int i = 0; i < 3; ++i)
        {
            EXPECT_NEAR(magSqr(mine.points[p[3 + i]] - mine.points[p[i]]), layerThickness*layerThickness, 1e-12);
        }
    }
    MPI_Allreduce(MPI_IN_PLACE, held.data(), int(held.size()), MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_EQ(std::count(held.begin(), held.end(), 1), label(held.size()));
    MPI_Allreduce(MPI_IN_PLACE, stackCellsHere.data(), int(stackCellsHere.size()), MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    EXPECT_EQ(std::count(stackCellsHere.begin(), stackCellsHere.end(), nLayers + 1), label(m.stacks.size()))
        << "a stack or its top tet was split between ranks";

    // This rank's cells and faces fit together
    EXPECT_NO_THROW
    (
        matchMixedFaces
        (
            mine.points.size(),
            mixedFaces(mine.tets, mine.prisms, mine.triangles, mine.quads, "test")
        )
    );

    // The processor faces to a rank are that rank's processor faces to
    // this one; the physical boundary is the layered cube's, once
    std::vector<std::vector<processorKey4>> send(comm.size());
    std::map<int, std::set<processorKey4>> toRank;
    double nPhysical = 0;
    const auto boundaryFace = [&](const quadVerts& f, int n, label region)
    {
        if (isInterfaceRegion(region))
        {
            const int s = int(interfaceNeighbour(region));
            EXPECT_NE(s, comm.rank());
            const processorKey4 k = processorKeyOf(f, n, mine.globalIds);
            send[s].push_back(k);
            toRank[s].insert(k);
        }
        else
        {
            ++nPhysical;
        }
    };
    for (std::size_t i = 0; i < mine.triangles.size(); ++i)
    {
        const triVerts& t = mine.triangles[i];
        boundaryFace({t[0], t[1], t[2], -1}, 3, mine.region[i]);
    }
    for (std::size_t i = 0; i < mine.quads.size(); ++i)
    {
        boundaryFace(mine.quads[i], 4, mine.quadRegion[i]);
    }
    const auto received = comm.exchange(send);
    for (int s = 0; s < comm.size(); ++s)
    {
        const std::set<processorKey4> theirs(received[s].begin(), received[s].end());
        EXPECT_EQ(theirs, toRank[s]) << "processor faces between ranks " << comm.rank()
            << " and " << s << " differ";
    }
    // The cube's unlayered sides, the walls under the stacks and the
    // stacks' open sides (an edge of a layered side on the cube's edge)
    double nSides = 0;
    for (const auto& s : m.stacks)
    {
        nSides += std::count(s.sideNeighbour.begin(), s.sideNeighbour.end(), -1);
    }
    EXPECT_EQ(comm.sum(nPhysical), double(m.cube.boundary.size()) + nLayers*nSides);
}
