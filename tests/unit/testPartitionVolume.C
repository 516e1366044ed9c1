// Stage 4 and its failure handling: a failing or crashing mesher falls
// back to the next one, and a partition that fails everywhere leaves its
// surface as STL and says so.

#include "partitionVolume.H"
#include "childProcess.H"
#include "meshingStep.H"
#include "pmshError.H"
#include "testMeshers.H"
#include "testUtilities.H"

#include <gtest/gtest.h>
#include <chrono>
#include <ctime>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace pmsh;
using namespace pmsh::test;

namespace
{

std::string tempFile(const std::string& name)
{
    return (std::filesystem::path(::testing::TempDir()) / name).string();
}

volumeMeshParameters partitionNamed(const std::string& what)
{
    volumeMeshParameters p;
    p.what = what;
    return p;
}

//- Why meshers (in order, with their retries) could not mesh a small
//  sphere (icosphere(1)) with parameters p.
std::string sphereFailures
(
    const std::vector<std::unique_ptr<VolumeMesher>>& meshers,
    const volumeMeshParameters& p
)
{
    const closedSurface sphere = icosphere(1);
    return errorOf([&]
    {
        meshVolumeWithFallbacks
        (
            meshers, sphere.points, sphere.triangles, p,
            tempFile("failedPartition1.stl"), ""
        );
    });
}

//- A failingMesher whose optimiser is not where its failures come from
//  (as HXT's quality pass): its retries keep their optimisation steps.
struct curingOptimiserMesher : failingMesher
{
    bool optimiserMayFail() const override { return false; }
};

} // End anonymous namespace


TEST(partitionVolume, firstAttemptSucceedsWithTheChosenBackend)
{
    const closedSurface sphere = icosphere(2);
    const std::vector<point3>& pts = sphere.points;
    const std::vector<triVerts>& tris = sphere.triangles;
    for (const std::string& backend : VolumeMesher::names())
    {
        const partitionVolumeResult r = meshVolumeWithFallbacks
        (
            VolumeMesher::NewAll(backend), pts, tris, {}, tempFile("unused.stl"), ""
        );
        EXPECT_EQ(r.backend, backend);
        EXPECT_EQ(r.attempts, 1);
        EXPECT_GT(r.mesh.tets.size(), 0u);
    }
}

TEST(partitionVolume, failingEverywhereWritesTheSurfaceAndNamesPartitionAndFile)
{
    const closedSurface sphere = icosphere(2);
    const std::vector<point3>& pts = sphere.points;
    const std::vector<triVerts>& tris = sphere.triangles;
    const std::string stl = tempFile("failedPartition3.stl");
    std::filesystem::remove(stl);

    const std::string m = errorOf([&]
    {
        meshVolumeWithFallbacks
        (
            meshers(std::make_unique<failingMesher>(), std::make_unique<crashingMesher>()),
            pts, tris, partitionNamed("partition 3"), stl, "Try another mesher."
        );
    });
    EXPECT_HAS(m, "Volume meshing of partition 3 failed in all 4 attempts");
    EXPECT_HAS(m, "Try another mesher.");
    EXPECT_HAS(m, "attempt 3 (failing; optimisationSteps 0, grading <= 0.2): cannot mesh");
    EXPECT_HAS(m, "attempt 4 (crashing; the crashing backend)");
    EXPECT_HAS(m, "signal 11");
    EXPECT_HAS(m, stl);

    // The STL holds the partition's surface, facet for facet
    std::ifstream is(stl);
    ASSERT_TRUE(is.good()) << stl;
    std::size_t facets = 0;
    for (std::string w; is >> w; ) facets += (w == "facet");
    EXPECT_EQ(facets, tris.size());
}

TEST(partitionVolume, retriesWithoutARiskyOptimiserAndWithMoreOfACuringOne)
{
    // Netgen's optimiser is where its crashes live: its retry goes without
    // it. HXT's quality pass removes the slivers the contract refuses: its
    // retry gets twice the steps.
    volumeMeshParameters p = partitionNamed("partition 1");
    p.optimisationSteps = 3;
    const std::string risky = sphereFailures(meshers(std::make_unique<failingMesher>()), p);
    EXPECT_HAS(risky, "attempt 2 (failing; optimisationSteps 0)");
    EXPECT_HAS(risky, "attempt 3 (failing; optimisationSteps 0, grading <= 0.2)");
    const std::string curing =
        sphereFailures(meshers(std::make_unique<curingOptimiserMesher>()), p);
    EXPECT_HAS(curing, "attempt 2 (failing; optimisationSteps 6)");
    EXPECT_HAS(curing, "attempt 3 (failing; optimisationSteps 6, grading <= 0.2)");
    EXPECT_FALSE(VolumeMesher::New("hxt")->optimiserMayFail());
    EXPECT_TRUE(VolumeMesher::New("netgen")->optimiserMayFail());
}

TEST(partitionVolume, aFailureWithoutStepsIsRetriedWithStepsNeverTheSameWay)
{
    // optimisationSteps 0 asks for speed; a mesh that failed without steps
    // fails again without them, so every retry and the fallback have the
    // default steps, say so, and no attempt repeats an earlier one
    volumeMeshParameters p = partitionNamed("partition 1");
    p.optimisationSteps = 0;
    const auto failuresOf = [&](std::unique_ptr<VolumeMesher> m)
    {
        return sphereFailures(meshers(std::move(m), std::make_unique<crashingMesher>()), p);
    };
    const int defaultSteps = volumeMeshParameters().optimisationSteps;
    ASSERT_GT(defaultSteps, 0);
    const std::string steps = "optimisationSteps " + std::to_string(defaultSteps);
    for (const std::string& m :
        {
            failuresOf(std::make_unique<failingMesher>()),
            failuresOf(std::make_unique<curingOptimiserMesher>())
        })
    {
        EXPECT_HAS(m, "failed in all 4 attempts");
        EXPECT_HAS(m, "attempt 1 (failing): cannot mesh");
        EXPECT_HAS(m, "attempt 2 (failing; " + steps + "): cannot mesh");
        EXPECT_HAS(m, "attempt 3 (failing; " + steps + ", grading <= 0.2): cannot mesh");
        EXPECT_HAS(m, "attempt 4 (crashing; the crashing backend, " + steps + ")");
    }

    // With threads, the single-threaded retry has the steps too; a grading
    // already at most 0.2 makes no attempt of its own
    p.threads = 2;
    p.grading = 0.1;
    const std::string m = failuresOf(std::make_unique<failingMesher>());
    EXPECT_HAS(m, "failed in all 3 attempts");
    EXPECT_HAS(m, "attempt 2 (failing; 1 thread, " + steps + "): cannot mesh");
    EXPECT_HAS(m, "attempt 3 (crashing; the crashing backend, " + steps + ")");
}

TEST(partitionVolume, aFailingMesherFallsBackToTheNextOne)
{
    const closedSurface sphere = icosphere(2);
    const std::vector<point3>& pts = sphere.points;
    const std::vector<triVerts>& tris = sphere.triangles;
    ::testing::internal::CaptureStdout();
    const partitionVolumeResult r = meshVolumeWithFallbacks
    (
        meshers(std::make_unique<failingMesher>(), VolumeMesher::New("hxt")),
        pts, tris, {}, tempFile("z.stl"), ""
    );
    const std::string log = ::testing::internal::GetCapturedStdout();
    EXPECT_EQ(r.backend, "hxt");
    EXPECT_EQ(r.attempts, 4);   // as asked, without optimisation, graded, then hxt
    EXPECT_HAS(r.failures, "attempt 1 (failing): cannot mesh a closed surface");
    EXPECT_GT(r.mesh.tets.size(), 0u);
    // Each failure is in the log as it happens, with what comes next
    EXPECT_HAS(log, "a closed surface, attempt 1 (failing) failed: ");
    EXPECT_HAS(log, "; attempt 4 (hxt; the hxt backend) next");
}

TEST(partitionVolume, aCrashingMesherFallsBackToTheNextOne)
{
    const closedSurface sphere = icosphere(2);
    const std::vector<point3>& pts = sphere.points;
    const std::vector<triVerts>& tris = sphere.triangles;
    volumeMeshParameters p;
    p.what = "the surface of partition 1";
    const partitionVolumeResult r = meshVolumeWithFallbacks
    (
        meshers(std::make_unique<crashingMesher>(), VolumeMesher::New("netgen")),
        pts, tris, p, tempFile("c.stl"), ""
    );
    EXPECT_EQ(r.backend, "netgen");
    EXPECT_EQ(r.attempts, 4);
    EXPECT_HAS(r.failures, "crashed on the surface of partition 1 (signal 11");
}


TEST(partitionVolume, aMesherThatBreaksWithThreadsIsRetriedWithOneThread)
{
    // Gmsh 4.8's HXT now and then duplicates an interior point when
    // multithreaded: here on every multithreaded call, so the mesh must
    // come from the single-threaded retry
    const closedSurface sphere = icosphere(2);
    volumeMeshParameters p;
    p.threads = 2;
    p.what = "partition 2";
    const partitionVolumeResult r = meshVolumeWithFallbacks
    (
        meshers(std::make_unique<duplicatesAPointWithThreadsMesher>()),
        sphere.points, sphere.triangles, p, tempFile("t.stl"), ""
    );
    EXPECT_EQ(r.attempts, 2);
    EXPECT_HAS(r.failures, "attempt 1 (duplicatesAPointWithThreads): ");
    EXPECT_HAS(r.failures, "partition 2 is not conforming");
    EXPECT_GT(r.mesh.tets.size(), 0u);
}


TEST(partitionVolume, multithreadedHxtEndsWithAConformingMeshWithinTwoAttempts)
{
    // The real HXT with 2 threads: its mesh passes VolumeMesher::mesh's
    // contract check, at the latest on the single-threaded retry
    const closedSurface sphere = icosphere(2);
    volumeMeshParameters p;
    p.threads = 2;
    for (int run = 0; run < 5; ++run)
    {
        const partitionVolumeResult r = meshVolumeWithFallbacks
        (
            VolumeMesher::NewAll("hxt"), sphere.points, sphere.triangles, p,
            tempFile("t.stl"), ""
        );
        EXPECT_EQ(r.backend, "hxt");
        EXPECT_LE(r.attempts, 2);
    }
}


TEST(meshInChildProcess, returnsTheChildsMeshBitForBit)
{
    const closedSurface sphere = icosphere(2);
    const std::vector<point3>& pts = sphere.points;
    const std::vector<triVerts>& tris = sphere.triangles;
    const TetMesh direct = VolumeMesher::New("netgen")->mesh(pts, tris, {});
    const TetMesh child = meshInChildProcess
    (
        [&] { return VolumeMesher::New("netgen")->mesh(pts, tris, {}); }, "an icosphere"
    );
    EXPECT_EQ(child.points, direct.points);
    EXPECT_EQ(child.tets, direct.tets);
}


TEST(meshInChildProcess, aCrashInTheChildIsAFatalErrorNamingTheSignal)
{
    const std::string m = errorOf([]
    {
        meshInChildProcess([]() -> TetMesh { std::raise(SIGSEGV); return {}; }, "a test surface");
    });
    EXPECT_HAS(m, "crashed on a test surface");
    EXPECT_HAS(m, "signal 11");
}


TEST(meshInChildProcess, aFatalErrorInTheChildKeepsItsMessage)
{
    const std::string m = errorOf([]
    {
        meshInChildProcess([]() -> TetMesh { throw FatalError("too many attempts"); }, "x");
    });
    EXPECT_EQ(m, "too many attempts");
}



namespace
{

//- Sets an environment variable while it lives.
class scopedEnvironment
{
    std::string name_;
public:
    scopedEnvironment(const std::string& name, const std::string& value)
    :
        name_(name)
    {
        ::setenv(name.c_str(), value.c_str(), 1);
    }
    ~scopedEnvironment()
    {
        ::unsetenv(name_.c_str());
    }
};

} // End anonymous namespace


TEST(meshInChildProcess, logsProgressWithTheAttemptAndTheChildsStep)
{
    const scopedEnvironment interval("PMSH_PROGRESS_INTERVAL", "0.25");
    ::testing::internal::CaptureStdout();
    meshInChildProcess
    (
        []
        {
            reportMeshingStep("filling the test volume");
            ::usleep(1300*1000);
            return TetMesh();
        },
        "a test surface", "partition 7, attempt 2 (hxt; 1 thread)"
    );
    const std::string out = ::testing::internal::GetCapturedStdout();
    const std::regex line
    (
        "    partition 7, attempt 2 \\(hxt; 1 thread\\): (\\d+) s so far, CPU \\d+ s,"
        " \\d+ MiB, step: (starting|filling the test volume)\n"
    );
    std::vector<std::string> steps;
    for (std::sregex_iterator m(out.begin(), out.end(), line), end; m != end; ++m)
    {
        steps.push_back((*m)[2]);
    }
    // 5 intervals in 1.3 s; a loaded machine may start the child late
    EXPECT_GE(steps.size(), 3u) << out;
    EXPECT_LE(steps.size(), 6u) << out;
    ASSERT_FALSE(steps.empty());
    EXPECT_EQ(steps.back(), "filling the test volume") << out;
}


namespace
{

double processCpu()
{
    timespec now{};
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return double(now.tv_sec) + 1e-9*double(now.tv_nsec);
}

//- Burn `seconds` of CPU time, calling tick() every 10 ms of it
template<class Tick>
void burnCpu(double seconds, const Tick& tick)
{
    const double start = processCpu();
    double next = start;
    volatile double x = 1;
    while (processCpu() < start + seconds)
    {
        for (int i = 0; i < 10000; ++i) x = x*1.0000001 + 1e-9;
        if (processCpu() >= next)
        {
            tick();
            next += 0.01;
        }
    }
}

} // End anonymous namespace


TEST(meshInChildProcess, aChildThatShowsNoProgressWithinWhatItAllowedItselfIsStoppedAsHung)
{
    // As Gmsh 4.8's HXT walking in circles: busy, and never done
    const scopedEnvironment interval("PMSH_PROGRESS_INTERVAL", "0.1");
    const auto start = std::chrono::steady_clock::now();
    try
    {
        meshInChildProcess
        (
            []
            {
                reportMeshingStep("walking in circles");
                expectProgressWithin(0.3);
                burnCpu(30, [] {});     // unstopped, it ends: the test fails
                return TetMesh();
            },
            "a test surface"
        );
        FAIL() << "a child that never shows progress again was not stopped";
    }
    catch (const FatalError& e)
    {
        EXPECT_NE(e.message().find("a test surface"), std::string::npos) << e.message();
        EXPECT_NE(e.message().find("stopped as hung"), std::string::npos) << e.message();
        EXPECT_NE(e.message().find("walking in circles"), std::string::npos) << e.message();
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 20) << "stopped long after its allowance";
}


TEST(meshInChildProcess, aChildThatKeepsShowingProgressIsNotStopped)
{
    // 1.5 s of CPU in all, five times its allowance, but progress every
    // 10 ms of it; then no bound for the rest
    const scopedEnvironment interval("PMSH_PROGRESS_INTERVAL", "0.1");
    const TetMesh m = meshInChildProcess
    (
        []
        {
            burnCpu(1.5, [] { expectProgressWithin(0.3); });
            expectProgressWithin(0);
            burnCpu(0.5, [] {});
            TetMesh done;
            done.points = {{1, 2, 3}};
            return done;
        },
        "a test surface"
    );
    EXPECT_EQ(m.points.size(), 1u);
}


TEST(meshInChildProcess, aWrongProgressIntervalNamesTheVariable)
{
    const scopedEnvironment interval("PMSH_PROGRESS_INTERVAL", "soon");
    const std::string m = errorOf([] { meshInChildProcess([] { return TetMesh(); }, "x"); });
    EXPECT_HAS(m, "PMSH_PROGRESS_INTERVAL is 'soon'");
    EXPECT_HAS(m, "seconds above 0");
}


TEST(meshInChildProcess, whatTheChildPrintsIsNotLostWhenItEndsOrCrashes)
{
    // Captured, stdout is a file: fully buffered unless the child flushes
    ::testing::internal::CaptureStdout();
    meshInChildProcess
    (
        [] { std::printf("the mesher's last words"); return TetMesh(); }, "x"
    );
    EXPECT_THROW
    (
        meshInChildProcess
        (
            []() -> TetMesh
            {
                std::printf("a line before the crash\n");
                std::raise(SIGSEGV);
                return {};
            },
            "y"
        ),
        FatalError
    );
    const std::string out = ::testing::internal::GetCapturedStdout();
    EXPECT_NE(out.find("the mesher's last words"), std::string::npos) << out;
    EXPECT_NE(out.find("a line before the crash"), std::string::npos) << out;
}


TEST(meshInChildProcess, theChildDiesWithItsParentWhenTheParentIsKilled)
{
    // This test process adopts its orphaned grandchildren, so that it can
    // see how the mesher child ended once its parent is gone
    ASSERT_EQ(::prctl(PR_SET_CHILD_SUBREAPER, 1), 0);
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    const pid_t parent = ::fork();
    ASSERT_GE(parent, 0);
    if (parent == 0)
    {
        ::close(fds[0]);
        meshInChildProcess
        (
            [&]() -> TetMesh
            {
                const pid_t me = ::getpid();
                (void)!::write(fds[1], &me, sizeof(me));
                for (;;) ::pause();
            },
            "a surface that takes forever"
        );
        ::_exit(0);
    }
    ::close(fds[1]);
    pid_t child = 0;
    ASSERT_EQ(::read(fds[0], &child, sizeof(child)), ssize_t(sizeof(child)));
    ::close(fds[0]);

    ::kill(parent, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(parent, &status, 0), parent);

    // The child, adopted by this process, must end by itself within 10 s
    pid_t ended = 0;
    for (int i = 0; i < 1000 && ended == 0; ++i)
    {
        ended = ::waitpid(child, &status, WNOHANG);
        if (ended == 0) ::usleep(10*1000);
    }
    if (ended == 0)
    {
        ::kill(child, SIGKILL);
        ::waitpid(child, &status, 0);
    }
    ::prctl(PR_SET_CHILD_SUBREAPER, 0);
    ASSERT_EQ(ended, child) << "the mesher child outlived its killed parent";
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
}
