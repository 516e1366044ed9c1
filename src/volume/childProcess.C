#include "childProcess.H"
#include "pmshError.H"

#include <cerrno>
#include <csignal>
#include <malloc.h>
#include <cstdint>
#include <cstring>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace
{

using namespace pmsh;

// The pipe protocol: a status byte (0 result, 1 error), then for a result
// the point and tet counts and arrays, for an error its message.
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

bool writeAll(int fd, const void* data, std::size_t n)
{
    const char* p = static_cast<const char*>(data);
    while (n > 0)
    {
        const ssize_t w = ::write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return false;
        p += w;
        n -= std::size_t(w);
    }
    return true;
}

template<class T>
bool writeArray(int fd, const std::vector<T>& v)
{
    const std::uint64_t n = v.size();
    return writeAll(fd, &n, sizeof(n)) && writeAll(fd, v.data(), n*sizeof(T));
}

bool readAll(int fd, void* data, std::size_t n)
{
    char* p = static_cast<char*>(data);
    while (n > 0)
    {
        const ssize_t r = ::read(fd, p, n);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return false;
        p += r;
        n -= std::size_t(r);
    }
    return true;
}

// Straight into the array: no second copy of a mesh of millions of cells
template<class T>
bool readArray(int fd, std::vector<T>& v)
{
    std::uint64_t n = 0;
    if (!readAll(fd, &n, sizeof(n))) return false;
    v.resize(n);
    return readAll(fd, v.data(), n*sizeof(T));
}

// Runs in the child: never returns
[[noreturn]] void childMain(int fd, const std::function<TetMesh()>& work)
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
    // _exit: no atexit handlers, no MPI or library destructors in the child
    ::_exit(ok ? 0 : 3);
}

} // End anonymous namespace


pmsh::TetMesh pmsh::meshInChildProcess
(
    const std::function<TetMesh()>& work,
    const std::string& what
)
{
    const char* function = "pmsh::meshInChildProcess";
    int fds[2];
    if (::pipe(fds) != 0)
    {
        throw FatalError(msg() << "Cannot create a pipe: " << std::strerror(errno), function);
    }
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
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent)
        {
            ::_exit(orphanedExit);
        }
        ::close(fds[0]);
        childMain(fds[1], work);
    }

    childGuard running(child);
    ::close(fds[1]);
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
