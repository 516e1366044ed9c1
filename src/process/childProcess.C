/*---------------------------------------------------------------------------*\
  pmshFoam: the life of a child process, from fork to reply
  (childProcess.H).
\*---------------------------------------------------------------------------*/

#include "childProcess.H"
#include "childWatchdog.H"
#include "pipeWire.H"
#include "pmshError.H"
#include "streamManip.H"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <malloc.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace
{

using namespace pmsh;
using namespace pmsh::pipeWire;

// The reply: a status byte (0 result, 1 error), then for a result the
// point and tet counts and arrays, for an error its message.
enum : char { resultFollows = 0, errorFollows = 1 };

// The exit status of a child whose parent died before it could ask to
// die with it (it has no one to mesh for)
constexpr int orphanedExit = 4;

//- Kills and reaps the child unless released: a parent that leaves by an
//  exception (a result too large for its memory) leaves no mesher behind.
class childGuard
{
    pid_t pid_;
public:
    explicit childGuard(pid_t pid) : pid_(pid) {}
    ~childGuard()
    {
        if (pid_ > 0)
        {
            ::kill(pid_, SIGKILL);
            int status = 0;
            while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {}
        }
    }
    childGuard(const childGuard&) = delete;
    childGuard& operator=(const childGuard&) = delete;
    pid_t release() { const pid_t p = pid_; pid_ = -1; return p; }
};

} // End anonymous namespace


void pmsh::replyFromChild(int fd, const std::function<TetMesh()>& work)
{
    // Open MPI's handlers would print the child's backtrace into the log;
    // the parent reports a crash once, with the signal
    for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT})
    {
        std::signal(sig, SIG_DFL);
    }
    // Whoever stops the run stops the mesher too: no handler of the
    // parent's (OpenFOAM's, MPI's) may keep it alive
    for (int sig : {SIGTERM, SIGINT, SIGHUP, SIGQUIT, SIGPIPE})
    {
        std::signal(sig, SIG_DFL);
    }
    // What the meshers print goes out line by line: a crash loses none of
    // it, and the parent's buffer was emptied before the fork
    // (a buffer of its own: glibc keeps the old one fully buffered)
    static char lineBuffer[BUFSIZ];
    std::setvbuf(stdout, lineBuffer, _IOLBF, sizeof(lineBuffer));

    // The mesher grows and shrinks large arrays all the time: let them
    // reuse the heap (pmshFoam itself maps each large array on its own, so
    // that freeing it returns the memory; here that would only cost page
    // faults, and the child's memory is returned when it exits)
    mallopt(M_MMAP_THRESHOLD, 64*1024*1024);

    bool ok = false;
    try
    {
        const TetMesh m = work();
        const char status = resultFollows;
        ok = writeAll(fd, &status, 1) && writeArray(fd, m.points) && writeArray(fd, m.tets);
    }
    catch (const std::exception& e)
    {
        const char status = errorFollows;
        const std::string message = e.what();
        std::vector<char> text(message.begin(), message.end());
        ok = writeAll(fd, &status, 1) && writeArray(fd, text);
    }
    ::close(fd);
    // _exit skips stdio's flush at exit: the meshers' last words first
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
    // _exit: no atexit handlers, no MPI or library destructors in the child
    ::_exit(ok ? 0 : 3);
}


pmsh::TetMesh pmsh::runInChild
(
    const std::string& what,
    const std::string& attempt,
    const std::function<void(int replyFd, const sharedStepPage& step)>& inChild,
    const std::function<void()>& inParent
)
{
    const char* function = "pmsh::meshInChildProcess";
    const double interval = progressInterval();
    const sharedStepPage step;
    int fds[2];
    if (::pipe(fds) != 0)
    {
        throw FatalError(msg() << "Cannot create a pipe: " << std::strerror(errno), function);
    }
    // The parent's unwritten output would be written twice: by the parent
    // and by the child's copy of the buffer
    std::cout.flush();
    std::fflush(nullptr);
    const pid_t parent = ::getpid();
    const pid_t child = ::fork();
    if (child < 0)
    {
        ::close(fds[0]);
        ::close(fds[1]);
        throw FatalError(msg() << "Cannot fork: " << std::strerror(errno), function);
    }
    if (child == 0)
    {
        // Die with the parent, however it ends; a parent that ended before
        // this line cannot signal: then its pid is no longer the parent's
        // (the request survives an exec)
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent)
        {
            ::_exit(orphanedExit);
        }
        ::close(fds[0]);
        inChild(fds[1], step);
        ::_exit(orphanedExit);
    }

    childGuard running(child);
    ::close(fds[1]);
    inParent();
    const std::string hung =
        waitForReply(fds[0], child, step.get(), interval, attempt.empty() ? what : attempt);
    if (!hung.empty())
    {
        ::close(fds[0]);
        throw FatalError(msg() << "The volume mesher of " << what << " made " << hung, function);
    }
    // Read before waiting: a child blocked on a full pipe would never end
    char reply = -1;
    std::vector<char> errorText;
    TetMesh result;
    const bool complete =
        readAll(fds[0], &reply, 1)
     && (
            reply == errorFollows
          ? readArray(fds[0], errorText)
          : readArray(fds[0], result.points) && readArray(fds[0], result.tets)
        );
    ::close(fds[0]);
    int status = 0;
    const pid_t finished = running.release();
    while (::waitpid(finished, &status, 0) < 0 && errno == EINTR) {}

    if (WIFSIGNALED(status))
    {
        const int sig = WTERMSIG(status);
        throw FatalError
        (
            msg() << "The volume mesher crashed on " << what << " (signal " << sig
                << ", " << ::strsignal(sig) << ")",
            function
        );
    }
    if (complete && reply == errorFollows)
    {
        throw FatalError(std::string(errorText.begin(), errorText.end()), function);
    }
    if (!complete || reply != resultFollows || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    {
        throw FatalError
        (
            msg() << "The volume mesher ended without a result on " << what
                << " (exit status " << (WIFEXITED(status) ? WEXITSTATUS(status) : -1) << ")",
            function
        );
    }
    return result;
}


pmsh::TetMesh pmsh::meshInChildProcess
(
    const std::function<TetMesh()>& work,
    const std::string& what,
    const std::string& attempt
)
{
    return runInChild
    (
        what, attempt,
        [&](int replyFd, const sharedStepPage& step)
        {
            reportStepsTo(step.get());
            replyFromChild(replyFd, work);
        },
        [] {}
    );
}


// ************************************************************************* //
