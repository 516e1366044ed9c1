#include "failTogether.H"
#include "foamShims.H"

#include <chrono>
#include <condition_variable>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

struct pmsh::abortUnlessAgreed::watchdog
{
    std::mutex mutex;
    std::condition_variable agreed;
    bool done = false;
    std::thread thread;
};


pmsh::abortUnlessAgreed::abortUnlessAgreed
(
    const Communicator& comm,
    const FatalError& error,
    double seconds
)
:
    watchdog_(new watchdog)
{
    watchdog& w = *watchdog_;
    const int rank = comm.rank();
    w.thread = std::thread([&w, error, seconds, rank]
    {
        std::unique_lock<std::mutex> lock(w.mutex);
        const bool agreed = w.agreed.wait_for
        (
            lock,
            std::chrono::duration<double>(seconds),
            [&w] { return w.done; }
        );
        if (agreed)
        {
            return;
        }
        std::ostringstream why;
        why << "Rank " << rank << " failed (the error above), and the other"
            " ranks did not come to agree on it within " << seconds << " s:"
            " one of them is most likely waiting for this rank in an exchange"
            " it will never join. Aborting every rank rather than hanging.";
        std::cerr
            << '[' << rank << "] " << error.report()
            << '[' << rank << "] " << FatalError(why.str(), "pmsh::failTogether").report()
            << std::flush;
        MPI_Abort(MPI_COMM_WORLD, 1);
    });
}


pmsh::abortUnlessAgreed::~abortUnlessAgreed()
{
    {
        const std::lock_guard<std::mutex> lock(watchdog_->mutex);
        watchdog_->done = true;
    }
    watchdog_->agreed.notify_one();
    watchdog_->thread.join();
}


// ************************************************************************* //
