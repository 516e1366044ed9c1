#include "coarseMesh.H"
#include "Geometry.H"
#include "pmshError.H"
#include "failTogether.H"
#include "partitionVolume.H"
#include "tetFaceMatching.H"

#include <algorithm>
#include <numeric>
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


//- The master's coarse mesh: Netgen's, or Netgen's surface filled by
//  parameters.mesher (with the fallbacks of stage 4, on every core).
CoarseMesh meshOnMaster(const Geometry& geometry, const coarseMeshParameters& parameters)
{
    if (parameters.mesher == "netgen")
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


void pmsh::releaseGeometry(CoarseMesh& coarse)
{
    // Swapped out, not cleared: clear() keeps the capacity
    std::vector<point3>().swap(coarse.points);
    std::vector<tetVerts>().swap(coarse.tets);
    std::vector<coarseBoundaryFace>().swap(coarse.boundary);
    std::vector<label>().swap(coarse.cellZone);
    std::vector<coarseZoneFace>().swap(coarse.zoneFaces);
}


namespace
{

//- Broadcast the master's names as one '\0'-separated buffer.
void broadcastNames(const pmsh::Communicator& comm, std::vector<std::string>& names)
{
    std::vector<char> buffer;
    for (const std::string& name : names)
    {
        buffer.insert(buffer.end(), name.begin(), name.end());
        buffer.push_back('\0');
    }
    comm.broadcast(buffer);
    names.clear();
    for (auto it = buffer.begin(); it != buffer.end(); )
    {
        auto end = std::find(it, buffer.end(), '\0');
        names.emplace_back(it, end);
        it = (end == buffer.end()) ? end : end + 1;
    }
}

} // End anonymous namespace


void pmsh::broadcastCoarseMesh(const Communicator& comm, CoarseMesh& coarse)
{
    comm.broadcast(coarse.points);
    comm.broadcast(coarse.tets);
    comm.broadcast(coarse.boundary);
    comm.broadcast(coarse.cellZone);
    comm.broadcast(coarse.zoneFaces);
    broadcastNames(comm, coarse.zones);
    comm.broadcast(coarse.periodicPatches);
    comm.broadcast(coarse.periodicPoints);

    // Patch names only: the types come from pmshDict, which every rank reads
    std::vector<std::string> names;
    for (const meshPatch& p : coarse.patches)
    {
        names.push_back(p.name);
    }
    broadcastNames(comm, names);
    coarse.patches.clear();
    for (const std::string& name : names)
    {
        coarse.patches.push_back({name});
    }
}


pmsh::zoneFaceIndex::zoneFaceIndex(const CoarseMesh& coarse)
{
    keys_.reserve(coarse.zoneFaces.size());
    for (std::size_t i = 0; i < coarse.zoneFaces.size(); ++i)
    {
        triVerts f = coarse.zoneFaces[i].v;
        std::sort(f.begin(), f.end());
        keys_.emplace_back(f, label(i));
    }
    std::sort(keys_.begin(), keys_.end());
}


pmsh::label pmsh::zoneFaceIndex::find(const triVerts& face) const
{
    if (keys_.empty())
    {
        return -1;
    }
    triVerts f = face;
    std::sort(f.begin(), f.end());
    const auto it = std::lower_bound
    (
        keys_.begin(), keys_.end(), std::make_pair(f, label(-1))
    );
    return it != keys_.end() && it->first == f ? it->second : -1;
}


std::vector<pmsh::faceNeighbours> pmsh::coarseFaceNeighbours(const CoarseMesh& coarse)
{
    std::vector<triVerts> boundary(coarse.boundary.size());
    for (std::size_t b = 0; b < boundary.size(); ++b)
    {
        boundary[b] = coarse.boundary[b].v;
    }
    const tetFaceMatch match = fittingTetFaces
    (
        coarse.nPoints(), coarse.tets, boundary,
        "The coarse mesh and its boundary do not fit together", "coarseFaceNeighbours"
    );

    std::vector<faceNeighbours> neighbours(coarse.nCells());
    for (faceId id = 0; id < match.nTetFaces; ++id)
    {
        neighbours[id/4][id % 4] = match.acrossOf(id);
    }
    return neighbours;
}


pmsh::coarsePointCells::coarsePointCells(const CoarseMesh& coarse)
:
    offsets_(coarse.nPoints() + 1, 0)
{
    for (const tetVerts& t : coarse.tets)
    {
        for (label p : t)
        {
            ++offsets_[p + 1];
        }
    }
    std::partial_sum(offsets_.begin(), offsets_.end(), offsets_.begin());
    cells_.resize(offsets_.back());
    std::vector<label> fill(offsets_.begin(), offsets_.end() - 1);
    for (label c = 0; c < coarse.nCells(); ++c)
    {
        for (label p : coarse.tets[c])
        {
            cells_[fill[p]++] = c;
        }
    }
}
