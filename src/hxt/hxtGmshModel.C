/*---------------------------------------------------------------------------*\
  pmshFoam: HXT through Gmsh's API and model (hxtBackends.H), the way in
  when Gmsh is not 4.8. All contact with Gmsh's API is in this file; every
  Gmsh quirk met is noted where it is handled.
\*---------------------------------------------------------------------------*/

#include "hxtBackends.H"
#include "pmshError.H"
#include "meshingStep.H"

#include <gmsh.h>

#include <malloc.h>

#include <algorithm>
#include <cstring>
#include <mutex>
#include <numeric>
#include <string>

namespace
{

using namespace pmsh;

// Gmsh keeps one global model and option set per process: initialise once
// and serialise all use (pmshFoam meshes one partition per rank at a time;
// the lock documents the constraint for anyone calling from threads).
std::mutex gmshMutex;

void initialiseGmsh()
{
    static std::once_flag once;
    std::call_once(once, []
    {
        // readConfigFiles = false: no ~/.gmshrc may change the meshing
        gmsh::initialize(0, nullptr, false);
        gmsh::option::setNumber("General.Terminal", 0);
    });
}


// Gmsh 4.8's API reports errors by throwing a std::string (not a
// std::exception); its log holds the detail.
[[noreturn]] void gmshFailed(const std::string& error, const std::string& what)
{
    std::vector<std::string> log;
    gmsh::logger::get(log);
    gmsh::logger::stop();
    msg m;
    m   << "Gmsh HXT could not mesh the volume of " << what << ": " << error;
    std::size_t shown = 0;
    for (auto it = log.rbegin(); it != log.rend() && shown < 5; ++it)
    {
        if (it->rfind("Error", 0) == 0 || it->rfind("Warning", 0) == 0)
        {
            m   << "\n    Gmsh: " << *it;
            ++shown;
        }
    }
    throw FatalError(m, "pmsh::gmshModelMesh");
}


//- While it lives, Gmsh's mesh size is at most the size field's
//  (hxtSizeField). Quirk: the callback is global to Gmsh, and it would
//  outlive the field: it is removed with the guard. Its arguments changed
//  in Gmsh 4.9 (the size Gmsh found comes last).
class sizeCallbackGuard
{
public:

    explicit sizeCallbackGuard(const ng::sizeField& sizes)
    {
        const ng::sizeField* field = &sizes;
#if GMSH_API_VERSION_MAJOR == 4 && GMSH_API_VERSION_MINOR < 9
        gmsh::model::mesh::setSizeCallback
        (
            [field](int, int, double x, double y, double z)
            {
                return (*field)({x, y, z});
            }
        );
#else
        gmsh::model::mesh::setSizeCallback
        (
            [field](int, int, double x, double y, double z, double lc)
            {
                return std::min(lc, (*field)({x, y, z}));
            }
        );
#endif
    }

    ~sizeCallbackGuard()
    {
        gmsh::model::mesh::removeSizeCallback();
    }

    sizeCallbackGuard(const sizeCallbackGuard&) = delete;
    sizeCallbackGuard& operator=(const sizeCallbackGuard&) = delete;
};


//- Gmsh's model of one partition's volume, built and read back in named
//  steps. Quirk: Gmsh 4.8 orders the surface's nodes by address before HXT
//  sees them (meshGRegionHxt.cpp), so its mesh depends on the heap's
//  history: every container lives as long as the model, declared in the
//  order the steps fill it, so that the steps allocate and free as one
//  function would.
class hxtModel
{
    const std::vector<point3>& surfacePoints_;
    const std::vector<triVerts>& surfaceTriangles_;
    const shellVolumes& volumes_;
    const std::size_t nSurface_;

    //- Gmsh's discrete surface of each shell
    std::vector<int> shellSurface_;
    std::vector<std::size_t> tagOfPoint_;
    //- Gmsh's nodes, and the index in the mesh of each node tag
    std::vector<std::size_t> nodeTags_;
    std::vector<double> coords_, parametric_;
    std::vector<std::size_t> newTags_;
    std::vector<label> index_;
    std::vector<std::size_t> noElementTags_, elementNodes_;

public:

    hxtModel
    (
        const std::vector<point3>& surfacePoints,
        const std::vector<triVerts>& surfaceTriangles,
        const shellVolumes& volumes
    )
    :
        surfacePoints_(surfacePoints),
        surfaceTriangles_(surfaceTriangles),
        volumes_(volumes),
        nSurface_(surfacePoints.size())
    {}

    //- One discrete surface per closed shell: a single surface loop around
    //  a surface of several shells (a partition around the body of a
    //  body-in-box domain) makes HXT fail. Node tags, not coordinates, map
    //  Gmsh's nodes back to ours: surface point surfacePointOfTag[tag - 1].
    //  Quirk: Gmsh renumbers the nodes unless their tags run 1..n without
    //  gaps, so each shell's points get the next tags in turn.
    void addShellSurfaces(std::vector<label>& surfacePointOfTag)
    {
        const auto& shells = volumes_.shells;
        shellSurface_.resize(shells.size());
        tagOfPoint_.assign(nSurface_, 0);
        surfacePointOfTag.reserve(nSurface_);
        for (std::size_t s = 0; s < shells.size(); ++s)
        {
            shellSurface_[s] = gmsh::model::addDiscreteEntity(2);
            std::vector<std::size_t> tags;
            std::vector<double> xyz;
            std::vector<std::size_t> triangleNodes;
            triangleNodes.reserve(3*shells[s].size());
            for (label i : shells[s])
            {
                for (label p : surfaceTriangles_[i])
                {
                    if (tagOfPoint_[p] == 0)
                    {
                        surfacePointOfTag.push_back(p);
                        tagOfPoint_[p] = surfacePointOfTag.size();
                        tags.push_back(tagOfPoint_[p]);
                        xyz.insert(xyz.end(), surfacePoints_[p].begin(), surfacePoints_[p].end());
                    }
                    triangleNodes.push_back(tagOfPoint_[p]);
                }
            }
            gmsh::model::mesh::addNodes(2, shellSurface_[s], tags, xyz);
            gmsh::model::mesh::addElementsByType(shellSurface_[s], 2, {}, triangleNodes);
        }
    }

    //- One volume per outer shell with its holes. Quirk: HXT leaves a
    //  discrete volume (addDiscreteEntity(3)) empty ("No elements in volume");
    //  a built-in-kernel volume bounded by surface loops on the discrete
    //  surfaces is meshed (the first loop its outside, the others its holes),
    //  and the surface mesh is kept as it is.
    void addVolumes()
    {
        for (const std::vector<label>& shells : volumes_.volumes)
        {
            std::vector<int> loops;
            for (label s : shells)
            {
                loops.push_back(gmsh::model::geo::addSurfaceLoop({shellSurface_[s]}));
            }
            gmsh::model::geo::addVolume(loops);
        }
        gmsh::model::geo::synchronize();
    }

    //- HXT, its threads, the size field and Gmsh's optimiser.
    void setMeshingOptions(const volumeMeshParameters& parameters)
    {
        gmsh::option::setNumber("Mesh.Algorithm3D", 10);       // HXT
        // Quirk: with more than one thread, Debian's Gmsh 4.8.4 HXT now and
        // then returns a duplicated interior node (faces matching nothing);
        // VolumeMesher::mesh catches it and meshVolumeWithFallbacks retries
        // with one thread
        gmsh::option::setNumber("General.NumThreads", parameters.threads);
        // Interior size grows from the surface edge lengths, held to the
        // size field (sizeCallbackGuard). Partition interfaces are refined
        // coarse interior faces, whose edges are up to 3x the fine size:
        // the field's cap keeps cells near them no coarser than in a serial
        // run of the same case. Quirk: the cap as Mesh.MeshSizeMax makes
        // Gmsh 4.8.4 crash (SIGSEGV in hxtRefineTetrahedra) whenever it lies
        // below the longer surface edges, which partition interfaces always
        // have; a size field or callback gives the same sizes without the
        // crash.
        gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 1);
        // For HXT, Mesh.Optimize is HXT's own optimiser (Gmsh's is skipped):
        // it costs little and takes the worst faces from about 80 to 65
        // degrees; the quality pass does the rest (bench/results/quality.md)
        gmsh::option::setNumber("Mesh.Optimize", parameters.optimisationSteps > 0);
        gmsh::option::setNumber("Mesh.OptimizeThreshold", hxtOptimiserThreshold);
    }

    //- The nodes of Gmsh's mesh into result.points: the surface points
    //  first, where Gmsh put them, then the new nodes in tag order; index_
    //  holds the point of each node tag (-1: none).
    void readNodes
    (
        const std::vector<label>& surfacePointOfTag,
        TetMesh& result
    )
    {
        gmsh::model::mesh::getNodes(nodeTags_, coords_, parametric_, -1, -1, false, false);

        // Tags 1..nSurface are the surface points (where Gmsh put them:
        // whether they are still where they went in is VolumeMesher::mesh's
        // to check); new nodes follow in tag order
        result.points = surfacePoints_;
        for (std::size_t k = 0; k < nodeTags_.size(); ++k)
        {
            if (nodeTags_[k] <= nSurface_)
            {
                result.points[surfacePointOfTag[nodeTags_[k] - 1]] =
                    {coords_[3*k], coords_[3*k + 1], coords_[3*k + 2]};
            }
            else
            {
                newTags_.push_back(k);
            }
        }
        std::sort
        (
            newTags_.begin(), newTags_.end(),
            [&](std::size_t a, std::size_t b) { return nodeTags_[a] < nodeTags_[b]; }
        );
        std::size_t maxTag = nSurface_;
        for (std::size_t k : newTags_) maxTag = std::max(maxTag, nodeTags_[k]);
        index_.assign(maxTag + 1, -1);
        for (std::size_t i = 0; i < nSurface_; ++i) index_[i + 1] = surfacePointOfTag[i];

        result.points.reserve(nSurface_ + newTags_.size());
        for (std::size_t k : newTags_)
        {
            index_[nodeTags_[k]] = label(result.points.size());
            result.points.push_back({coords_[3*k], coords_[3*k + 1], coords_[3*k + 2]});
        }
    }

    //- The tets of Gmsh's mesh into result.tets, positive, through the node
    //  index_ of readNodes; frees Gmsh's model.
    void readTets(TetMesh& result)
    {
        // The peak memory of a large partition is Gmsh's model plus what is
        // copied out of it: only the tets' node tags are asked for (no
        // element tags), and the model is freed, its pages handed back,
        // before the tets are built from them (24 bytes per cell less)
        gmsh::model::mesh::preallocateElementsByType
        (
            4, false, true, noElementTags_, elementNodes_
        );
        gmsh::model::mesh::getElementsByType(4, noElementTags_, elementNodes_);
        gmsh::model::remove();
        ::malloc_trim(0);

        result.tets.resize(elementNodes_.size()/4);
        for (std::size_t e = 0; e < result.tets.size(); ++e)
        {
            tetVerts& t = result.tets[e];
            for (int k = 0; k < 4; ++k)
            {
                const std::size_t tag = elementNodes_[4*e + k];
                if (tag >= index_.size() || index_[tag] < 0)
                {
                    throw std::string("a tet refers to an unknown node");
                }
                t[k] = index_[tag];
            }
            const auto& P = result.points;
            if (tetVolume6(P[t[0]], P[t[1]], P[t[2]], P[t[3]]) < 0)
            {
                std::swap(t[2], t[3]);
            }
        }
    }
};

} // End anonymous namespace


pmsh::TetMesh pmsh::gmshModelMesh
(
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const shellVolumes& volumes,
    const volumeMeshParameters& parameters
)
{
    std::lock_guard<std::mutex> lock(gmshMutex);
    initialiseGmsh();

    TetMesh result;
    std::vector<label> surfacePointOfTag;
    try
    {
        gmsh::logger::start();
        gmsh::model::add("pmshFoamPartition");
        hxtModel model(surfacePoints, surfaceTriangles, volumes);
        model.addShellSurfaces(surfacePointOfTag);
        model.addVolumes();
        model.setMeshingOptions(parameters);

        const ng::sizeField sizes = hxtSizeField(surfacePoints, surfaceTriangles, parameters);
        const sizeCallbackGuard sizeGuard(sizes);
        gmsh::model::mesh::generate(3);
        reportMeshingStep("Gmsh HXT: reading the mesh back");

        model.readNodes(surfacePointOfTag, result);
        model.readTets(result);

        gmsh::logger::stop();
    }
    catch (const std::string& error)
    {
        gmsh::model::remove();
        gmshFailed(error, parameters.what);
    }
    catch (const std::exception& error)
    {
        gmsh::model::remove();
        gmshFailed(error.what(), parameters.what);
    }
    return result;
}


// ************************************************************************* //
