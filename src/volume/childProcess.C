#include "childProcess.H"
#include "Info.H"
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

//- The step a child is in, in memory shared with its parent: the parent
//  reads it when it logs progress, the child writes it whenever it likes,
//  with no pipe traffic and no thread. The sequence number is odd while
//  the text is being written, so the parent never logs half a step.
struct sharedStep
{
    std::atomic<unsigned> sequence;
    char text[252];
};

// The child's page; nullptr in the parent, where reportMeshingStep does
// nothing
sharedStep* childStep = nullptr;

void writeStep(sharedStep& shared, const std::string& step)
{
    // One writer at a time (a backend may report from a thread of its own)
    static std::mutex writing;
    const std::lock_guard<std::mutex> lock(writing);
    shared.sequence.fetch_add(1, std::memory_order_acq_rel);
    const std::size_t n = std::min(step.size(), sizeof(shared.text) - 1);
    std::memcpy(shared.text, step.data(), n);
    shared.text[n] = 0;
    shared.sequence.fetch_add(1, std::memory_order_acq_rel);
}

// The step, or `previous` when the child is writing it just now
std::string readStep(const sharedStep& shared, const std::string& previous)
{
    const unsigned before = shared.sequence.load(std::memory_order_acquire);
    if (before % 2)
    {
        return previous;
    }
    char text[sizeof(shared.text)];
    std::memcpy(text, shared.text, sizeof(text));
    text[sizeof(text) - 1] = 0;
    std::atomic_thread_fence(std::memory_order_acquire);
    return shared.sequence.load(std::memory_order_relaxed) == before ? text : previous;
}

//- A page of shared memory that outlives the fork in both processes.
class sharedStepPage
{
    sharedStep* page_;
public:
    sharedStepPage()
    :
        page_
        (
            static_cast<sharedStep*>
            (
                ::mmap
                (
                    nullptr, sizeof(sharedStep), PROT_READ | PROT_WRITE,
                    MAP_SHARED | MAP_ANONYMOUS, -1, 0
                )
            )
        )
    {
        if (page_ == MAP_FAILED)
        {
            page_ = nullptr;
            return;
        }
        new (page_) sharedStep();
        writeStep(*page_, "starting");
    }
    ~sharedStepPage()
    {
        if (page_) ::munmap(page_, sizeof(sharedStep));
    }
    sharedStepPage(const sharedStepPage&) = delete;
    sharedStepPage& operator=(const sharedStepPage&) = delete;

    //- nullptr where shared memory was refused: progress without steps
    sharedStep* get() const { return page_; }
};

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
//  every `interval` seconds meanwhile.
void waitLogging
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
            return;
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
            std::ostringstream line;
            line
                << "    " << attempt << ": " << std::lround(elapsed) << " s so far, CPU "
                << std::lround(cpu) << " s, " << std::lround(resident/(1024*1024))
                << " MiB, step: " << lastStep;
            PoutLine(line.str());
            next += every;
        }
    }
}

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


void pmsh::reportMeshingStep(const std::string& step)
{
    if (childStep)
    {
        writeStep(*childStep, step);
    }
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


pmsh::TetMesh pmsh::meshInChildProcess
(
    const std::function<TetMesh()>& work,
    const std::string& what,
    const std::string& attempt
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
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent)
        {
            ::_exit(orphanedExit);
        }
        childStep = step.get();
        ::close(fds[0]);
        childMain(fds[1], work);
    }

    childGuard running(child);
    ::close(fds[1]);
    waitLogging(fds[0], child, step.get(), interval, attempt.empty() ? what : attempt);
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
