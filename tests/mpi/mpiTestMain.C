#include "mpiTestMain.H"
#include "foamShims.H"

#include "UPstream.H"

#include <cstdlib>

namespace
{
const pmsh::Communicator* theWorld = nullptr;
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
    pmsh::setLogRank(comm.rank(), comm.parallel());
    pmsh::setInfoSilent(true);

    ::testing::InitGoogleTest(&argc, argv);
    if (!comm.master())
    {
        // Failures still print (with the rank's assertion text)
        auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
        delete listeners.Release(listeners.default_result_printer());
    }
    const int failed = RUN_ALL_TESTS();
    const double anyFailed = comm.max(double(failed));
    if (comm.master() && anyFailed)
    {
        std::cout << "Some rank failed a test" << std::endl;
    }
    pmsh::foam::endNullMPI();
    Foam::UPstream::exit(anyFailed ? 1 : 0);
    return 1;
}
