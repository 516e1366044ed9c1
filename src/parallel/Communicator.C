#include "Communicator.H"
#include "foamShims.H"
#include "pmshError.H"

#include "Pstream.H"
#include "PstreamReduceOps.H"
#include "UIPstream.H"
#include "UOPstream.H"

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

// x of every rank, in rank order, on every rank
template<class T>
Foam::List<T> gatherAll(T x)
{
    Foam::List<T> all(Foam::UPstream::nProcs(), x);
    all[Foam::UPstream::myProcNo()] = x;
    pmsh::foam::allGatherList(all);
    return all;
}

} // End anonymous namespace


namespace
{

// The tag of the master's "done" message (not one OpenFOAM uses)
constexpr int masterDoneTag = 4712;

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
    const Foam::List<std::int64_t> all = gatherAll(x);
    std::int64_t below = 0;
    for (int r = 0; r < rank_; ++r)
    {
        below += all[r];
    }
    return below;
}


std::vector<double> pmsh::Communicator::allGather(double x) const
{
    const Foam::List<double> all = gatherAll(x);
    return std::vector<double>(all.begin(), all.end());
}


void pmsh::Communicator::broadcastBytes(std::vector<char>& bytes) const
{
    Foam::List<char> buffer;
    if (master())
    {
        buffer = Foam::UList<char>(bytes.data(), Foam::label(bytes.size()));
    }
    pmsh::foam::broadcast(buffer);
    bytes.assign(buffer.begin(), buffer.end());
    traffic_.broadcastBytes += double(bytes.size());
}


std::vector<std::vector<char>> pmsh::Communicator::exchangeBytes
(
    const std::vector<std::vector<char>>& send
) const
{
    if (!parallel_)
    {
        return send;
    }
    if (int(send.size()) != size_)
    {
        throw FatalError(msg() << "exchange needs one buffer per rank", "Communicator::exchange");
    }

    Foam::List<Foam::List<char>> sendBuffers(size_);
    for (int r = 0; r < size_; ++r)
    {
        if (r != rank_ && !send[r].empty())
        {
            ++traffic_.messages;
            traffic_.bytes += double(send[r].size());
        }
        sendBuffers[r] = Foam::UList<char>
        (
            const_cast<char*>(send[r].data()), Foam::label(send[r].size())
        );
    }
    Foam::List<Foam::List<char>> recvBuffers;
    Foam::Pstream::exchange<Foam::List<char>, char>(sendBuffers, recvBuffers);

    std::vector<std::vector<char>> recv(size_);
    for (int r = 0; r < size_; ++r)
    {
        recv[r].assign(recvBuffers[r].begin(), recvBuffers[r].end());
    }
    return recv;
}
