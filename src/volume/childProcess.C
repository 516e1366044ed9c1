#include "childProcess.H"
#include "error.H"

#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <sys/wait.h>
#include <unistd.h>

namespace
{

using namespace pmsh;

// The pipe protocol: a status byte (0 result, 1 error), then for a result
// the point and tet counts and arrays, for an error its message.
enum : char { resultFollows = 0, errorFollows = 1 };

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

// Everything the child wrote, until it closed the pipe
std::vector<char> readAll(int fd)
{
    std::vector<char> bytes;
    char buffer[1 << 16];
    for (;;)
    {
        const ssize_t r = ::read(fd, buffer, sizeof(buffer));
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) break;
        bytes.insert(bytes.end(), buffer, buffer + r);
    }
    return bytes;
}

template<class T>
bool readArray(const std::vector<char>& bytes, std::size_t& pos, std::vector<T>& v)
{
    std::uint64_t n = 0;
    if (pos + sizeof(n) > bytes.size()) return false;
    std::memcpy(&n, bytes.data() + pos, sizeof(n));
    pos += sizeof(n);
    if (pos + n*sizeof(T) > bytes.size()) return false;
    v.resize(n);
    std::memcpy(v.data(), bytes.data() + pos, n*sizeof(T));
    pos += n*sizeof(T);
    return true;
}

// Runs in the child: never returns
[[noreturn]] void childMain(int fd, const std::function<TetMesh()>& work)
{
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
    const pid_t child = ::fork();
    if (child < 0)
    {
        ::close(fds[0]);
        ::close(fds[1]);
        throw FatalError(msg() << "Cannot fork: " << std::strerror(errno), function);
    }
    if (child == 0)
    {
        ::close(fds[0]);
        childMain(fds[1], work);
    }

    ::close(fds[1]);
    const std::vector<char> bytes = readAll(fds[0]);   // before waiting: no pipe deadlock
    ::close(fds[0]);
    int status = 0;
    while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {}

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
    std::size_t pos = 1;
    if (!bytes.empty() && bytes[0] == errorFollows)
    {
        std::vector<char> text;
        readArray(bytes, pos, text);
        throw FatalError(std::string(text.begin(), text.end()), function);
    }
    TetMesh result;
    if
    (
        bytes.empty() || bytes[0] != resultFollows
     || !readArray(bytes, pos, result.points) || !readArray(bytes, pos, result.tets)
     || !WIFEXITED(status) || WEXITSTATUS(status) != 0
    )
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
