#include "fineCellBalance.H"
#include "failTogether.H"
#include "meshPatch.H"
#include "pmshError.H"
#include "mixedFaceMatching.H"
#include "tetFaceMatching.H"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <numeric>
#include <unordered_map>

namespace
{

using namespace pmsh;

// Rounds of moves at most: one is enough unless a rank must pass on more
// than it holds (the 8-rank chains of the MPI tests take 2)
constexpr int maxRounds = 10;

// Across a face after the move: its patch (>= 0), the interface with a
// rank (interfaceRegion), or another cell of the same rank
constexpr label internalFace = std::numeric_limits<label>::max();

// A cell of N points and F faces on its way to another rank, with
// everything it needs there. Tets and prisms travel apart, so that a
// mesh without layers sends what it always sent.
template<int N, int F>
struct movedCell
{
    std::array<label, N> globalIds;
    std::array<point3, N> points;
    std::array<barycentricId, N> pointIds;
    std::array<label, F> across;        //!< per outward face
    label zone;
};
using movedTet = movedCell<4, 4>;
using movedPrism = movedCell<6, 5>;

// A processor face, triangle or quad, by its global points
// (processorKeyOf)
using processorKey = std::array<label, 4>;

// Where the cell behind a processor face goes, told to the rank across
struct faceDestination
{
    processorKey key;
    int dest;
};

// Neighbouring ranks: those behind this rank's processor faces
std::vector<int> neighbourRanks(const rankTets& mesh)
{
    std::vector<int> ranks;
    for (const auto* regions : {&mesh.region, &mesh.quadRegion})
    {
        for (label r : *regions)
        {
            if (isInterfaceRegion(r))
            {
                ranks.push_back(int(interfaceNeighbour(r)));
            }
        }
    }
    std::sort(ranks.begin(), ranks.end());
    ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());
    return ranks;
}

// How many cells this rank sends to each neighbour: first-order
// diffusion, each rank exchanging its load and degree with its neighbours
// every iteration, flows accumulated (Cybenko 1989)
std::map<int, double> diffusionFlows
(
    const Communicator& comm,
    const std::vector<int>& neighbours,
    double load,
    double mean,
    double tolerance
)
{
    std::map<int, double> flow;
    for (int s : neighbours) flow[s] = 0;
    const double degree = double(neighbours.size());
    for (int iter = 0; iter < 1000; ++iter)
    {
        if (comm.max(std::abs(load - mean)) <= 0.25*tolerance*mean)
        {
            break;
        }
        std::vector<std::vector<double>> send(comm.size());
        for (int s : neighbours) send[s] = {load, degree};
        const std::vector<std::vector<double>> received = comm.exchange(send);
        double change = 0;
        for (int s : neighbours)
        {
            if (received[s].size() != 2) continue;
            const double alpha = 1.0/(std::max(degree, received[s][1]) + 1);
            const double f = alpha*(load - received[s][0]);
            flow[s] += f;
            change -= f;
        }
        load += change;
    }
    return flow;
}

// The cells' faces and what lies across each: the faces of tets alone
// are matched by the tet matcher, as they were before layers could move
// (the same ids when there are no prisms: tet faces, then triangles)
class cellFaces
{
public:

    const mixedFaces ids;
    const std::vector<faceId> across;

private:

    const rankTets& mesh_;

    static std::vector<faceId> matched(const rankTets& mesh, const mixedFaces& ids)
    {
        if (mesh.prisms.empty() && mesh.quads.empty())
        {
            return fittingTetFaces
            (
                mesh.points.size(), mesh.tets, mesh.triangles,
                "This rank's fine mesh and its surface do not fit together",
                "balanceFineCells"
            ).across;
        }
        return matchMixedFaces(mesh.points.size(), ids);
    }

public:

    explicit cellFaces(const rankTets& mesh)
    :
        ids(mesh.tets, mesh.prisms, mesh.triangles, mesh.quads, "balanceFineCells"),
        across(matched(mesh, ids)),
        mesh_(mesh)
    {}

    label nCells() const { return label(mesh_.tets.size() + mesh_.prisms.size()); }

    //- The region of boundary face id (a triangle or a quad)
    label regionOf(faceId id) const
    {
        return id < ids.quadsStart
            ? mesh_.region[id - ids.nCellFaces]
            : mesh_.quadRegion[id - ids.quadsStart];
    }

    //- The rank behind cell face id (a boundary face on the interface
    //  with it), or -1
    int rankAcross(faceId id) const
    {
        const faceId other = across[id];
        if (other < ids.nCellFaces || other == noFace) return -1;
        const label r = regionOf(other);
        return isInterfaceRegion(r) ? int(interfaceNeighbour(r)) : -1;
    }

    //- A face's key by the global ids of its points
    processorKey keyOf(faceId id) const
    {
        quadVerts f;
        const int n = ids.pointsOf(id, f);
        return processorKeyOf(f, n, mesh_.globalIds);
    }
};


// The cells that move together: a prism with the cells across its
// triangles (the prisms below and above it, the tet on its stack), so a
// stack of layers and the tet on it never straddle two ranks; every other
// tet alone. As lists: unit u's cells are cells[start[u] .. start[u+1]).
struct moveUnits
{
    std::vector<label> unitOf;      //!< per cell
    std::vector<label> start;
    std::vector<label> cells;

    explicit moveUnits(const cellFaces& faces)
    {
        const label nCells = faces.nCells();
        const label nTets = faces.ids.nTets();
        std::vector<label> parent(nCells);
        std::iota(parent.begin(), parent.end(), 0);
        const auto root = [&](label c)
        {
            while (parent[c] != c) c = parent[c] = parent[parent[c]];
            return c;
        };
        for (label c = nTets; c < nCells; ++c)
        {
            for (int f = 0; f < 2; ++f)     // prismFace: 0 and 1 the triangles
            {
                const faceId other = faces.across[faces.ids.firstFace(c) + f];
                if (other < faces.ids.nCellFaces)
                {
                    parent[root(faces.ids.cellOf(other))] = root(c);
                }
            }
        }
        unitOf.resize(nCells);
        start.assign(1, 0);
        std::vector<label> unitOfRoot(nCells, -1);
        std::vector<label> size;
        for (label c = 0; c < nCells; ++c)
        {
            label& u = unitOfRoot[root(c)];
            if (u < 0)
            {
                u = label(size.size());
                size.push_back(0);
            }
            unitOf[c] = u;
            ++size[u];
        }
        for (label n : size) start.push_back(start.back() + n);
        cells.resize(nCells);
        std::vector<label> next(start.begin(), start.end() - 1);
        for (label c = 0; c < nCells; ++c)
        {
            cells[next[unitOf[c]]++] = c;
        }
    }
};


// Destinations: for each neighbour that gets cells, the units nearest
// their interface, layer by layer (breadth first from the interface)
std::vector<int> cellDestinations
(
    const cellFaces& faces,
    const moveUnits& units,
    const std::map<int, double>& flow,
    int me
)
{
    const mixedFaces& ids = faces.ids;
    const label nUnits = label(units.start.size()) - 1;
    std::vector<int> dest(faces.nCells(), me);
    for (const auto& [s, f] : flow)
    {
        label wanted = label(std::floor(f + 0.5));
        if (wanted <= 0) continue;
        std::deque<label> front;
        std::vector<bool> queued(nUnits, false);
        const auto enqueue = [&](label u)
        {
            if (!queued[u])
            {
                queued[u] = true;
                front.push_back(u);
            }
        };
        for (faceId id = 0; id < ids.nCellFaces; ++id)
        {
            if (faces.rankAcross(id) == s)
            {
                enqueue(units.unitOf[ids.cellOf(id)]);
            }
        }
        while (!front.empty() && wanted > 0)
        {
            const label u = front.front();
            front.pop_front();
            if (dest[units.cells[units.start[u]]] != me) continue;
            for (label i = units.start[u]; i < units.start[u + 1]; ++i)
            {
                const label c = units.cells[i];
                dest[c] = s;
                --wanted;
                for (int fi = 0; fi < ids.nFacesOf(c); ++fi)
                {
                    const faceId other = faces.across[ids.firstFace(c) + fi];
                    if (other < ids.nCellFaces)
                    {
                        enqueue(units.unitOf[ids.cellOf(other)]);
                    }
                }
            }
        }
    }
    return dest;
}


// Where the cells behind this rank's processor faces go, from their
// ranks, by the faces' global keys
std::map<processorKey, int> destinationsAcross
(
    const Communicator& comm,
    const cellFaces& faces,
    const std::vector<int>& dest
)
{
    std::vector<std::vector<faceDestination>> tell(comm.size());
    for (faceId id = 0; id < faces.ids.nCellFaces; ++id)
    {
        const int s = faces.rankAcross(id);
        if (s >= 0)
        {
            tell[s].push_back({faces.keyOf(id), dest[faces.ids.cellOf(id)]});
        }
    }
    std::map<processorKey, int> destAcross;
    for (const auto& fromRank : comm.exchange(tell))
    {
        for (const faceDestination& fd : fromRank)
        {
            destAcross[fd.key] = fd.dest;
        }
    }
    return destAcross;
}


// Every cell's faces as they will be at its destination
class acrossAfterMove
{
    const cellFaces& faces_;
    const std::vector<int>& dest_;
    const std::map<processorKey, int>& destAcross_;

public:

    acrossAfterMove
    (
        const cellFaces& faces,
        const std::vector<int>& dest,
        const std::map<processorKey, int>& destAcross
    )
    :
        faces_(faces),
        dest_(dest),
        destAcross_(destAcross)
    {}

    //- What lies across face fi of cell c once it is at its destination
    label operator()(label c, int fi) const
    {
        const mixedFaces& ids = faces_.ids;
        const faceId other = faces_.across[ids.firstFace(c) + fi];
        int d;
        if (other < ids.nCellFaces)
        {
            d = dest_[ids.cellOf(other)];
        }
        else
        {
            const label r = faces_.regionOf(other);
            if (!isInterfaceRegion(r))
            {
                return r;   // a physical patch
            }
            const auto it = destAcross_.find(faces_.keyOf(other));
            if (it == destAcross_.end())
            {
                throw FatalError
                (
                    msg() << "A processor face of cell " << c << " toward rank "
                        << faces_.rankAcross(other) << " has no match there:"
                        " the ranks' meshes disagree before the balance (a bug;"
                        " the decomposition method in system/decomposeParDict"
                        " may avoid it)",
                    "pmsh::balanceFineCells"
                );
            }
            d = it->second;
        }
        return d == dest_[c] ? internalFace : interfaceRegion(d);
    }
};


// The cells leaving this rank, packed per destination, tets and prisms
// apart; the staying cells and what will lie across their faces
struct packedMove
{
    std::vector<std::vector<movedTet>> tets;
    std::vector<std::vector<movedPrism>> prisms;
    std::vector<label> staying;
    std::vector<std::array<label, 5>> stayingAcross;
};

template<int N, int F>
movedCell<N, F> packedCell
(
    const rankTets& mesh,
    const std::array<label, N>& verts,
    label c,
    label zone,
    const acrossAfterMove& acrossOf
)
{
    movedCell<N, F> m;
    for (int k = 0; k < N; ++k)
    {
        const label p = verts[k];
        m.globalIds[k] = mesh.globalIds[p];
        m.points[k] = mesh.points[p];
        m.pointIds[k] = mesh.pointIds.empty() ? barycentricId() : mesh.pointIds[p];
    }
    for (int k = 0; k < F; ++k)
    {
        m.across[k] = acrossOf(c, k);
    }
    m.zone = zone;
    return m;
}

packedMove packMovedCells
(
    const rankTets& mesh,
    const std::vector<int>& dest,
    const acrossAfterMove& acrossOf,
    int me,
    int nRanks
)
{
    packedMove move;
    move.tets.resize(nRanks);
    move.prisms.resize(nRanks);
    const label nTets = label(mesh.tets.size());
    for (label c = 0; c < label(dest.size()); ++c)
    {
        if (dest[c] == me)
        {
            move.staying.push_back(c);
        }
        else if (c < nTets)
        {
            const label zone = mesh.tetZone.empty() ? 0 : mesh.tetZone[c];
            move.tets[dest[c]].push_back
            (
                packedCell<4, 4>(mesh, mesh.tets[c], c, zone, acrossOf)
            );
        }
        else
        {
            const label j = c - nTets;
            const label zone = mesh.prismZone.empty() ? 0 : mesh.prismZone[j];
            move.prisms[dest[c]].push_back
            (
                packedCell<6, 5>(mesh, mesh.prisms[j], c, zone, acrossOf)
            );
        }
    }
    move.stayingAcross.resize(move.staying.size());
    for (std::size_t i = 0; i < move.staying.size(); ++i)
    {
        const label c = move.staying[i];
        for (int k = 0; k < (c < nTets ? 4 : 5); ++k)
        {
            move.stayingAcross[i][k] = acrossOf(c, k);
        }
    }
    return move;
}


// The new mesh of a rank, cell by cell: points each once, by global
// number, boundary faces where something other than a local cell lies
// across
class rankCellsBuilder
{
    const bool zoned_;
    std::unordered_map<label, label> pointOf_;

    void addFace(const quadVerts& f, int n, label across)
    {
        if (across == internalFace) return;
        if (n == 3)
        {
            out.triangles.push_back({f[0], f[1], f[2]});
            out.region.push_back(across);
        }
        else
        {
            out.quads.push_back(f);
            out.quadRegion.push_back(across);
        }
    }

public:

    rankTets out;

    explicit rankCellsBuilder(bool zoned)
    :
        zoned_(zoned)
    {}

    label addPoint(label g, const point3& x, const barycentricId& id)
    {
        const auto inserted = pointOf_.emplace(g, label(out.points.size()));
        if (inserted.second)
        {
            out.points.push_back(x);
            out.globalIds.push_back(g);
            out.pointIds.push_back(id);
        }
        return inserted.first->second;
    }

    void addTet(const tetVerts& t, const label* across, label zone)
    {
        out.tets.push_back(t);
        if (zoned_) out.tetZone.push_back(zone);
        const auto faces = outwardTetFaces(t);
        for (int k = 0; k < 4; ++k)
        {
            addFace({faces[k][0], faces[k][1], faces[k][2], -1}, 3, across[k]);
        }
    }

    void addPrism(const prismVerts& p, const label* across, label zone)
    {
        out.prisms.push_back(p);
        if (zoned_) out.prismZone.push_back(zone);
        for (int k = 0; k < 5; ++k)
        {
            quadVerts f;
            const int n = prismFace(p, k, f);
            addFace(f, n, across[k]);
        }
    }

    //- A cell that came from another rank
    template<int N, int F>
    void addMoved(const movedCell<N, F>& m)
    {
        std::array<label, N> c;
        for (int k = 0; k < N; ++k)
        {
            c[k] = addPoint(m.globalIds[k], m.points[k], m.pointIds[k]);
        }
        if constexpr (N == 4)
        {
            addTet(c, m.across.data(), m.zone);
        }
        else
        {
            addPrism(c, m.across.data(), m.zone);
        }
    }
};


// The new mesh: the staying cells' points in their order, then the points
// that came with others. mesh is freed before the received cells are
// added (the peak memory of the move); returns the number received.
std::int64_t assembleMovedMesh
(
    rankTets& mesh,
    bool zoned,
    const packedMove& move,
    std::vector<std::vector<movedTet>>& receivedTets,
    std::vector<std::vector<movedPrism>>& receivedPrisms
)
{
    rankCellsBuilder builder(zoned);
    const label nTets = label(mesh.tets.size());
    const auto localPoint = [&](label p)
    {
        return builder.addPoint
        (
            mesh.globalIds[p], mesh.points[p],
            mesh.pointIds.empty() ? barycentricId() : mesh.pointIds[p]
        );
    };
    for (std::size_t i = 0; i < move.staying.size(); ++i)
    {
        const label c = move.staying[i];
        if (c < nTets)
        {
            tetVerts t;
            for (int k = 0; k < 4; ++k) t[k] = localPoint(mesh.tets[c][k]);
            builder.addTet
            (
                t, move.stayingAcross[i].data(),
                mesh.tetZone.empty() ? 0 : mesh.tetZone[c]
            );
        }
        else
        {
            prismVerts p;
            for (int k = 0; k < 6; ++k) p[k] = localPoint(mesh.prisms[c - nTets][k]);
            builder.addPrism
            (
                p, move.stayingAcross[i].data(),
                mesh.prismZone.empty() ? 0 : mesh.prismZone[c - nTets]
            );
        }
    }
    mesh = rankTets();
    std::int64_t nReceived = 0;
    for (auto& fromRank : receivedTets)
    {
        for (const movedTet& m : fromRank) builder.addMoved(m);
        nReceived += std::int64_t(fromRank.size());
        freeStorage(fromRank);
    }
    for (auto& fromRank : receivedPrisms)
    {
        for (const movedPrism& m : fromRank) builder.addMoved(m);
        nReceived += std::int64_t(fromRank.size());
        freeStorage(fromRank);
    }
    mesh = std::move(builder.out);
    return nReceived;
}


// One round of moves towards the flows of the current loads; returns the
// cells this rank received
std::int64_t balanceRound
(
    const pmsh::Communicator& comm,
    pmsh::rankTets& mesh,
    double nCells,
    double mean,
    double tolerance
)
{
    const int me = comm.rank();
    const std::vector<int> neighbours = neighbourRanks(mesh);
    const std::map<int, double> flow =
        diffusionFlows(comm, neighbours, nCells, mean, tolerance);

    // What lies across each cell face now, and the cells that move together
    const cellFaces faces(mesh);
    const moveUnits units(faces);

    const std::vector<int> dest = cellDestinations(faces, units, flow, me);
    const std::map<processorKey, int> destAcross =
        destinationsAcross(comm, faces, dest);

    // Zoned when any rank is: a rank may have received no zoned cell yet
    const bool zoned =
        comm.sum(std::int64_t(!mesh.tetZone.empty() || !mesh.prismZone.empty())) > 0;
    // Local work between collectives: a rank that threw here would leave
    // the others waiting in the exchange
    packedMove move;
    failTogether(comm, [&]
    {
        move = packMovedCells
        (
            mesh, dest, acrossAfterMove(faces, dest, destAcross), me, comm.size()
        );
    });
    std::vector<std::vector<movedTet>> receivedTets = comm.exchange(move.tets);
    freeStorage(move.tets);
    std::vector<std::vector<movedPrism>> receivedPrisms = comm.exchange(move.prisms);
    freeStorage(move.prisms);

    return assembleMovedMesh(mesh, zoned, move, receivedTets, receivedPrisms);
}

} // End anonymous namespace


pmsh::fineBalanceStats pmsh::balanceFineCells
(
    const Communicator& comm,
    rankTets& mesh,
    double tolerance
)
{
    fineBalanceStats stats;
    if (!comm.parallel())
    {
        return stats;
    }
    const auto nCells = [&] { return double(mesh.tets.size() + mesh.prisms.size()); };
    const auto largestOverMean = [&](double& mean)
    {
        const std::vector<double> loads = comm.allGather(nCells());
        double total = 0;
        for (double l : loads) total += l;
        mean = total/comm.size();
        return *std::max_element(loads.begin(), loads.end())/mean;
    };
    double mean = 0;
    stats.before = largestOverMean(mean);
    stats.after = stats.before;

    // A rank sends only the cells it holds at the start of a round: where
    // the flow through a rank is more than it holds (a chain of ranks, the
    // surplus at one end), the next round passes on what it received
    for (int round = 0; round < maxRounds && stats.after > 1 + tolerance; ++round)
    {
        const std::int64_t moved =
            comm.sum(balanceRound(comm, mesh, nCells(), mean, tolerance));
        stats.moved += moved;
        stats.after = largestOverMean(mean);
        if (moved == 0)
        {
            break;
        }
    }
    return stats;
}


// ************************************************************************* //
