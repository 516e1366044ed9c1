#include "mpiTestMain.H"

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
    pmsh::Communicator comm(argc, argv);
    theWorld = &comm;
    pmsh::setLogRank(comm.rank(), true);
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
    return anyFailed ? 1 : 0;
}
