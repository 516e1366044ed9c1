#include "globalNumbering.H"
#include "failTogether.H"
#include "labelLimit.H"
#include "pmshError.H"

#include <algorithm>
#include <unordered_map>

namespace
{

// What an owner tells a holder: this id has this global number
struct numberedId
{
    pmsh::barycentricId id;
    pmsh::label number;
};

} // End anonymous namespace


pmsh::globalRange pmsh::numberRankByRank
(
    const Communicator& comm,
    std::int64_t count,
    const std::string& what,
    std::int64_t first
)
{
    globalRange range;
    range.start = first + comm.exclusiveScan(count);
    range.end = first + comm.sum(count);
    try
    {
        checkFitsLabel(range.end, what);
    }
    catch (const FatalError& e)
    {
        // Every rank has the same end: all stop here, the master says why
        throw collectiveFailure(e, comm.master());
    }
    return range;
}


pmsh::globalPointNumbering::globalPointNumbering
(
    const Communicator& comm,
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart,
    const FineSurface& surface,
    label nLocalPoints
)
:
    globalIds_(nLocalPoints, -1)
{
    const int me = comm.rank();
    const label nSurface = label(surface.points.size());
    const coarsePointCells pointCells(coarse);

    // Owner of each surface point; the interior points are all ours
    std::vector<int> owner(nSurface, me);
    std::vector<std::vector<int>> otherHolders(nSurface);
    for (label p = 0; p < nSurface; ++p)
    {
        if (comm.size() == 1)
        {
            break;      // one rank holds everything
        }
        const barycentricId& id = surface.ids[p];
        std::vector<int> holders = holderRanks(id, pointCells, cellPart);
        if (std::find(holders.begin(), holders.end(), me) == holders.end())
        {
            throw FatalError
            (
                msg() << "Surface point " << id << " of rank " << me
                    << " is not held by that rank",
                "globalPointNumbering"
            );
        }
        if (holders.size() < 2)
        {
            continue;
        }
        ++nShared_;
        owner[p] = ownerRank(id, holders);
        holders.erase(std::find(holders.begin(), holders.end(), me));
        otherHolders[p] = std::move(holders);
    }

    nOwned_ = nLocalPoints - nSurface;
    for (label p = 0; p < nSurface; ++p)
    {
        nOwned_ += (owner[p] == me);
    }
    const globalRange range = numberRankByRank(comm, nOwned_, "points");
    label next = label(range.start);
    nGlobal_ = label(range.end);

    // Number what we own, in local order, and tell the other holders
    std::vector<std::vector<numberedId>> send(comm.size());
    for (label p = 0; p < nLocalPoints; ++p)
    {
        if (p < nSurface && owner[p] != me)
        {
            continue;
        }
        globalIds_[p] = next++;
        if (p < nSurface)
        {
            for (int r : otherHolders[p])
            {
                send[r].push_back({surface.ids[p], globalIds_[p]});
            }
        }
    }

    const std::vector<std::vector<numberedId>> received = comm.exchange(send);

    std::unordered_map<barycentricId, label, barycentricIdHash> awaiting;
    for (label p = 0; p < nSurface; ++p)
    {
        if (owner[p] != me)
        {
            awaiting.emplace(surface.ids[p], p);
        }
    }
    label nAssigned = 0;
    for (int r = 0; r < comm.size(); ++r)
    {
        for (const numberedId& n : received[r])
        {
            auto it = awaiting.find(n.id);
            if (it == awaiting.end() || globalIds_[it->second] >= 0)
            {
                throw FatalError
                (
                    msg() << "Rank " << r << " numbered point " << n.id
                        << " for rank " << me << ", which does not await it",
                    "globalPointNumbering"
                );
            }
            globalIds_[it->second] = n.number;
            ++nAssigned;
        }
    }
    if (nAssigned != label(awaiting.size()))
    {
        throw FatalError
        (
            msg() << "Rank " << me << " received numbers for " << nAssigned
                << " of its " << awaiting.size() << " shared points owned by"
                << " other ranks",
            "globalPointNumbering"
        );
    }
}
