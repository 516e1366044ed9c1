#include "fineCellBalance.H"
#include "meshPatch.H"
#include "pmshError.H"
#include "tetFaceMatching.H"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <unordered_map>

namespace
{

using namespace pmsh;

// Across a face after the move: its patch (>= 0), the interface with a
// rank (interfaceRegion), or another tet of the same rank
constexpr label internalFace = std::numeric_limits<label>::max();

// A tet on its way to another rank, with everything it needs there
struct movedTet
{
    std::array<label, 4> globalIds;
    std::array<point3, 4> points;
    std::array<barycentricId, 4> pointIds;
    std::array<label, 4> across;        //!< per outward face
    label zone;
};

// Where the tet behind a processor face goes, told to the rank across
struct faceDestination
{
    globalFaceKey key;
    int dest;
};

// Neighbouring ranks: those behind this rank's processor faces
std::vector<int> neighbourRanks(const rankTets& mesh)
{
    std::vector<int> ranks;
    for (label r : mesh.region)
    {
        if (isInterfaceRegion(r))
        {
            ranks.push_back(int(interfaceNeighbour(r)));
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

// Destinations: for each neighbour that gets cells, the tets nearest
// their interface, layer by layer (breadth first from the interface)
std::vector<int> tetDestinations
(
    const rankTets& mesh,
    const tetFaceMatch& match,
    const std::map<int, double>& flow,
    int me
)
{
    const label nTets = label(mesh.tets.size());
    const faceId nTetFaces = faceId(4*mesh.tets.size());
    std::vector<int> dest(nTets, me);
    for (const auto& [s, f] : flow)
    {
        label wanted = label(std::floor(f + 0.5));
        if (wanted <= 0) continue;
        std::deque<label> front;
        std::vector<bool> queued(nTets, false);
        for (faceId id = 0; id < nTetFaces; ++id)
        {
            const faceId other = match.across[id];
            if
            (
                other >= nTetFaces && other != noFace
             && mesh.region[other - nTetFaces] == interfaceRegion(s)
             && !queued[id/4]
            )
            {
                queued[id/4] = true;
                front.push_back(label(id/4));
            }
        }
        while (!front.empty() && wanted > 0)
        {
            const label t = front.front();
            front.pop_front();
            if (dest[t] != me) continue;
            dest[t] = s;
            --wanted;
            for (int fi = 0; fi < 4; ++fi)
            {
                const faceId other = match.across[4*t + fi];
                if (other < nTetFaces && !queued[other/4])
                {
                    queued[other/4] = true;
                    front.push_back(label(other/4));
                }
            }
        }
    }
    return dest;
}


// Where the tets behind this rank's processor faces go, from their ranks,
// by the faces' global keys
std::map<globalFaceKey, int> destinationsAcross
(
    const Communicator& comm,
    const rankTets& mesh,
    const tetFaceMatch& match,
    const std::vector<int>& dest
)
{
    const faceId nTetFaces = faceId(4*mesh.tets.size());
    std::vector<std::vector<faceDestination>> tell(comm.size());
    for (faceId id = 0; id < nTetFaces; ++id)
    {
        const faceId other = match.across[id];
        if (other >= nTetFaces && other != noFace && isInterfaceRegion(mesh.region[other - nTetFaces]))
        {
            const int s = int(interfaceNeighbour(mesh.region[other - nTetFaces]));
            tell[s].push_back({globalKeyOf(mesh.triangles[other - nTetFaces], mesh.globalIds), dest[id/4]});
        }
    }
    std::map<globalFaceKey, int> destAcross;
    for (const auto& fromRank : comm.exchange(tell))
    {
        for (const faceDestination& fd : fromRank)
        {
            destAcross[fd.key] = fd.dest;
        }
    }
    return destAcross;
}


// Every tet's faces as they will be at its destination
class acrossAfterMove
{
    const rankTets& mesh_;
    const tetFaceMatch& match_;
    const std::vector<int>& dest_;
    const std::map<globalFaceKey, int>& destAcross_;
    const faceId nTetFaces_;

public:

    acrossAfterMove
    (
        const rankTets& mesh,
        const tetFaceMatch& match,
        const std::vector<int>& dest,
        const std::map<globalFaceKey, int>& destAcross
    )
    :
        mesh_(mesh),
        match_(match),
        dest_(dest),
        destAcross_(destAcross),
        nTetFaces_(faceId(4*mesh.tets.size()))
    {}

    //- What lies across face fi of tet t once it is at its destination
    label operator()(label t, int fi) const
    {
        const faceId other = match_.across[4*t + fi];
        int d;
        if (other < nTetFaces_)
        {
            d = dest_[other/4];
        }
        else
        {
            const label r = mesh_.region[other - nTetFaces_];
            if (!isInterfaceRegion(r))
            {
                return r;   // a physical patch
            }
            d = destAcross_.at(globalKeyOf(mesh_.triangles[other - nTetFaces_], mesh_.globalIds));
        }
        return d == dest_[t] ? internalFace : interfaceRegion(d);
    }
};


// The tets leaving this rank, packed per destination; the staying tets
// and what will lie across their faces
std::vector<std::vector<movedTet>> packMovedTets
(
    const rankTets& mesh,
    const std::vector<int>& dest,
    const acrossAfterMove& acrossOf,
    int me,
    int nRanks,
    std::vector<label>& staying,
    std::vector<std::array<label, 4>>& stayingAcross
)
{
    std::vector<std::vector<movedTet>> send(nRanks);
    for (label t = 0; t < label(mesh.tets.size()); ++t)
    {
        if (dest[t] == me)
        {
            staying.push_back(t);
            continue;
        }
        movedTet m;
        for (int k = 0; k < 4; ++k)
        {
            const label p = mesh.tets[t][k];
            m.globalIds[k] = mesh.globalIds[p];
            m.points[k] = mesh.points[p];
            m.pointIds[k] = mesh.pointIds.empty() ? barycentricId() : mesh.pointIds[p];
            m.across[k] = acrossOf(t, k);
        }
        m.zone = mesh.tetZone.empty() ? 0 : mesh.tetZone[t];
        send[dest[t]].push_back(m);
    }
    stayingAcross.resize(staying.size());
    for (std::size_t i = 0; i < staying.size(); ++i)
    {
        for (int k = 0; k < 4; ++k)
        {
            stayingAcross[i][k] = acrossOf(staying[i], k);
        }
    }
    return send;
}


// The new mesh of a rank, tet by tet: points each once, by global number,
// boundary faces where something other than a local tet lies across
class rankTetsBuilder
{
    const bool zoned_;
    std::unordered_map<label, label> pointOf_;

public:

    rankTets out;

    explicit rankTetsBuilder(bool zoned)
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

    void addTet(const tetVerts& t, const std::array<label, 4>& across, label zone)
    {
        out.tets.push_back(t);
        if (zoned_) out.tetZone.push_back(zone);
        const auto faces = outwardTetFaces(t);
        for (int k = 0; k < 4; ++k)
        {
            if (across[k] != internalFace)
            {
                out.triangles.push_back(faces[k]);
                out.region.push_back(across[k]);
            }
        }
    }
};


// The new mesh: the staying tets' points in their order, then the points
// that came with others. mesh is freed before the received tets are added
// (the peak memory of the move); returns the number received.
std::int64_t assembleMovedMesh
(
    rankTets& mesh,
    const std::vector<label>& staying,
    const std::vector<std::array<label, 4>>& stayingAcross,
    std::vector<std::vector<movedTet>>& received
)
{
    const bool zoned = !mesh.tetZone.empty();
    rankTetsBuilder builder(zoned);
    for (std::size_t i = 0; i < staying.size(); ++i)
    {
        const tetVerts& old = mesh.tets[staying[i]];
        tetVerts t;
        for (int k = 0; k < 4; ++k)
        {
            t[k] = builder.addPoint
            (
                mesh.globalIds[old[k]], mesh.points[old[k]],
                mesh.pointIds.empty() ? barycentricId() : mesh.pointIds[old[k]]
            );
        }
        builder.addTet(t, stayingAcross[i], zoned ? mesh.tetZone[staying[i]] : 0);
    }
    mesh = rankTets();
    std::int64_t nReceived = 0;
    for (auto& fromRank : received)
    {
        for (const movedTet& m : fromRank)
        {
            tetVerts t;
            for (int k = 0; k < 4; ++k)
            {
                t[k] = builder.addPoint(m.globalIds[k], m.points[k], m.pointIds[k]);
            }
            builder.addTet(t, m.across, m.zone);
            ++nReceived;
        }
        freeStorage(fromRank);
    }
    mesh = std::move(builder.out);
    return nReceived;
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
    // Layered meshes stay as they are (see the header): decided together,
    // as one rank may have no layers
    const bool layered = !mesh.prisms.empty() || !mesh.quads.empty();
    if (comm.sum(std::int64_t(layered)) > 0)
    {
        stats.layered = true;
        return stats;
    }
    const int me = comm.rank();
    const label nTets = label(mesh.tets.size());
    const std::vector<double> loads = comm.allGather(double(nTets));
    double total = 0;
    for (double l : loads) total += l;
    const double mean = total/comm.size();
    stats.before = *std::max_element(loads.begin(), loads.end())/mean;
    stats.after = stats.before;
    if (stats.before <= 1 + tolerance)
    {
        return stats;
    }

    const std::vector<int> neighbours = neighbourRanks(mesh);
    const std::map<int, double> flow =
        diffusionFlows(comm, neighbours, double(nTets), mean, tolerance);

    // What lies across each tet face now
    const tetFaceMatch match = fittingTetFaces
    (
        mesh.points.size(), mesh.tets, mesh.triangles,
        "This rank's fine mesh and its surface do not fit together", "balanceFineCells"
    );

    const std::vector<int> dest = tetDestinations(mesh, match, flow, me);
    const std::map<globalFaceKey, int> destAcross =
        destinationsAcross(comm, mesh, match, dest);

    std::vector<label> staying;
    std::vector<std::array<label, 4>> stayingAcross;
    std::vector<std::vector<movedTet>> send = packMovedTets
    (
        mesh, dest, acrossAfterMove(mesh, match, dest, destAcross), me,
        comm.size(), staying, stayingAcross
    );
    std::vector<std::vector<movedTet>> received = comm.exchange(send);
    freeStorage(send);

    const std::int64_t nReceived =
        assembleMovedMesh(mesh, staying, stayingAcross, received);

    stats.moved = comm.sum(nReceived);
    const std::vector<double> after = comm.allGather(double(mesh.tets.size()));
    stats.after = *std::max_element(after.begin(), after.end())/mean;
    return stats;
}
