#include "Communicator.H"
#include "foamShims.H"
#include "pmshError.H"

#include "Pstream.H"
#include "PstreamReduceOps.H"
#include "UIPstream.H"
#include "UOPstream.H"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <thread>

pmsh::Communicator::Communicator()
:
    parallel_(Foam::UPstream::parRun()),
    rank_(Foam::UPstream::myProcNo()),
    size_(Foam::UPstream::nProcs())
{}


void pmsh::Communicator::abort(int errorCode) const
{
    if (parallel_)
    {
        Foam::UPstream::abort();
    }
    std::exit(errorCode);
}


double pmsh::Communicator::sum(double x) const
{
    return Foam::returnReduce(x, Foam::sumOp<double>());
}

std::int64_t pmsh::Communicator::sum(std::int64_t x) const
{
    return Foam::returnReduce(x, Foam::sumOp<std::int64_t>());
}

double pmsh::Communicator::min(double x) const
{
    return Foam::returnReduce(x, Foam::minOp<double>());
}

double pmsh::Communicator::max(double x) const
{
    return Foam::returnReduce(x, Foam::maxOp<double>());
}

std::int64_t pmsh::Communicator::max(std::int64_t x) const
{
    return Foam::returnReduce(x, Foam::maxOp<std::int64_t>());
}

void pmsh::Communicator::barrier() const
{
    // A reduction: v1912's UPstream has no barrier
    all(true);
}

bool pmsh::Communicator::all(bool flag) const
{
    return Foam::returnReduce(flag, Foam::andOp<bool>());
}

bool pmsh::Communicator::any(bool flag) const
{
    return Foam::returnReduce(flag, Foam::orOp<bool>());
}


namespace
{

// Tags of pmshFoam's own messages (not ones OpenFOAM uses)
constexpr int masterDoneTag = 4712;
constexpr int broadcastTag = 4713;
constexpr int exchangeTag = 4714;

// MPI counts are ints: payloads go in messages of at most 1 GiB
constexpr std::size_t maxMessageBytes = std::size_t(1) << 30;

// Call send(offset, n) for each message of a payload of `bytes` bytes
template<class Message>
void forEachMessage(std::size_t bytes, const Message& message)
{
    for (std::size_t offset = 0; offset < bytes; offset += maxMessageBytes)
    {
        message(offset, std::min(maxMessageBytes, bytes - offset));
    }
}

} // End anonymous namespace


void pmsh::Communicator::masterDone() const
{
    if (!parallel_)
    {
        return;
    }
    char done = 1;
    for (int r = 1; r < size_; ++r)
    {
        Foam::UOPstream::write
        (
            Foam::UPstream::commsTypes::blocking, r, &done, 1, masterDoneTag
        );
    }
}


void pmsh::Communicator::sleepUntilMasterDone() const
{
    if (!parallel_)
    {
        return;
    }
    char done = 0;
    const Foam::label request = Foam::UPstream::nRequests();
    Foam::UIPstream::read
    (
        Foam::UPstream::commsTypes::nonBlocking, 0, &done, 1, masterDoneTag
    );
    while (!Foam::UPstream::finishedRequest(request))
    {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    Foam::UPstream::resetRequests(request);
}


std::int64_t pmsh::Communicator::exclusiveScan(std::int64_t x) const
{
    // Not globalIndex: its offsets are labels (32-bit in Debian's build)
    // and global point counts pass 2^31
    const std::vector<std::int64_t> all = allGather(x);
    std::int64_t below = 0;
    for (int r = 0; r < rank_; ++r)
    {
        below += all[r];
    }
    return below;
}


void pmsh::Communicator::broadcastRaw(char* data, std::size_t bytes) const
{
    // A binomial tree from the master (as MPI_Bcast's): each rank receives
    // from the rank its lowest set bit away, then sends on to the ranks
    // below that bit; every message goes straight from and into `data`
    using namespace Foam;
    int mask = 1;
    for (; mask < size_; mask <<= 1)
    {
        if (rank_ & mask)
        {
            forEachMessage(bytes, [&](std::size_t offset, std::size_t n)
            {
                UIPstream::read
                (
                    UPstream::commsTypes::scheduled, rank_ - mask, data + offset,
                    std::streamsize(n), broadcastTag
                );
            });
            break;
        }
    }
    for (mask >>= 1; mask > 0; mask >>= 1)
    {
        if (rank_ + mask < size_)
        {
            forEachMessage(bytes, [&](std::size_t offset, std::size_t n)
            {
                UOPstream::write
                (
                    UPstream::commsTypes::scheduled, rank_ + mask, data + offset,
                    std::streamsize(n), broadcastTag
                );
            });
        }
    }
}


std::vector<char> pmsh::Communicator::allGatherRaw
(
    const char* item,
    std::size_t bytes
) const
{
    Foam::List<Foam::List<char>> all(size_);
    all[rank_] = Foam::UList<char>(const_cast<char*>(item), Foam::label(bytes));
    pmsh::foam::allGatherList(all);
    std::vector<char> gathered;
    gathered.reserve(size_*bytes);
    for (const Foam::List<char>& fromRank : all)
    {
        gathered.insert(gathered.end(), fromRank.begin(), fromRank.end());
    }
    return gathered;
}


std::vector<std::size_t> pmsh::Communicator::exchangeCounts
(
    const std::vector<std::size_t>& counts
) const
{
    if (int(counts.size()) != size_)
    {
        throw FatalError(msg() << "exchange needs one buffer per rank", "Communicator::exchange");
    }
    Foam::labelList send(size_), received(size_);
    for (int r = 0; r < size_; ++r)
    {
        if (counts[r] > std::size_t(Foam::labelMax))
        {
            throw FatalError
            (
                msg() << "Too much data for one rank to send to another: "
                    << counts[r] << " items.\nUse more ranks",
                "Communicator::exchange"
            );
        }
        send[r] = Foam::label(counts[r]);
    }
    Foam::UPstream::allToAll(send, received);
    return std::vector<std::size_t>(received.begin(), received.end());
}


void pmsh::Communicator::exchangeRaw
(
    const std::vector<const char*>& send,
    const std::vector<std::size_t>& sendBytes,
    const std::vector<char*>& recv,
    const std::vector<std::size_t>& recvBytes
) const
{
    using namespace Foam;
    const label firstRequest = UPstream::nRequests();
    for (int r = 0; r < size_; ++r)
    {
        if (r == rank_) continue;
        forEachMessage(recvBytes[r], [&](std::size_t offset, std::size_t n)
        {
            UIPstream::read
            (
                UPstream::commsTypes::nonBlocking, r, recv[r] + offset,
                std::streamsize(n), exchangeTag
            );
        });
    }
    for (int r = 0; r < size_; ++r)
    {
        if (r == rank_ || sendBytes[r] == 0) continue;
        ++traffic_.messages;
        traffic_.bytes += double(sendBytes[r]);
        forEachMessage(sendBytes[r], [&](std::size_t offset, std::size_t n)
        {
            UOPstream::write
            (
                UPstream::commsTypes::nonBlocking, r, send[r] + offset,
                std::streamsize(n), exchangeTag
            );
        });
    }
    UPstream::waitRequests(firstRequest);
}
