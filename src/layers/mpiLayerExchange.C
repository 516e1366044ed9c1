#include "mpiLayerExchange.H"
#include "globalNumbering.H"
#include "pmshError.H"

#include <algorithm>

namespace
{

using namespace pmsh;

// Ids on the wire, 12 bytes: every id of the problem fits
// (barycentricId::packable)
struct packedCodec
{
    using wire = std::array<std::uint32_t, 3>;
    int levels;
    wire encode(const barycentricId& id) const { return id.pack(levels); }
    barycentricId decode(const wire& w) const { return barycentricId::unpack(w, levels); }
};

// Ids on the wire whole, 24 bytes: a coarse mesh too large to pack
struct wholeCodec
{
    using wire = barycentricId;
    const wire& encode(const barycentricId& id) const { return id; }
    const barycentricId& decode(const wire& w) const { return w; }
};

// body(codec) with the exchange's codec: ids packed where they fit
// (mpiLayerExchange::packed), else whole. The one place that chooses, for
// every exchange of the kernel
template<class Body>
void withCodec(bool packed, int levels, const Body& body)
{
    if (packed)
    {
        body(packedCodec{levels});
    }
    else
    {
        body(wholeCodec{});
    }
}

// One triangle's share of a shared point's sum, as sent
template<class Wire>
struct wireContribution
{
    Wire point;
    std::array<Wire, 3> key;
    label tag;
    vector3 value;
};

// A rank's value for a shared point, as sent
template<class Wire>
struct wireValue
{
    Wire point;
    double value;
};

} // End anonymous namespace


pmsh::mpiLayerExchange::mpiLayerExchange
(
    const Communicator& comm,
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart,
    int refinementLevels
)
:
    comm_(comm),
    cellPart_(cellPart),
    pointCells_(coarse),
    levels_(refinementLevels),
    packed_(barycentricId::packable(coarse.points.size(), refinementLevels))
{}


void pmsh::mpiLayerExchange::plan(const std::vector<barycentricId>& ids)
{
    if (ids == planIds_ && others_.size() == ids.size())
    {
        return;
    }
    const int me = comm_.rank();
    planIds_ = ids;
    others_.assign(ids.size(), {});
    index_.clear();
    nShared_ = 0;
    for (std::size_t i = 0; i < ids.size(); ++i)
    {
        std::vector<int> holders = holderRanks(ids[i], pointCells_, cellPart_);
        const auto mine = std::find(holders.begin(), holders.end(), me);
        if (mine == holders.end())
        {
            throw FatalError
            (
                msg() << "Layer point " << ids[i] << " of rank " << me
                    << " is not held by that rank",
                "mpiLayerExchange"
            );
        }
        holders.erase(mine);
        if (holders.empty())
        {
            continue;       // ours alone: nothing to send or await
        }
        if (!index_.emplace(ids[i], label(i)).second)
        {
            throw FatalError
            (
                msg() << "Layer point " << ids[i] << " passed twice by rank " << me,
                "mpiLayerExchange"
            );
        }
        others_[i] = std::move(holders);
        ++nShared_;
    }
}


pmsh::label pmsh::mpiLayerExchange::indexOf(const barycentricId& id, int from) const
{
    const auto it = index_.find(id);
    if (it == index_.end())
    {
        throw FatalError
        (
            msg() << "Rank " << from << " sent layer data for point " << id
                << " to rank " << comm_.rank() << ", which does not share it:"
                << " the holders disagree on their shared points",
            "mpiLayerExchange"
        );
    }
    return it->second;
}


template<class Codec>
void pmsh::mpiLayerExchange::gatherAs
(
    const Codec& codec,
    const std::vector<barycentricId>& ids,
    std::vector<std::vector<keyedContribution>>& contributions
)
{
    using record = wireContribution<typename Codec::wire>;
    std::vector<std::vector<record>> send(comm_.size());
    for (std::size_t i = 0; i < ids.size(); ++i)
    {
        for (const int r : others_[i])
        {
            for (const keyedContribution& c : contributions[i])
            {
                send[r].push_back
                ({
                    codec.encode(ids[i]),
                    {codec.encode(c.key[0]), codec.encode(c.key[1]), codec.encode(c.key[2])},
                    c.tag,
                    c.value
                });
            }
        }
    }
    const std::vector<std::vector<record>> received = comm_.exchange(send);

    // Appended in rank order; the kernel sorts by (tag, key) before summing
    for (int r = 0; r < comm_.size(); ++r)
    {
        if (r == comm_.rank())
        {
            continue;
        }
        for (const record& w : received[r])
        {
            contributions[indexOf(codec.decode(w.point), r)].push_back
            ({
                {codec.decode(w.key[0]), codec.decode(w.key[1]), codec.decode(w.key[2])},
                w.tag,
                w.value
            });
        }
    }
}


template<class Codec>
void pmsh::mpiLayerExchange::minimumAs
(
    const Codec& codec,
    const std::vector<barycentricId>& ids,
    std::vector<double>& values
)
{
    using record = wireValue<typename Codec::wire>;
    std::vector<std::vector<record>> send(comm_.size());
    for (std::size_t i = 0; i < ids.size(); ++i)
    {
        for (const int r : others_[i])
        {
            send[r].push_back({codec.encode(ids[i]), values[i]});
        }
    }
    const std::vector<std::vector<record>> received = comm_.exchange(send);
    for (int r = 0; r < comm_.size(); ++r)
    {
        if (r == comm_.rank())
        {
            continue;
        }
        for (const record& w : received[r])
        {
            double& v = values[indexOf(codec.decode(w.point), r)];
            v = std::min(v, w.value);
        }
    }
}


void pmsh::mpiLayerExchange::gatherContributions
(
    const std::vector<barycentricId>& ids,
    std::vector<std::vector<keyedContribution>>& contributions
)
{
    if (ids.size() != contributions.size())
    {
        throw FatalError
        (
            msg() << ids.size() << " ids but " << contributions.size()
                << " lists of contributions",
            "mpiLayerExchange::gatherContributions"
        );
    }
    plan(ids);
    withCodec
    (
        packed_, levels_,
        [&](const auto& codec) { gatherAs(codec, ids, contributions); }
    );
}


void pmsh::mpiLayerExchange::minimum
(
    const std::vector<barycentricId>& ids,
    std::vector<double>& values
)
{
    if (ids.size() != values.size())
    {
        throw FatalError
        (
            msg() << ids.size() << " ids but " << values.size() << " values",
            "mpiLayerExchange::minimum"
        );
    }
    plan(ids);
    withCodec
    (
        packed_, levels_,
        [&](const auto& codec) { minimumAs(codec, ids, values); }
    );
}


bool pmsh::mpiLayerExchange::anyRank(bool local)
{
    return comm_.any(local);
}


int pmsh::mpiLayerExchange::rank() const
{
    return comm_.rank();
}
