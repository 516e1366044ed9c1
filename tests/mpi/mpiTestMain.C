#include "mpiTestMain.H"
#include "foamShims.H"

#include "UPstream.H"

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <streambuf>

namespace
{
const pmsh::Communicator* theWorld = nullptr;

// Takes what is written and keeps nothing (the stream stays good, as
// OpenFOAM's Sout on std::cout requires)
class discardingBuffer : public std::streambuf
{
protected:
    int overflow(int c) override { return traits_type::not_eof(c); }
};

// A failed assertion on a rank other than the master, which does not print
// GoogleTest's progress: without it only the exit code would tell
class failurePrinter : public ::testing::EmptyTestEventListener
{
    const int rank_;
public:
    explicit failurePrinter(int rank) : rank_(rank) {}
    void OnTestPartResult(const ::testing::TestPartResult& result) override
    {
        if (result.failed())
        {
            std::printf
            (
                "[rank %d] %s:%d: Failure\n%s\n", rank_,
                result.file_name() ? result.file_name() : "unknown file",
                result.line_number(), result.message()
            );
            std::fflush(stdout);
        }
    }
};
}

const pmsh::Communicator& pmsh::test::world()
{
    return *theWorld;
}


int main(int argc, char** argv)
{
    // Volume meshing forks children that make no MPI calls, as in pmshFoam
    ::setenv("OMPI_MCA_mpi_warn_on_fork", "0", 0);

    // OpenFOAM's Pstream starts MPI, as argList does for -parallel; on
    // one rank the same tests run serially (MPI started for Netgen only,
    // as pmshFoam does)
    const char* worldSize = std::getenv("OMPI_COMM_WORLD_SIZE");
    if (worldSize && std::atoi(worldSize) > 1)
    {
        Foam::UPstream::init(argc, argv, false);
    }
    else
    {
        pmsh::foam::initNullMPI();
    }
    const pmsh::Communicator comm;
    theWorld = &comm;
    // The stages' logs (std::cout) would bury GoogleTest's report, which
    // it prints with printf
    discardingBuffer discard;
    std::streambuf* const log = std::cout.rdbuf(&discard);

    ::testing::InitGoogleTest(&argc, argv);
    if (!comm.master())
    {
        auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
        delete listeners.Release(listeners.default_result_printer());
        listeners.Append(new failurePrinter(comm.rank()));
    }
    const int failed = RUN_ALL_TESTS();
    const double anyFailed = comm.max(double(failed));
    std::cout.rdbuf(log);
    if (comm.master() && anyFailed)
    {
        std::cout << "Some rank failed a test" << std::endl;
    }
    pmsh::foam::endNullMPI();
    Foam::UPstream::exit(anyFailed ? 1 : 0);
    return 1;
}
