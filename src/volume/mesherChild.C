/*---------------------------------------------------------------------------*\
  pmshFoam: a VolumeMesher run in a child process (mesherChild.H).
\*---------------------------------------------------------------------------*/

#include "mesherChild.H"
#include "pipeWire.H"
#include "pmshError.H"
#include "streamManip.H"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sys/socket.h>
#include <unistd.h>

namespace
{

using namespace pmsh;
using namespace pmsh::pipeWire;

// The request of a fresh mesher process: what it meshes and how, in the
// order written
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
     && pipe(p.netgenSmoothing) && pipe(p.mendGradients)
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

bool writeRequest(int fd, const mesherRequest& r)
{
    return transferRequest(pipeWriter{fd}, r);
}

bool readRequest(int fd, mesherRequest& r)
{
    return transferRequest(pipeReader{fd}, r);
}

// The executable that meshers run in, fresh (meshInFreshProcesses); empty:
// they run in a fork of the caller
std::string freshProcessExecutable;

} // End anonymous namespace


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
    replyFromChild
    (
        replyFd,
        [&] { return mesher->mesh(request.points, request.triangles, request.parameters); }
    );
}


// ************************************************************************* //
