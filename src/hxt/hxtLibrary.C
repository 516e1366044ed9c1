/*---------------------------------------------------------------------------*\
  pmshFoam: HXT called directly, without Gmsh's model (hxtBackends.H). All
  contact with HXT's own functions is in this file; every quirk met is
  noted where it is handled.
\*---------------------------------------------------------------------------*/

#include "hxtBackends.H"
#include "pmshError.H"
#include "meshingStep.H"

#include <gmsh.h>

#include <malloc.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <mutex>
#include <numeric>
#include <string>

#if GMSH_API_VERSION_MAJOR == 4 && GMSH_API_VERSION_MINOR == 8
#define PMSH_HXT_LIBRARY 1
#endif

std::string pmsh::gmshVersion()
{
    return GMSH_API_VERSION;
}


#ifdef PMSH_HXT_LIBRARY

// HXT's C interface as Gmsh 4.8 builds it (contrib/hxt: hxt_mesh.h,
// hxt_tetMesh.h, hxt_message.h; the same in 4.8.0 to 4.8.4). Debian ships
// libgmsh's HXT symbols but not these headers; only what is used here is
// declared, field for field. The options changed in Gmsh 4.9, hence the
// version test above.
extern "C"
{

// HXTStatus is a C enum: 0 is success, negative values are errors
typedef int hxtStatus;

struct HXTMesh
{
    struct
    {
        double* coord;          // x, y, z and a size per vertex
        uint32_t num;
        uint32_t size;
    } vertices;
    struct
    {
        uint32_t* node;
        uint64_t* neigh;
        uint32_t* color;
        uint16_t* flag;
        uint64_t num;
        uint64_t size;
    } tetrahedra;
    struct
    {
        uint32_t* node;
        uint32_t* color;
        uint64_t num;
        uint64_t size;
    } triangles;
    struct
    {
        uint32_t* node;
        uint32_t* color;
        uint64_t num;
        uint64_t size;
    } lines;
    struct
    {
        uint32_t* node;
        uint32_t* color;
        uint32_t num;
        uint32_t size;
    } points;
    struct
    {
        uint32_t numVolumes;
        uint32_t* numSurfacesPerVolume;
        uint32_t* surfacesPerVolume;
        uint32_t numSurfaces;
        uint32_t* numCurvesPerSurface;
        uint32_t* curvesPerSurface;
        uint32_t numCurves;
        uint32_t* endPointsOfCurves;
        uint32_t numPoints;
        uint32_t* points;
    } brep;
};

struct HXTTetMeshOptions
{
    int defaultThreads;
    int delaunayThreads;
    int improveThreads;
    int reproducible;
    int verbosity;
    int stat;
    int refine;
    int optimize;
    struct
    {
        double (*callback)(double*, double*, double*, double*, void*);
        void* userData;
        double min;
    } quality;
    struct
    {
        hxtStatus (*callback)(double* coord, uint32_t* volume, size_t n, void* userData);
        void* userData;
        double min;
        double max;
        double factor;
    } nodalSizes;
};

struct HXTMessage
{
    const char* string;
    const char* func;
    const char* file;
    const char* line;
    int threadId;
    int numThreads;
    int level;                  // 0 info, 1 debug, 2 warning, 3 error, 4 trace
};

hxtStatus hxtMeshCreate(HXTMesh** mesh);
hxtStatus hxtMeshDelete(HXTMesh** mesh);
hxtStatus hxtTetMesh(HXTMesh* mesh, HXTTetMeshOptions* options);
hxtStatus hxtSetMessageCallback(hxtStatus (*callback)(HXTMessage*));
const char* hxtGetStatusString(hxtStatus status);

} // End extern "C"


namespace
{

using namespace pmsh;

constexpr uint32_t ghostVertex = UINT32_MAX;

// HXT's message handler is global: one mesh at a time per process (the
// lock), and its last warnings and errors kept for the error message
std::mutex hxtMutex;
std::deque<std::string> hxtComplaints;

hxtStatus keepComplaints(HXTMessage* message)
{
    if (message && message->level >= 2 && message->string)
    {
        hxtComplaints.emplace_back(message->string);
        if (hxtComplaints.size() > 5)
        {
            hxtComplaints.pop_front();
        }
    }
    return 0;
}


// Quirk: HXT allocates with malloc and frees with free (Gmsh builds it
// without HXT_ALIGN_ALLOCATIONS), and it frees and grows the arrays handed
// to it, so they are malloc'd here. Were they not what it expects, its
// hxtMeshDelete would report a pointer error, not crash.
template<class T>
T* hxtArray(std::size_t n)
{
    T* p = static_cast<T*>(std::malloc(std::max<std::size_t>(n, 1)*sizeof(T)));
    if (!p)
    {
        throw std::bad_alloc();
    }
    return p;
}


//- HXT's mesh, deleted with it
class hxtMesh
{
    HXTMesh* mesh_ = nullptr;

public:

    hxtMesh()
    {
        if (hxtMeshCreate(&mesh_) != 0)
        {
            throw std::bad_alloc();
        }
    }

    ~hxtMesh()
    {
        release();
    }

    hxtMesh(const hxtMesh&) = delete;
    hxtMesh& operator=(const hxtMesh&) = delete;

    HXTMesh* operator->() const
    {
        return mesh_;
    }

    HXTMesh* get() const
    {
        return mesh_;
    }

    hxtStatus release()
    {
        hxtStatus s = 0;
        if (mesh_)
        {
            s = hxtMeshDelete(&mesh_);
            mesh_ = nullptr;
            // its arrays were the largest blocks of the process
            ::malloc_trim(0);
        }
        return s;
    }
};


[[noreturn]] void hxtFailed(hxtStatus status, const std::string& what)
{
    msg m;
    m   << "Gmsh HXT could not mesh the volume of " << what << ": "
        << hxtGetStatusString(status) << " (status " << status << ')';
    for (const std::string& c : hxtComplaints)
    {
        m   << "\n    HXT: " << c;
    }
    throw FatalError(m, "pmsh::hxtLibraryMesh");
}


//- The order in which HXT gets the surface points: HXT vertex i is surface
//  point order[i], a shuffle of them (xorshift, fixed seed: the same
//  surface gets the same mesh). Quirk: Gmsh 4.8.4's HXT can walk in
//  circles while it inserts points (walking2Cavity has no bound; fixed in
//  Gmsh 4.10), and whether it does depends on the vertex numbering, which
//  breaks ties among the many cospherical points of a refined curved
//  surface. A sphere partition of 55M cells walked in circles given its
//  points in pmshFoam's order, and again shell by shell in order of first
//  use; shuffled, it was meshed in 125 s (bench/results/massive.md). The
//  shuffle is no cure: the next 107M-cell run walked in circles on a
//  partition all the same. So HXT shows progress at each refinement round
//  (interiorSizes), the parent stops a child that shows none for too long
//  (expectProgressWithin), and each attempt of the retry ladder shuffles
//  with a seed of its own (volumeMeshParameters::pointOrder).
std::vector<label> insertionOrder(std::size_t nPoints, unsigned seed)
{
    std::vector<label> order(nPoints);
    std::iota(order.begin(), order.end(), label(0));
    uint64_t x = 88172645463325252ull ^ (0x9E3779B97F4A7C15ull*seed);
    for (std::size_t i = nPoints; i > 1; --i)
    {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        std::swap(order[i - 1], order[x % i]);
    }
    return order;
}


//- The surface in HXT's numbering (insertionOrder): its points (the size
//  left at 0: HXT takes each point's from its edges), its triangles
//  coloured by shell (colour = shell + 1), and the volumes as the colours
//  of their shells. Without volumes HXT would fill every closed region,
//  the inside of holes too.
void setSurface
(
    HXTMesh* m,
    const std::vector<point3>& points,
    const std::vector<label>& order,
    const std::vector<triVerts>& triangles,
    const shellVolumes& volumes
)
{
    std::vector<uint32_t> hxtIndex(points.size());
    m->vertices.coord = hxtArray<double>(4*points.size());
    m->vertices.num = m->vertices.size = uint32_t(points.size());
    for (std::size_t i = 0; i < order.size(); ++i)
    {
        hxtIndex[order[i]] = uint32_t(i);
        const point3& p = points[order[i]];
        double* x = m->vertices.coord + 4*i;
        x[0] = p[0];
        x[1] = p[1];
        x[2] = p[2];
        x[3] = 0;
    }

    m->triangles.node = hxtArray<uint32_t>(3*triangles.size());
    m->triangles.color = hxtArray<uint32_t>(triangles.size());
    m->triangles.num = m->triangles.size = triangles.size();
    for (std::size_t t = 0; t < triangles.size(); ++t)
    {
        for (int k = 0; k < 3; ++k)
        {
            m->triangles.node[3*t + k] = hxtIndex[triangles[t][k]];
        }
        m->triangles.color[t] = uint32_t(volumes.shellOf[t] + 1);
    }

    std::size_t nShells = 0;
    for (const std::vector<label>& v : volumes.volumes) nShells += v.size();
    m->brep.numVolumes = uint32_t(volumes.volumes.size());
    m->brep.numSurfacesPerVolume = hxtArray<uint32_t>(volumes.volumes.size());
    m->brep.surfacesPerVolume = hxtArray<uint32_t>(nShells);
    std::size_t at = 0;
    for (std::size_t v = 0; v < volumes.volumes.size(); ++v)
    {
        m->brep.numSurfacesPerVolume[v] = uint32_t(volumes.volumes[v].size());
        for (label s : volumes.volumes[v])
        {
            m->brep.surfacesPerVolume[at++] = uint32_t(s + 1);
        }
    }
}


//- How much CPU time HXT may take, with `nPoints` points in its mesh,
//  until its next refinement round begins (or it ends): far more than it
//  takes. On this machine a 54M-cell partition (9M points) took 240 s in
//  all, its optimiser and the longest rounds well under 100 s each; a
//  walk in circles never ends.
double hxtCpuAllowance(std::size_t nPoints)
{
    return 120 + 60e-6*double(nPoints);
}


//- What HXT's size callback reads: the size field, and the points so far
struct sizeCallbackData
{
    const ng::sizeField* sizes;
    std::atomic<std::size_t> nPoints;
};


//- HXT's size callback: each new point's size is the one HXT interpolated
//  from the surface, at most the size field's there (as Gmsh does with
//  Mesh.MeshSizeExtendFromBoundary and a background field). HXT calls it
//  once per refinement round: the sign of progress its parent waits for
hxtStatus interiorSizes(double* coord, uint32_t*, size_t n, void* data)
{
    sizeCallbackData& d = *static_cast<sizeCallbackData*>(data);
    expectProgressWithin(hxtCpuAllowance(d.nPoints += n));
    const ng::sizeField& sizes = *d.sizes;
    for (size_t i = 0; i < n; ++i)
    {
        double* x = coord + 4*i;
        const double cap = sizes({x[0], x[1], x[2]});
        x[3] = x[3] > 0 ? std::min(x[3], cap) : cap;
    }
    return 0;
}


//- The tets inside the volumes, positive, into a TetMesh: the surface
//  points first, in their order (HXT keeps its input vertices where they
//  were: HXT vertex i is surface point order[i]), then the points HXT
//  added, in its order. With them, the tet across each face, from HXT's
//  own adjacency. HXT's colour array is spent doing so.
TetMesh readMesh
(
    HXTMesh* m,
    const std::vector<point3>& surfacePoints,
    const std::vector<label>& order
)
{
    const std::size_t nSurface = surfacePoints.size();
    const uint32_t nVolumes = m->brep.numVolumes;
    auto inside = [&](uint64_t t)
    {
        return m->tetrahedra.node[4*t + 3] != ghostVertex
            && m->tetrahedra.color[t] < nVolumes;
    };

    std::vector<label> index(m->vertices.num, -1);
    std::size_t nTets = 0;
    for (uint64_t t = 0; t < m->tetrahedra.num; ++t)
    {
        if (!inside(t)) continue;
        ++nTets;
        for (int k = 0; k < 4; ++k) index[m->tetrahedra.node[4*t + k]] = 0;
    }

    TetMesh result;
    result.points = surfacePoints;
    for (std::size_t i = 0; i < nSurface; ++i)
    {
        const double* x = m->vertices.coord + 4*i;
        const point3& p = surfacePoints[order[i]];
        if (x[0] != p[0] || x[1] != p[1] || x[2] != p[2])
        {
            throw FatalError
            (
                msg() << "HXT moved or renumbered surface point " << order[i],
                "pmsh::hxtLibraryMesh"
            );
        }
        index[i] = order[i];
    }
    std::size_t nNew = 0;
    for (std::size_t i = nSurface; i < index.size(); ++i) nNew += index[i] == 0;
    result.points.reserve(nSurface + nNew);
    for (std::size_t i = nSurface; i < index.size(); ++i)
    {
        if (index[i] < 0) continue;
        index[i] = label(result.points.size());
        const double* x = m->vertices.coord + 4*i;
        result.points.push_back({x[0], x[1], x[2]});
    }

    // Each tet's index in the result goes where its colour was, once read
    // (4 bytes a tet spared at stage 4's peak); outside: none
    constexpr uint32_t none = UINT32_MAX;
    uint32_t* const resultIndex = m->tetrahedra.color;
    result.tets.reserve(nTets);
    for (uint64_t t = 0; t < m->tetrahedra.num; ++t)
    {
        if (!inside(t))
        {
            resultIndex[t] = none;
            continue;
        }
        resultIndex[t] = uint32_t(result.tets.size());
        const uint32_t* n = m->tetrahedra.node + 4*t;
        tetVerts v{index[n[0]], index[n[1]], index[n[2]], index[n[3]]};
        const auto& P = result.points;
        if (tetVolume6(P[v[0]], P[v[1]], P[v[2]], P[v[3]]) < 0)
        {
            std::swap(v[2], v[3]);
        }
        result.tets.push_back(v);
    }

    // HXT's neigh[4t + l] is 4u + l', u's facet l' against t's facet l,
    // facet l opposite node l; pmshFoam's face k is opposite point 3 - k
    // (tetFace), and nodes 2 and 3 trade places in a tet turned positive
    result.tetsAcross.resize(4*nTets);
    for (uint64_t t = 0; t < m->tetrahedra.num; ++t)
    {
        const uint32_t i = resultIndex[t];
        if (i == none) continue;
        const bool turned = result.tets[i][2] != index[m->tetrahedra.node[4*t + 2]];
        for (int l = 0; l < 4; ++l)
        {
            const uint64_t n = m->tetrahedra.neigh[4*t + l];
            const uint32_t u = n/4 < m->tetrahedra.num ? resultIndex[n/4] : none;
            const int at = turned && l >= 2 ? 5 - l : l;
            result.tetsAcross[4*i + 3 - at] = u == none ? -1 : label(u);
        }
    }
    return result;
}

} // End anonymous namespace


bool pmsh::hxtLibraryAvailable()
{
    return true;
}


pmsh::TetMesh pmsh::hxtLibraryMesh
(
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const shellVolumes& volumes,
    const volumeMeshParameters& parameters
)
{
    std::lock_guard<std::mutex> lock(hxtMutex);
    hxtComplaints.clear();
    hxtSetMessageCallback(keepComplaints);

    hxtMesh mesh;
    const std::vector<label> order = insertionOrder(surfacePoints.size(), parameters.pointOrder);
    setSurface(mesh.get(), surfacePoints, order, surfaceTriangles, volumes);

    // As Gmsh 4.8 calls it (meshGRegionHxt.cpp): reproducible, refined
    // to the sizes, and HXT's own optimiser (Gmsh's Mesh.Optimize for HXT)
    // unless optimisationSteps is 0
    HXTTetMeshOptions options{};
    options.defaultThreads = std::max(parameters.threads, 1);
    options.reproducible = 1;
    options.refine = 1;
    options.optimize = parameters.optimisationSteps > 0;
    options.quality.min = hxtOptimiserThreshold;
    const ng::sizeField sizeField = hxtSizeField(surfacePoints, surfaceTriangles, parameters);
    sizeCallbackData sizes{&sizeField, {surfacePoints.size()}};
    options.nodalSizes.callback = interiorSizes;
    options.nodalSizes.userData = &sizes;
    options.nodalSizes.max = 1e22;
    options.nodalSizes.factor = 1;

    expectProgressWithin(hxtCpuAllowance(surfacePoints.size()));
    const hxtStatus status = hxtTetMesh(mesh.get(), &options);
    expectProgressWithin(0);
    if (status != 0)
    {
        hxtFailed(status, parameters.what);
    }

    reportMeshingStep("Gmsh HXT: reading the mesh back");
    TetMesh result = readMesh(mesh.get(), surfacePoints, order);
    const hxtStatus freed = mesh.release();
    if (freed != 0)
    {
        hxtFailed(freed, parameters.what + " (freeing HXT's mesh)");
    }
    return result;
}

#else

bool pmsh::hxtLibraryAvailable()
{
    return false;
}


pmsh::TetMesh pmsh::hxtLibraryMesh
(
    const std::vector<point3>&,
    const std::vector<triVerts>&,
    const shellVolumes&,
    const volumeMeshParameters& parameters
)
{
    throw FatalError
    (
        msg() << "HXT's own functions are declared for Gmsh 4.8 only, this"
            " is Gmsh " << GMSH_API_VERSION << " (meshing " << parameters.what
            << " goes through Gmsh's model instead)",
        "pmsh::hxtLibraryMesh"
    );
}

#endif


// ************************************************************************* //
