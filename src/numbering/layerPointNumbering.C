/*---------------------------------------------------------------------------*\
  pmshFoam: stage 5 for prism layer points (globalPointNumbering::
  addLayerPoints). A layer point is named (barycentric id of its surface
  point p, level k), the same on every rank; only some of p's holders use
  it, so the owner is chosen among its users, which they learn from each
  other: each user tells p's other holders that it uses (id, k). Messages
  go only to p's holders (from the coarse mesh and the partition), and the
  owner depends only on the set of users, not on the order messages come
  in: the numbers are deterministic.
\*---------------------------------------------------------------------------*/
#include "globalNumbering.H"
#include "pmshError.H"

#include <algorithm>
#include <unordered_map>

namespace
{

using namespace pmsh;

// "This rank uses level `level` of the point with this id"
struct usedLevel
{
    barycentricId id;
    std::int32_t level;
};

// "Level `level` of the point with this id has this global number"
struct numberedLevel
{
    barycentricId id;
    std::int32_t level;
    label number;
};

struct levelHash
{
    std::size_t operator()(const std::pair<barycentricId, int>& key) const
    {
        return barycentricIdHash()(key.first)*31 + std::size_t(key.second);
    }
};

using levelIndex =
    std::unordered_map<std::pair<barycentricId, int>, label, levelHash>;


// Per layer point: the ranks that use it, ascending (this rank among
// them), from one exchange with p's other holders
std::vector<std::vector<int>> layerPointUsers
(
    const Communicator& comm,
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart,
    const std::vector<barycentricId>& surfaceIds,
    const std::vector<std::pair<label, int>>& layerPoints,
    levelIndex& index
)
{
    const int me = comm.rank();
    const label n = label(layerPoints.size());
    std::vector<std::vector<int>> users(n, std::vector<int>{me});
    std::vector<std::vector<usedLevel>> send(comm.size());
    const coarsePointCells pointCells(coarse);
    for (label j = 0; j < n; ++j)
    {
        const auto [p, k] = layerPoints[j];
        if (p < 0 || p >= label(surfaceIds.size()) || k < 0)
        {
            throw FatalError
            (
                msg() << "Layer point (" << p << ", " << k << ") of rank " << me
                    << " is not a level of one of its " << surfaceIds.size()
                    << " surface points",
                "globalPointNumbering::addLayerPoints"
            );
        }
        const barycentricId& id = surfaceIds[p];
        if (!index.emplace(std::make_pair(id, k), j).second)
        {
            throw FatalError
            (
                msg() << "Layer point (" << id << ", " << k << ") listed twice"
                    << " by rank " << me,
                "globalPointNumbering::addLayerPoints"
            );
        }
        if (comm.size() == 1)
        {
            continue;
        }
        const std::vector<int> holders = holderRanks(id, pointCells, cellPart);
        if (std::find(holders.begin(), holders.end(), me) == holders.end())
        {
            throw FatalError
            (
                msg() << "Layer point (" << id << ", " << k << ") of rank " << me
                    << " is not held by that rank",
                "globalPointNumbering::addLayerPoints"
            );
        }
        for (const int r : holders)
        {
            if (r != me)
            {
                send[r].push_back({id, std::int32_t(k)});
            }
        }
    }

    // A holder that does not use (id, k) only learns that others do
    const std::vector<std::vector<usedLevel>> received = comm.exchange(send);
    for (int r = 0; r < comm.size(); ++r)
    {
        if (r == me)
        {
            continue;
        }
        for (const usedLevel& u : received[r])
        {
            const auto it = index.find({u.id, u.level});
            if (it != index.end())
            {
                users[it->second].push_back(r);
            }
        }
    }
    for (std::vector<int>& u : users)
    {
        std::sort(u.begin(), u.end());
    }
    return users;
}

} // End anonymous namespace


void pmsh::globalPointNumbering::addLayerPoints
(
    const Communicator& comm,
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart,
    const std::vector<barycentricId>& surfaceIds,
    const std::vector<std::pair<label, int>>& layerPoints
)
{
    const int me = comm.rank();
    const label n = label(layerPoints.size());
    levelIndex index;
    const std::vector<std::vector<int>> users = layerPointUsers
    (
        comm, coarse, cellPart, surfaceIds, layerPoints, index
    );

    // The paper's owner rule on the users, the level added to the sum
    std::vector<int> owner(n);
    label nOwnedLayer = 0;
    for (label j = 0; j < n; ++j)
    {
        const auto [p, k] = layerPoints[j];
        const std::vector<int>& u = users[j];
        owner[j] = u[(surfaceIds[p].ownerSum() + std::uint64_t(k)) % u.size()];
        nOwnedLayer += (owner[j] == me);
        nSharedLayer_ += (u.size() > 1);
    }

    // After every ordinary point: those keep their numbers
    const globalRange range = numberRankByRank(comm, nOwnedLayer, "points", nGlobal_);
    label next = label(range.start);
    const label first = label(globalIds_.size());
    globalIds_.resize(first + n, -1);
    std::vector<std::vector<numberedLevel>> send(comm.size());
    for (label j = 0; j < n; ++j)
    {
        if (owner[j] != me)
        {
            continue;
        }
        globalIds_[first + j] = next++;
        const auto [p, k] = layerPoints[j];
        for (const int r : users[j])
        {
            if (r != me)
            {
                send[r].push_back({surfaceIds[p], std::int32_t(k), globalIds_[first + j]});
            }
        }
    }
    nOwned_ += nOwnedLayer;
    nGlobal_ = label(range.end);

    const std::vector<std::vector<numberedLevel>> received = comm.exchange(send);
    label nAssigned = 0;
    for (int r = 0; r < comm.size(); ++r)
    {
        if (r == me)
        {
            continue;
        }
        for (const numberedLevel& m : received[r])
        {
            const auto it = index.find({m.id, m.level});
            if (it == index.end() || owner[it->second] != r || globalIds_[first + it->second] >= 0)
            {
                throw FatalError
                (
                    msg() << "Rank " << r << " numbered layer point (" << m.id
                        << ", " << m.level << ") for rank " << me
                        << ", which does not await it from that rank",
                    "globalPointNumbering::addLayerPoints"
                );
            }
            globalIds_[first + it->second] = m.number;
            ++nAssigned;
        }
    }
    if (nAssigned != n - nOwnedLayer)
    {
        throw FatalError
        (
            msg() << "Rank " << me << " received numbers for " << nAssigned
                << " of its " << n - nOwnedLayer << " layer points owned by"
                << " other ranks",
            "globalPointNumbering::addLayerPoints"
        );
    }
}
