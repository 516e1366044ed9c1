// Stage 4 across MPI ranks, as pmshFoam runs it (meshVolumeWithFallbacks in
// failTogether): a rank whose meshers all fail stops every rank together
// with its own error, and a mesher dying of SIGSEGV in one rank's child
// process is a failed attempt there, replaced by the next mesher, while
// the MPI job and the other ranks go on.

#include "mpiTestMain.H"
#include "failTogether.H"
#include "partitionVolume.H"
#include "testMeshers.H"
#include "testUtilities.H"

#include <filesystem>

using namespace pmsh;
using namespace pmsh::test;

namespace
{

//- meshVolumeWithFallbacks on this rank's copy of an icosphere, in failTogether.
partitionVolumeResult meshTogether
(
    const std::vector<std::unique_ptr<VolumeMesher>>& meshers,
    const std::string& failedSurfaceFile
)
{
    const Communicator& comm = world();
    const closedSurface s = icosphere(1);
    volumeMeshParameters p;
    p.what = "partition " + std::to_string(comm.rank());
    partitionVolumeResult result;
    failTogether(comm, [&]
    {
        result = meshVolumeWithFallbacks
        (
            meshers, s.points, s.triangles, p, failedSurfaceFile, ""
        );
    });
    return result;
}

} // End anonymous namespace


TEST(parallelVolumeMeshing, oneRankFailingStopsEveryRankTogether)
{
    const Communicator& comm = world();
    const int failing = comm.size() - 1;
    const tempDir dir("volumeFailure");
    const std::string stl = dir/"failedPartition.stl";

    std::string error;
    bool printed = false;
    try
    {
        meshTogether
        (
            comm.rank() == failing
          ? meshers(std::make_unique<failingMesher>())
          : VolumeMesher::NewAll("netgen"),
            stl
        );
    }
    catch (const collectiveFailure& e)
    {
        error = e.message();
        printed = e.print();
    }
    ASSERT_FALSE(error.empty()) << "rank " << comm.rank() << " went on";

    if (comm.rank() == failing)
    {
        // Its own error, printed, and its surface left for diagnosis
        EXPECT_HAS(error, "Volume meshing of partition " + std::to_string(failing));
        EXPECT_TRUE(printed);
        EXPECT_TRUE(std::filesystem::exists(stl));
    }
    else
    {
        // The others meshed, then stopped; only the master says why
        EXPECT_HAS(error, "another rank failed");
        EXPECT_EQ(printed, comm.master());
        EXPECT_FALSE(std::filesystem::exists(stl));
    }
}


TEST(parallelVolumeMeshing, aMesherCrashingOnOneRankIsReplacedThere)
{
    const Communicator& comm = world();
    const int crashing = comm.size() - 1;
    const tempDir dir("volumeCrash");

    partitionVolumeResult r;
    ASSERT_NO_THROW
    (
        r = meshTogether
        (
            comm.rank() == crashing
          ? meshers(std::make_unique<crashingMesher>(), VolumeMesher::New("netgen"))
          : VolumeMesher::NewAll("hxt"),
            dir/"unused.stl"
        )
    );
    if (comm.rank() == crashing)
    {
        EXPECT_EQ(r.backend, "netgen");
        EXPECT_GT(r.attempts, 1);
        EXPECT_HAS
        (
            r.failures,
            "crashed on partition " + std::to_string(crashing) + " (signal 11"
        );
    }
    else
    {
        EXPECT_EQ(r.backend, "hxt");
        EXPECT_EQ(r.attempts, 1);
    }
    EXPECT_GT(r.nCells, 0);
}
