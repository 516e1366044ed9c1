#include "childProcess.H"
#include "meshingStep.H"
#include "streamManip.H"
#include "pmshError.H"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <malloc.h>
#include <mutex>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <poll.h>
#include <sys/mman.h>
#include <sys/socket.h>
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

//- CPU seconds (user + system) and resident bytes of a process, from
//  /proc; zeros where it cannot be read.
void processUsage(pid_t pid, double& cpuSeconds, double& residentBytes)
{
    cpuSeconds = 0;
    residentBytes = 0;
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
    // The command name, in parentheses, may hold spaces: fields follow the
    // last ')', the state first; utime and stime are the 12th and 13th
    const std::size_t close = text.rfind(')');
    if (close != std::string::npos)
    {
        std::istringstream fields(text.substr(close + 1));
        std::string field;
        double ticks = 0;
        for (int i = 1; i <= 13 && fields >> field; ++i)
        {
            if (i >= 12) ticks += std::atof(field.c_str());
        }
        cpuSeconds = ticks/double(::sysconf(_SC_CLK_TCK));
    }
    std::ifstream statm("/proc/" + std::to_string(pid) + "/statm");
    double pages = 0, resident = 0;
    if (statm >> pages >> resident)
    {
        residentBytes = resident*double(::sysconf(_SC_PAGESIZE));
    }
}

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

//- Wait until the child's reply starts (or it hangs up), logging a line
//  every `interval` seconds meanwhile. Empty, or why the child is taken
//  for hung: it used more CPU time since its last sign of progress than
//  it allowed itself (expectProgressWithin).
std::string waitLogging
(
    int fd,
    pid_t child,
    const sharedStep* step,
    double interval,
    const std::string& attempt
)
{
    using clock = std::chrono::steady_clock;
    const clock::time_point start = clock::now();
    const auto every = std::chrono::duration_cast<clock::duration>
    (
        std::chrono::duration<double>(interval)
    );
    clock::time_point next = start + every;
    std::string lastStep = "starting";
    for (;;)
    {
        const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>
        (
            next - clock::now()
        ).count();
        pollfd reply{fd, POLLIN, 0};
        const int ready = ::poll(&reply, 1, int(std::max<long long>(0, wait)));
        if (ready > 0 || (ready < 0 && errno != EINTR))
        {
            return {};
        }
        if (ready == 0)
        {
            if (step)
            {
                lastStep = readStep(*step, lastStep);
            }
            double cpu = 0, resident = 0;
            processUsage(child, cpu, resident);
            const double elapsed = std::chrono::duration<double>(clock::now() - start).count();
            const double allowed = step ? overdueAllowance(*step, cpu) : 0;
            if (allowed > 0)
            {
                return msg()
                    << "no sign of progress in " << std::lround(allowed)
                    << " s of CPU time (step: " << lastStep << ", " << std::lround(elapsed)
                    << " s so far): stopped as hung";
            }
            logMesherLine
            (
                msg() << attempt << ": " << std::lround(elapsed) << " s so far, CPU "
                    << std::lround(cpu) << " s, " << std::lround(resident/(1024*1024))
                    << " MiB, step: " << lastStep
            );
            next += every;
        }
    }
}

// All n bytes through move(at, count), a read or a write that may move
// fewer than count bytes from offset `at` on: again where it stopped, also
// after a signal interrupted it. False at an error or the end of the
// stream. One loop for both directions, so that they end alike.
template<class Move>
bool moveAll(std::size_t n, const Move& move)
{
    std::size_t done = 0;
    while (done < n)
    {
        const ssize_t moved = move(done, n - done);
        if (moved < 0 && errno == EINTR) continue;
        if (moved <= 0) return false;
        done += std::size_t(moved);
    }
    return true;
}

bool writeAll(int fd, const void* data, std::size_t n)
{
    const char* p = static_cast<const char*>(data);
    return moveAll
    (
        n,
        [&](std::size_t at, std::size_t count)
        {
            // A socket (the request) whose reader died fails here, not by
            // SIGPIPE, which would end the caller
            ssize_t w = ::send(fd, p + at, count, MSG_NOSIGNAL);
            if (w < 0 && errno == ENOTSOCK) w = ::write(fd, p + at, count);
            return w;
        }
    );
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
    return moveAll
    (
        n,
        [&](std::size_t at, std::size_t count) { return ::read(fd, p + at, count); }
    );
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

// The request of a fresh mesher process (meshInChildProcess with a
// VolumeMesher): what it meshes and how, in the order written

bool writeString(int fd, const std::string& text)
{
    return writeArray(fd, std::vector<char>(text.begin(), text.end()));
}

bool readString(int fd, std::string& text)
{
    std::vector<char> chars;
    if (!readArray(fd, chars)) return false;
    text.assign(chars.begin(), chars.end());
    return true;
}

template<class T>
bool writeValue(int fd, const T& x)
{
    return writeAll(fd, &x, sizeof(T));
}

template<class T>
bool readValue(int fd, T& x)
{
    return readAll(fd, &x, sizeof(T));
}

struct mesherRequest
{
    std::string mesher;
    std::vector<point3> points;
    std::vector<triVerts> triangles;
    volumeMeshParameters parameters;
};

// Every field of a request through pipe, in the one order that the
// parent writes and the child reads them: pipe(x) writes or reads x as
// its type travels (a string, an array or a value), pipe.resize sizes a
// list being read (a writer's does nothing)
template<class Pipe, class Request>
bool transferRequest(const Pipe& pipe, Request& r)
{
    auto& p = r.parameters;
    std::uint64_t nRegions = p.regions.size();
    bool ok =
        pipe(r.mesher) && pipe(r.points) && pipe(r.triangles)
     && pipe(p.maxCellSize) && pipe(p.grading)
     && pipe(p.optimisationSteps) && pipe(p.threads) && pipe(p.pointOrder)
     && pipe(p.what) && pipe(p.interfaceTriangles)
     && pipe(nRegions);
    pipe.resize(p.regions, ok ? nRegions : 0);
    for (auto& g : p.regions)
    {
        ok = ok
         && pipe(g.name) && pipe(g.type)
         && pipe(g.min) && pipe(g.max) && pipe(g.centre)
         && pipe(g.point1) && pipe(g.point2)
         && pipe(g.radius) && pipe(g.size);
    }
    return ok;
}

struct requestWriter
{
    int fd;
    bool operator()(const std::string& s) const { return writeString(fd, s); }
    template<class T>
    bool operator()(const std::vector<T>& v) const { return writeArray(fd, v); }
    template<class T>
    bool operator()(const T& x) const { return writeValue(fd, x); }
    template<class T>
    void resize(const std::vector<T>&, std::uint64_t) const {}
};

struct requestReader
{
    int fd;
    bool operator()(std::string& s) const { return readString(fd, s); }
    template<class T>
    bool operator()(std::vector<T>& v) const { return readArray(fd, v); }
    template<class T>
    bool operator()(T& x) const { return readValue(fd, x); }
    template<class T>
    void resize(std::vector<T>& v, std::uint64_t n) const { v.resize(n); }
};

bool writeRequest(int fd, const mesherRequest& r)
{
    return transferRequest(requestWriter{fd}, r);
}

bool readRequest(int fd, mesherRequest& r)
{
    return transferRequest(requestReader{fd}, r);
}

// The executable that meshers run in, fresh (meshInFreshProcesses); empty:
// they run in a fork of the caller
std::string freshProcessExecutable;

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

} // End anonymous namespace


void pmsh::logMesherLine(const std::string& line)
{
    // Flushed once, prefix included: the lines of ranks that print at the
    // same time do not cut into each other
    const std::ios_base::fmtflags flags = std::cout.flags();
    std::cout.unsetf(std::ios_base::unitbuf);
    Foam::Pout<< "    " << line.c_str() << Foam::endl;
    std::cout.flags(flags);
}


double pmsh::progressInterval()
{
    const char* name = "PMSH_PROGRESS_INTERVAL";
    const char* value = std::getenv(name);
    if (!value || !*value)
    {
        return 30;
    }
    char* end = nullptr;
    const double seconds = std::strtod(value, &end);
    if (*end || !(seconds > 0) || !std::isfinite(seconds))
    {
        throw FatalError
        (
            msg() << "The environment variable " << name << " is '" << value
                << "': valid values are seconds above 0 between progress lines"
                << " of stage 4 (unset: 30)",
            "pmsh::progressInterval"
        );
    }
    return seconds;
}


namespace
{

//- The common part of both ways to mesh in a child: fork, make the child
//  die with its parent, let it start (inChild: never returns), hand it its
//  input (inParent), log progress while it works, and read its result.
//  The child writes its reply to the fd it is given.
pmsh::TetMesh runInChild
(
    const std::string& what,
    const std::string& attempt,
    const std::function<void(int replyFd, const sharedStepPage& step)>& inChild,
    const std::function<void()>& inParent
)
{
    using namespace pmsh;
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
        waitLogging(fds[0], child, step.get(), interval, attempt.empty() ? what : attempt);
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

} // End anonymous namespace


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
            childMain(replyFd, work);
        },
        [] {}
    );
}


const char* const pmsh::mesherChildOption = "-pmshMesherChild";


void pmsh::meshInFreshProcesses()
{
    std::vector<char> path(4096);
    const ssize_t n = ::readlink("/proc/self/exe", path.data(), path.size() - 1);
    if (n <= 0)
    {
        throw FatalError
        (
            msg() << "Cannot read /proc/self/exe: " << std::strerror(errno)
                << " (the volume meshers run in fresh processes of pmshFoam)",
            "pmsh::meshInFreshProcesses"
        );
    }
    freshProcessExecutable.assign(path.data(), std::size_t(n));
}


pmsh::TetMesh pmsh::meshInChildProcess
(
    const VolumeMesher& mesher,
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const volumeMeshParameters& parameters,
    const std::string& attempt
)
{
    if (freshProcessExecutable.empty() || !mesher.dependsOnTheHeap())
    {
        return meshInChildProcess
        (
            [&] { return mesher.mesh(surfacePoints, surfaceTriangles, parameters); },
            parameters.what, attempt
        );
    }

    int request[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM, 0, request) != 0)
    {
        throw FatalError
        (
            msg() << "Cannot create a socket pair: " << std::strerror(errno),
            "pmsh::meshInChildProcess"
        );
    }
    TetMesh result;
    try
    {
        result = runInChild
        (
            parameters.what, attempt,
            [&](int replyFd, const sharedStepPage& step)
            {
                ::close(request[0]);
                const std::string exe = freshProcessExecutable;
                const std::string fds[3] =
                {
                    std::to_string(request[1]), std::to_string(replyFd),
                    std::to_string(step.fd())
                };
                const char* argv[] =
                {
                    exe.c_str(), mesherChildOption,
                    fds[0].c_str(), fds[1].c_str(), fds[2].c_str(), nullptr
                };
                ::execv(exe.c_str(), const_cast<char* const*>(argv));
                std::fprintf
                (
                    stderr, "Cannot run %s for the volume mesher: %s\n",
                    exe.c_str(), std::strerror(errno)
                );
            },
            [&]
            {
                ::close(request[1]);
                // A child that dies before reading it all is told by its
                // exit status, not by this write
                writeRequest
                (
                    request[0],
                    {mesher.name(), surfacePoints, surfaceTriangles, parameters}
                );
                ::close(request[0]);
            }
        );
    }
    catch (...)
    {
        ::close(request[0]);
        ::close(request[1]);
        throw;
    }
    return result;
}


int pmsh::mesherChildMain(int argc, char* argv[])
{
    if (argc != 5)
    {
        std::fprintf
        (
            stderr, "%s %s: meant for pmshFoam itself (request, reply and step fds)\n",
            argv[0], mesherChildOption
        );
        return 1;
    }
    const int requestFd = std::atoi(argv[2]);
    const int replyFd = std::atoi(argv[3]);
    reportStepsTo(sharedStepPage::mapStep(std::atoi(argv[4])));
    mesherRequest request;
    const bool complete = readRequest(requestFd, request);
    ::close(requestFd);
    if (!complete)
    {
        return 2;
    }
    const std::unique_ptr<VolumeMesher> mesher = VolumeMesher::New(request.mesher);
    childMain
    (
        replyFd,
        [&] { return mesher->mesh(request.points, request.triangles, request.parameters); }
    );
}
