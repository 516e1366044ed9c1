// Stage 4 backends and their failure handling: every backend keeps the
// surface contract, a failing backend falls back to the other, and a
// partition that fails everywhere leaves its surface as STL and says so.

#include "partitionVolume.H"
#include "childProcess.H"
#include "pmshError.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

using namespace pmsh;

namespace
{

// A closed, outward icosphere (radius 1) refined twice: 162 points
void icosphere(std::vector<point>& pts, std::vector<triFace>& tris)
{
    const double t = (1 + std::sqrt(5.0))/2;
    pts = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    tris = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9},
            {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2},
            {3, 2, 6}, {3, 6, 8}, {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10},
            {8, 6, 7}, {9, 8, 1}};
    for (point& p : pts) p = (1/std::sqrt(magSqr(p)))*p;
    for (int level = 0; level < 2; ++level)
    {
        std::map<std::pair<label, label>, label> mid;
        auto midpoint = [&](label a, label b)
        {
            auto key = std::make_pair(std::min(a, b), std::max(a, b));
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            point m = midPoint(pts[a], pts[b]);
            pts.push_back((1/std::sqrt(magSqr(m)))*m);
            return mid[key] = label(pts.size() - 1);
        };
        std::vector<triFace> finer;
        for (const triFace& f : tris)
        {
            const label ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
            finer.insert(finer.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
        }
        tris = finer;
    }
}

std::string tempFile(const std::string& name)
{
    return (std::filesystem::path(::testing::TempDir()) / name).string();
}

struct envVar
{
    explicit envVar(const char* value) { ::setenv("PMSH_TEST_FAIL_VOLUME_RANK", value, 1); }
    ~envVar() { ::unsetenv("PMSH_TEST_FAIL_VOLUME_RANK"); }
};

} // End anonymous namespace


class volumeBackend : public ::testing::TestWithParam<std::string> {};

TEST_P(volumeBackend, surfaceWithAHoleIsAFatalErrorNotACrash)
{
    std::vector<point> pts;
    std::vector<triFace> tris;
    icosphere(pts, tris);
    tris.pop_back();
    EXPECT_THROW(VolumeMesher::New(GetParam())->mesh(pts, tris, {}), FatalError);
}

TEST_P(volumeBackend, inwardSurfaceIsAFatalError)
{
    std::vector<point> pts;
    std::vector<triFace> tris;
    icosphere(pts, tris);
    for (triFace& t : tris) std::swap(t[1], t[2]);
    EXPECT_THROW(VolumeMesher::New(GetParam())->mesh(pts, tris, {}), FatalError);
}

INSTANTIATE_TEST_SUITE_P(backends, volumeBackend, ::testing::ValuesIn(VolumeMesher::names()));


TEST(partitionVolume, firstAttemptSucceedsWithTheChosenBackend)
{
    std::vector<point> pts;
    std::vector<triFace> tris;
    icosphere(pts, tris);
    for (const std::string& backend : VolumeMesher::names())
    {
        const partitionVolumeResult r =
            meshPartitionVolume(backend, pts, tris, {}, 0, tempFile("unused.stl"));
        EXPECT_EQ(r.backend, backend);
        EXPECT_EQ(r.attempts, 1);
        EXPECT_GT(r.mesh.tets.size(), 0u);
    }
}

TEST(partitionVolume, failingEverywhereWritesTheSurfaceAndNamesPartitionAndFile)
{
    std::vector<point> pts;
    std::vector<triFace> tris;
    icosphere(pts, tris);
    const std::string stl = tempFile("failedPartition3.stl");
    std::filesystem::remove(stl);

    envVar fail("3");
    try
    {
        meshPartitionVolume("netgen", pts, tris, {}, 3, stl);
        FAIL() << "expected FatalError";
    }
    catch (const FatalError& e)
    {
        const std::string m = e.what();
        EXPECT_NE(m.find("partition 3"), std::string::npos) << m;
        EXPECT_NE(m.find(stl), std::string::npos) << m;
        EXPECT_NE(m.find("hxt backend"), std::string::npos) << "no fallback tried:\n" << m;
    }
    // The STL holds the partition's surface, facet for facet
    std::ifstream is(stl);
    ASSERT_TRUE(is.good()) << stl;
    std::size_t facets = 0;
    for (std::string w; is >> w; ) facets += (w == "facet");
    EXPECT_EQ(facets, tris.size());
}

TEST(partitionVolume, aFailingBackendFallsBackToTheOther)
{
    std::vector<point> pts;
    std::vector<triFace> tris;
    icosphere(pts, tris);
    envVar fail("2:netgen");
    const partitionVolumeResult r =
        meshPartitionVolume("netgen", pts, tris, {}, 2, tempFile("z.stl"));
    EXPECT_EQ(r.backend, "hxt");
    EXPECT_EQ(r.attempts, 4);   // netgen as asked, without optimisation, graded, then hxt
    EXPECT_GT(r.mesh.tets.size(), 0u);
}


TEST(partitionVolume, injectedFailureOnlyHitsTheNamedRank)
{
    std::vector<point> pts;
    std::vector<triFace> tris;
    icosphere(pts, tris);
    envVar fail("5");
    EXPECT_NO_THROW(meshPartitionVolume("hxt", pts, tris, {}, 4, tempFile("x.stl")));
    EXPECT_THROW(meshPartitionVolume("hxt", pts, tris, {}, 5, tempFile("y.stl")), FatalError);
}


TEST(partitionVolume, multithreadedHxtGivesAConformingMeshOrFallsBackToOneThread)
{
    std::vector<point> pts;
    std::vector<triFace> tris;
    icosphere(pts, tris);
    volumeMeshParameters p;
    p.threads = 2;
    for (int run = 0; run < 5; ++run)
    {
        const partitionVolumeResult r =
            meshPartitionVolume("hxt", pts, tris, p, 0, tempFile("t.stl"));
        EXPECT_EQ(r.backend, "hxt");
        EXPECT_LE(r.attempts, 2);
    }
}


TEST(meshInChildProcess, returnsTheChildsMeshBitForBit)
{
    std::vector<point> pts;
    std::vector<triFace> tris;
    icosphere(pts, tris);
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
    try
    {
        meshInChildProcess([]() -> TetMesh { std::raise(SIGSEGV); return {}; }, "a test surface");
        FAIL() << "expected FatalError";
    }
    catch (const FatalError& e)
    {
        const std::string m = e.what();
        EXPECT_NE(m.find("crashed on a test surface"), std::string::npos) << m;
        EXPECT_NE(m.find("signal 11"), std::string::npos) << m;
    }
}


TEST(meshInChildProcess, aFatalErrorInTheChildKeepsItsMessage)
{
    try
    {
        meshInChildProcess([]() -> TetMesh { throw FatalError("too many attempts"); }, "x");
        FAIL() << "expected FatalError";
    }
    catch (const FatalError& e)
    {
        EXPECT_EQ(std::string(e.what()), "too many attempts");
    }
}

