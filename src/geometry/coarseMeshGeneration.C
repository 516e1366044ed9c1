/*---------------------------------------------------------------------------*\
  pmshFoam: stage 1, the coarse mesh (see coarseMeshGeneration.H).
\*---------------------------------------------------------------------------*/

#include "coarseMeshGeneration.H"
#include "failTogether.H"
#include "partitionVolume.H"

#include <algorithm>
#include <thread>

#include <sched.h>

namespace
{

using namespace pmsh;

//- While it lives, this thread (and the processes it forks) may run on
//  every CPU of the machine. mpirun binds each rank to a core or socket;
//  while the master meshes alone the other ranks sleep
//  (masterWorksOthersSleep), so their cores are free for its threads.
class wholeMachineAffinity
{
public:

    wholeMachineAffinity()
    :
        saved_(::sched_getaffinity(0, sizeof(original_), &original_) == 0)
    {
        cpu_set_t all;
        CPU_ZERO(&all);
        const unsigned n = std::max(1u, std::thread::hardware_concurrency());
        for (unsigned c = 0; c < n && c < CPU_SETSIZE; ++c)
        {
            CPU_SET(c, &all);
        }
        // Best effort: where it is not allowed, the threads share the core
        ::sched_setaffinity(0, sizeof(all), &all);
    }

    ~wholeMachineAffinity()
    {
        if (saved_)
        {
            ::sched_setaffinity(0, sizeof(original_), &original_);
        }
    }

    wholeMachineAffinity(const wholeMachineAffinity&) = delete;
    wholeMachineAffinity& operator=(const wholeMachineAffinity&) = delete;

private:

    cpu_set_t original_;
    bool saved_;
};


//- The master's coarse mesh: Netgen's, or the coarse surface (Netgen's
//  or remeshed) filled by parameters.mesher (with the fallbacks of stage
//  4, on every core).
CoarseMesh meshOnMaster(const Geometry& geometry, const coarseMeshParameters& parameters)
{
    if (parameters.mesher == "netgen" && !geometry.remeshesCoarseSurface(parameters.coarseSurface))
    {
        CoarseMesh coarse = geometry.coarseMesh(parameters);
        coarse.volumeMesher = "netgen";
        return coarse;
    }

    // Each zone is filled on its own: its boundary faces and its side of
    // the faces between zones
    CoarseMesh coarse = geometry.coarseSurface(parameters);
    std::vector<triVerts> triangles;
    std::vector<label> triangleZone;
    for (const coarseBoundaryFace& b : coarse.boundary)
    {
        triangles.push_back(b.v);
        triangleZone.push_back(b.zone);
    }
    for (const coarseZoneFace& f : coarse.zoneFaces)
    {
        triangles.push_back(f.v);
        triangleZone.push_back(f.inside);
        triangles.push_back({f.v[0], f.v[2], f.v[1]});
        triangleZone.push_back(f.outside);
    }
    if (coarse.zones.empty())
    {
        triangleZone.clear();
    }

    volumeMeshParameters p;
    p.maxCellSize = parameters.maxCellSize;
    p.grading = parameters.grading;
    // One thread: multithreaded HXT gives another coarse mesh from run to
    // run, and so another partition and fine mesh (on this shared 2-core
    // machine one thread was not slower: README, "Reproducible meshes")
    p.threads = 1;
    p.what = "the coarse surface";
    p.regions = parameters.regions;

    const wholeMachineAffinity everyCore;
    partitionVolumeResult volume = meshVolumeByZone
    (
        VolumeMesher::NewAll(parameters.mesher), coarse.points, triangles,
        triangleZone, coarse.zones, p, parameters.failedSurfaceFile,
        // Every mesher (hxt and netgen) has just been tried: suggesting
        // coarseMesher netgen would suggest what failed
        "Every volume mesher was tried on it. In system/pmshDict try another"
        " maxCellSize (Netgen's coarse surface is made anew), or look at the"
        " surface written for gaps or walls thinner than its triangles."
    );
    coarse.points = std::move(volume.mesh.points);
    coarse.tets = std::move(volume.mesh.tets);
    coarse.cellZone = std::move(volume.tetZone);
    coarse.volumeMesher = volume.backend;
    return coarse;
}

} // End anonymous namespace


pmsh::CoarseMesh pmsh::generateCoarseMesh
(
    const Communicator& comm,
    const Geometry& geometry,
    const coarseMeshParameters& parameters
)
{
    CoarseMesh coarse;
    failTogether(comm, [&]
    {
        comm.masterWorksOthersSleep([&]
        {
            coarse = meshOnMaster(geometry, parameters);
        });
    });
    broadcastCoarseMesh(comm, coarse);
    return coarse;
}


// ************************************************************************* //
