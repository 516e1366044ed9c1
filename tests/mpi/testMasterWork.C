// Work the master does alone while the other ranks wait (stage 1, the
// coarse mesh): it runs once, on the master, every rank goes on after it,
// the others wait without using their core (the master's threads need
// it), and a failure on the master stops every rank together (no rank left
// waiting for a master that threw).

#include "mpiTestMain.H"
#include "failTogether.H"

#include <chrono>
#include <thread>
#include <time.h>

using namespace pmsh;

namespace
{

//- CPU seconds this process has used so far.
double cpuSeconds()
{
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9*double(t.tv_nsec);
}

} // End anonymous namespace


TEST(masterWork, runsOnceOnTheMasterAndEveryRankGoesOnAfterIt)
{
    const Communicator& comm = test::world();
    double runs = 0;
    double finishedAt = 0;
    comm.masterWorksOthersSleep([&]
    {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        runs += 1;
        finishedAt = double(std::chrono::steady_clock::now().time_since_epoch().count());
    });
    const double returnedAt = double(std::chrono::steady_clock::now().time_since_epoch().count());
    EXPECT_EQ(comm.sum(runs), 1.0);
    EXPECT_EQ(runs, comm.master() ? 1.0 : 0.0);
    // No rank returned before the master's work had finished (one clock:
    // the ranks share this machine)
    EXPECT_GE(comm.min(returnedAt), comm.max(finishedAt));
}


TEST(masterWork, theOtherRanksWaitWithoutUsingTheirCore)
{
    // A blocking MPI receive or barrier polls: the waiting rank's CPU time
    // grows with its wall time (all of it on an idle core, its share on a
    // loaded one). Sleeping in short steps costs a few wake-ups.
    const Communicator& comm = test::world();
    const auto wallStart = std::chrono::steady_clock::now();
    const double cpuStart = cpuSeconds();
    comm.masterWorksOthersSleep([&]
    {
        std::this_thread::sleep_for(std::chrono::seconds(1));
    });
    const double cpu = cpuSeconds() - cpuStart;
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
    if (!comm.master())
    {
        EXPECT_LT(cpu, 0.05*wall)
            << "rank " << comm.rank() << " used " << cpu << " s of CPU in "
            << wall << " s waiting for the master";
    }
}


TEST(masterWork, aFailureOnTheMasterStopsEveryRankTogether)
{
    const Communicator& comm = test::world();
    bool stopped = false;
    try
    {
        failTogether(comm, [&]
        {
            comm.masterWorksOthersSleep([&]
            {
                throw FatalError("the master's work failed", "test");
            });
        });
    }
    catch (const collectiveFailure& e)
    {
        stopped = true;
        if (comm.master())
        {
            EXPECT_NE(e.message().find("the master's work failed"), std::string::npos);
        }
    }
    EXPECT_TRUE(stopped);
    EXPECT_TRUE(comm.all(stopped));
}


// Run alone, at 2 ranks (tests/CMakeLists.txt: failTogetherAbort.np2):
// success is the run aborting with both errors, not this test passing
TEST(failTogetherAbort, aRankThatFailsWhileTheOthersWaitForItInAnExchangeAbortsTheRun)
{
    const Communicator& comm = test::world();
    if (!comm.parallel())
    {
        GTEST_SKIP() << "needs 2 ranks";
    }
    failTogether
    (
        comm,
        [&]
        {
            if (comm.rank() == 1)
            {
                throw FatalError("rank 1's work failed", "test");
            }
            // The others wait for rank 1 in an exchange it never joins
            comm.exchange(std::vector<std::vector<int>>(comm.size()));
        },
        2
    );
    ADD_FAILURE() << "rank " << comm.rank() << " went on: the run was not aborted";
}
