#include "Communicator.H"
#include "error.H"

#include <cstdlib>
#include <limits>

namespace
{

// MPI counts are int: move large buffers in chunks below 2^31 bytes
constexpr std::size_t maxChunk = std::size_t(1) << 30;

} // End anonymous namespace


pmsh::Communicator::Communicator()
:
    parallel_(false),
    rank_(0),
    size_(1)
{}


pmsh::Communicator::Communicator(int& argc, char**& argv)
:
    parallel_(true),
    rank_(0),
    size_(1)
{
    // Volume meshing runs in forked children that make no MPI calls (see
    // childProcess.H): tell Open MPI not to warn about the fork, unless
    // the user has set it
    ::setenv("OMPI_MCA_mpi_warn_on_fork", "0", 0);

    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_SINGLE, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
}


pmsh::Communicator::~Communicator()
{
    if (parallel_)
    {
        MPI_Finalize();
    }
}


void pmsh::Communicator::barrier() const
{
    if (parallel_)
    {
        MPI_Barrier(MPI_COMM_WORLD);
    }
}


void pmsh::Communicator::abort(int errorCode) const
{
    if (parallel_)
    {
        MPI_Abort(MPI_COMM_WORLD, errorCode);
    }
    std::exit(errorCode);
}


namespace
{

template<class T>
T allReduce(bool parallel, T x, MPI_Datatype type, MPI_Op op)
{
    if (parallel)
    {
        MPI_Allreduce(MPI_IN_PLACE, &x, 1, type, op, MPI_COMM_WORLD);
    }
    return x;
}

} // End anonymous namespace


double pmsh::Communicator::sum(double x) const
{
    return allReduce(parallel_, x, MPI_DOUBLE, MPI_SUM);
}

std::int64_t pmsh::Communicator::sum(std::int64_t x) const
{
    return allReduce(parallel_, x, MPI_INT64_T, MPI_SUM);
}

double pmsh::Communicator::min(double x) const
{
    return allReduce(parallel_, x, MPI_DOUBLE, MPI_MIN);
}

double pmsh::Communicator::max(double x) const
{
    return allReduce(parallel_, x, MPI_DOUBLE, MPI_MAX);
}

std::int64_t pmsh::Communicator::max(std::int64_t x) const
{
    return allReduce(parallel_, x, MPI_INT64_T, MPI_MAX);
}

bool pmsh::Communicator::all(bool flag) const
{
    return allReduce(parallel_, int(flag), MPI_INT, MPI_MIN) != 0;
}

bool pmsh::Communicator::any(bool flag) const
{
    return allReduce(parallel_, int(flag), MPI_INT, MPI_MAX) != 0;
}


std::int64_t pmsh::Communicator::exclusiveScan(std::int64_t x) const
{
    std::int64_t below = 0;
    if (parallel_)
    {
        MPI_Exscan(&x, &below, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
        if (rank_ == 0)
        {
            below = 0;  // MPI leaves rank 0's result undefined
        }
    }
    return below;
}


std::vector<double> pmsh::Communicator::allGather(double x) const
{
    std::vector<double> all(size_, x);
    if (parallel_)
    {
        MPI_Allgather(&x, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, MPI_COMM_WORLD);
    }
    return all;
}


void pmsh::Communicator::broadcastBytes(void* data, std::size_t nBytes) const
{
    char* p = static_cast<char*>(data);
    for (std::size_t done = 0; done < nBytes; done += maxChunk)
    {
        const std::size_t n = std::min(maxChunk, nBytes - done);
        MPI_Bcast(p + done, int(n), MPI_BYTE, 0, MPI_COMM_WORLD);
    }
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

    // Sizes first, then point-to-point messages in chunks (no 2 GiB limit)
    std::vector<std::uint64_t> sendSizes(size_), recvSizes(size_);
    for (int r = 0; r < size_; ++r)
    {
        sendSizes[r] = send[r].size();
    }
    MPI_Alltoall
    (
        sendSizes.data(), 1, MPI_UINT64_T,
        recvSizes.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD
    );

    std::vector<std::vector<char>> recv(size_);
    std::vector<MPI_Request> requests;
    const int tag = 4711;
    for (int r = 0; r < size_; ++r)
    {
        recv[r].resize(recvSizes[r]);
        for (std::size_t done = 0; done < recvSizes[r]; done += maxChunk)
        {
            requests.emplace_back();
            MPI_Irecv
            (
                recv[r].data() + done, int(std::min(maxChunk, recvSizes[r] - done)),
                MPI_BYTE, r, tag, MPI_COMM_WORLD, &requests.back()
            );
        }
    }
    for (int r = 0; r < size_; ++r)
    {
        for (std::size_t done = 0; done < sendSizes[r]; done += maxChunk)
        {
            requests.emplace_back();
            MPI_Isend
            (
                const_cast<char*>(send[r].data()) + done,
                int(std::min(maxChunk, sendSizes[r] - done)),
                MPI_BYTE, r, tag, MPI_COMM_WORLD, &requests.back()
            );
        }
    }
    MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    return recv;
}
