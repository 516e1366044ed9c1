// Work the master does alone while the other ranks wait (stage 1, the
// coarse mesh): it runs once, on the master, every rank goes on after it,
// and a failure on the master stops every rank together (no rank left
// waiting for a master that threw).

#include "mpiTestMain.H"
#include "failTogether.H"

#include <chrono>
#include <thread>

using namespace pmsh;

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
