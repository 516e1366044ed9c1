#include "partitionVolume.H"
#include "childProcess.H"
#include "pmshError.H"

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace
{

using namespace pmsh;

// Test-only fault injection: PMSH_TEST_FAIL_VOLUME_RANK =
// "<rank>[:<backend>][:crash]" makes that rank's attempts (with that backend
// only, if named) fail, or with ":crash" die of SIGSEGV inside the mesher's
// child process, as a crashing Netgen or Gmsh would.
enum class injectedFault { none, failure, crash };

injectedFault injectedFaultFor(int rank, const std::string& backend)
{
    const char* value = std::getenv("PMSH_TEST_FAIL_VOLUME_RANK");
    if (!value)
    {
        return injectedFault::none;
    }
    std::vector<std::string> fields;
    std::istringstream spec(value);
    for (std::string field; std::getline(spec, field, ':');)
    {
        fields.push_back(field);
    }
    const bool crash = !fields.empty() && fields.back() == "crash";
    if (crash)
    {
        fields.pop_back();
    }
    const bool hit =
        !fields.empty() && std::atoi(fields[0].c_str()) == rank
     && (fields.size() < 2 || fields[1] == backend);
    return !hit ? injectedFault::none : crash ? injectedFault::crash : injectedFault::failure;
}

struct attempt
{
    std::string backend;
    volumeMeshParameters parameters;
    std::string change;     // what differs from the first attempt
};

} // End anonymous namespace


void pmsh::writeSurfaceStl
(
    const std::string& fileName,
    const std::string& solidName,
    const std::vector<point>& points,
    const std::vector<triFace>& triangles
)
{
    const std::filesystem::path path(fileName);
    if (path.has_parent_path())
    {
        std::filesystem::create_directories(path.parent_path());
    }
    std::ofstream os(fileName);
    os  << std::setprecision(17) << "solid " << solidName << '\n';
    for (const triFace& t : triangles)
    {
        const vector n = cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
        const double mag = std::sqrt(magSqr(n));
        const double s = mag > 0 ? 1/mag : 0;
        os  << "  facet normal " << s*n[0] << ' ' << s*n[1] << ' ' << s*n[2] << '\n'
            << "    outer loop\n";
        for (label p : t)
        {
            os  << "      vertex " << points[p][0] << ' ' << points[p][1] << ' '
                << points[p][2] << '\n';
        }
        os  << "    endloop\n  endfacet\n";
    }
    os  << "endsolid " << solidName << '\n';
}


pmsh::partitionVolumeResult pmsh::meshPartitionVolume
(
    const std::string& backend,
    const std::vector<point>& surfacePoints,
    const std::vector<triFace>& surfaceTriangles,
    const volumeMeshParameters& parameters,
    int rank,
    const std::string& failedSurfaceFile
)
{
    // The attempts, in order: as asked; single-threaded; without optimisation (Netgen's
    // optimiser is where most of its rare crashes and hangs live); with a
    // tighter interior size; then the other backend
    const std::string other = backend == "netgen" ? "hxt" : "netgen";
    std::vector<attempt> attempts{{backend, parameters, ""}};
    volumeMeshParameters p = parameters;
    if (p.threads > 1)
    {
        // Gmsh 4.8's multithreaded HXT can duplicate interior points
        p.threads = 1;
        attempts.push_back({backend, p, "1 thread"});
    }
    if (p.optimisationSteps > 0)
    {
        p.optimisationSteps = 0;
        attempts.push_back({backend, p, "optimisationSteps 0"});
    }
    p.grading = std::min(p.grading, 0.2);
    attempts.push_back({backend, p, "optimisationSteps 0, grading <= 0.2"});
    attempts.push_back({other, parameters, "the " + other + " backend"});

    std::string failures;
    for (std::size_t a = 0; a < attempts.size(); ++a)
    {
        try
        {
            const injectedFault fault = injectedFaultFor(rank, attempts[a].backend);
            if (fault == injectedFault::failure)
            {
                throw FatalError("failure injected by PMSH_TEST_FAIL_VOLUME_RANK");
            }
            const auto mesher = VolumeMesher::New(attempts[a].backend);
            partitionVolumeResult result;
            result.mesh = meshInChildProcess
            (
                [&]
                {
                    if (fault == injectedFault::crash)
                    {
                        std::raise(SIGSEGV);
                    }
                    return mesher->mesh
                    (
                        surfacePoints, surfaceTriangles, attempts[a].parameters
                    );
                },
                attempts[a].parameters.what
            );
            result.backend = attempts[a].backend;
            result.attempts = int(a) + 1;
            result.nCells = label(result.mesh.tets.size());
            result.failures = failures;
            return result;
        }
        catch (const FatalError& e)
        {
            failures += msg()
                << "\n  attempt " << a + 1 << " (" << attempts[a].backend
                << (attempts[a].change.empty() ? "" : "; " + attempts[a].change)
                << "): " << e.message();
        }
    }

    writeSurfaceStl(failedSurfaceFile, "partition" + std::to_string(rank), surfacePoints, surfaceTriangles);
    throw FatalError
    (
        msg() << "Volume meshing of partition " << rank << " failed in all "
            << attempts.size() << " attempts:" << failures << "\n"
            << "Its surface is written to " << failedSurfaceFile << " for diagnosis.\n"
            << "Try a smaller maxCellSize (a finer coarse mesh) or another"
            << " volumeMesher in system/pmshDict.",
        "meshPartitionVolume"
    );
}
