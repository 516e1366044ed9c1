/*---------------------------------------------------------------------------*\
  pmshFoam: volume mesher selection and the check of its contract.
\*---------------------------------------------------------------------------*/

#include "VolumeMesher.H"
#include "surfaceTopology.H"
#include "netgenVolumeMesher.H"
#include "hxtVolumeMesher.H"
#include "pmshError.H"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <unordered_map>

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace pmsh
{
namespace
{

//- A triangle's point set (sorted), as a hash key.
struct triKey
{
    label v[3];

    explicit triKey(const triFace& f)
    :
        v{f[0], f[1], f[2]}
    {
        if (v[0] > v[1]) std::swap(v[0], v[1]);
        if (v[1] > v[2]) std::swap(v[1], v[2]);
        if (v[0] > v[1]) std::swap(v[0], v[1]);
    }

    bool operator==(const triKey& o) const
    {
        return v[0] == o.v[0] && v[1] == o.v[1] && v[2] == o.v[2];
    }
};


struct triKeyHash
{
    std::size_t operator()(const triKey& k) const
    {
        std::uint64_t h = std::uint64_t(std::uint32_t(k.v[0]));
        h = h*0x9e3779b97f4a7c15ull ^ std::uint32_t(k.v[1]);
        h = h*0x9e3779b97f4a7c15ull ^ std::uint32_t(k.v[2]);
        return std::size_t(h ^ (h >> 29));
    }
};


//- Same oriented triangle (equal up to a cyclic rotation)?
bool sameOrientation(const triFace& a, const triFace& b)
{
    for (int r = 0; r < 3; ++r)
    {
        if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3])
        {
            return true;
        }
    }
    return false;
}

} // End anonymous namespace
} // End namespace pmsh


// * * * * * * * * * * * * * * * * Selectors  * * * * * * * * * * * * * * * //

std::vector<std::string> pmsh::VolumeMesher::names()
{
    return {"netgen", "hxt"};
}


std::unique_ptr<pmsh::VolumeMesher> pmsh::VolumeMesher::New(const std::string& name)
{
    if (name == "netgen")
    {
        return std::unique_ptr<VolumeMesher>(new netgenVolumeMesher());
    }
    if (name == "hxt")
    {
        return std::unique_ptr<VolumeMesher>(new hxtVolumeMesher());
    }

    msg m;
    m   << "Unknown volumeMesher \"" << name << "\".\nValid volume meshers:";
    for (const std::string& n : names())
    {
        m   << "\n    " << n;
    }
    throw FatalError(m, "pmsh::VolumeMesher::New");
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

pmsh::TetMesh pmsh::VolumeMesher::mesh
(
    const std::vector<point>& surfacePoints,
    const std::vector<triFace>& surfaceTriangles,
    const volumeMeshParameters& parameters
) const
{
    checkClosedSurface(surfacePoints, surfaceTriangles, parameters.what);
    TetMesh result = generate(surfacePoints, surfaceTriangles, parameters);
    verifyVolumeMesh
    (
        surfacePoints, surfaceTriangles, result,
        title() + "'s mesh of " + parameters.what
    );
    return result;
}


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

void pmsh::checkClosedSurface
(
    const std::vector<point>& points,
    const std::vector<triFace>& triangles,
    const std::string& what
)
{
    const char* function = "pmsh::checkClosedSurface";
    const label np = label(points.size());

    if (triangles.size() < 4)
    {
        throw FatalError
        (
            msg()
                << "Cannot mesh the volume of " << what << ": "
                << triangles.size() << " triangles cannot enclose a volume",
            function
        );
    }

    const surfacePointDefects use = findSurfacePointDefects(np, triangles);
    if (use.badTriangle >= 0)
    {
        throw FatalError
        (
            msg()
                << "Triangle " << use.badTriangle << " of " << what << " refers to"
                << " point " << use.badPoint << ": valid points are 0.." << np - 1,
            function
        );
    }
    for (std::size_t t = 0; t < triangles.size(); ++t)
    {
        const triFace& f = triangles[t];
        if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2])
        {
            throw FatalError
            (
                msg()
                    << "Triangle " << t << " of " << what << " repeats a point: ("
                    << f[0] << ' ' << f[1] << ' ' << f[2] << ')',
                function
            );
        }
    }
    if (use.firstUnused >= 0)
    {
        throw FatalError
        (
            msg()
                << "Point " << use.firstUnused << ' ' << str(points[use.firstUnused])
                << " of " << what << " is used by no triangle: Netgen would drop"
                << " and renumber it",
            function
        );
    }

    // Closed, manifold, consistently oriented
    const surfaceEdgeDefects defects = findSurfaceEdgeDefects(triangles);
    if (!defects.none())
    {
        const auto [problem, e] =
            defects.nOpen
          ? std::make_pair("is not closed: an edge is used by one triangle only", defects.firstOpen)
          : defects.nNonManifold
          ? std::make_pair("is not manifold: an edge is used by more than two triangles", defects.firstNonManifold)
          : std::make_pair("is inconsistently oriented: an edge is traversed twice in the same direction", defects.firstInconsistent);
        throw FatalError
        (
            msg()
                << "Cannot mesh the volume of " << what << ": the surface "
                << problem << ", e.g. the edge " << str(points[e.first])
                << '-' << str(points[e.second]),
            function
        );
    }

    // Outward: positive enclosed volume (about a point of the surface)
    double v6 = 0;
    for (const triFace& f : triangles)
    {
        v6 += tetVolume6(points[0], points[f[0]], points[f[1]], points[f[2]]);
    }
    if (!(v6 > 0))
    {
        throw FatalError
        (
            msg()
                << "Cannot mesh the volume of " << what << ": the surface"
                << " encloses a " << (v6 < 0 ? "negative" : "zero") << " volume ("
                << v6/6 << "), its triangles must point out of the volume",
            function
        );
    }
}


void pmsh::verifyVolumeMesh
(
    const std::vector<point>& surfacePoints,
    const std::vector<triFace>& surfaceTriangles,
    const TetMesh& result,
    const std::string& what
)
{
    const char* function = "pmsh::verifyVolumeMesh";
    const label nSurface = label(surfacePoints.size());
    const label np = label(result.points.size());

    if (result.tets.empty())
    {
        throw FatalError(msg() << what << " has no tets", function);
    }

    // Surface points first, in order, bit for bit
    if (np < nSurface)
    {
        throw FatalError
        (
            msg()
                << what << " has " << np << " points, fewer than the "
                << nSurface << " surface points it must keep",
            function
        );
    }
    for (label i = 0; i < nSurface; ++i)
    {
        if (std::memcmp(result.points[i].data(), surfacePoints[i].data(), sizeof(point)) != 0)
        {
            throw FatalError
            (
                msg()
                    << what << " does not keep surface point " << i << ": "
                    << str(surfacePoints[i]) << " became " << str(result.points[i]),
                function
            );
        }
    }

    // Positive tets; their total volume is checked against the surface's
    double tetVolumeSum = 0;
    for (std::size_t t = 0; t < result.tets.size(); ++t)
    {
        const tetCell& c = result.tets[t];
        for (label p : c)
        {
            if (p < 0 || p >= np)
            {
                throw FatalError
                (
                    msg()
                        << what << ": tet " << t << " refers to point " << p
                        << " (there are " << np << ")",
                    function
                );
            }
        }
        const double v6 = tetVolume6
        (
            result.points[c[0]], result.points[c[1]],
            result.points[c[2]], result.points[c[3]]
        );
        if (!(v6 > 0))
        {
            throw FatalError
            (
                msg()
                    << what << ": tet " << t << " is "
                    << (v6 < 0 ? "inverted" : "flat") << " (6 x volume " << v6
                    << "), points " << str(result.points[c[0]]) << ' '
                    << str(result.points[c[1]]) << ' '
                    << str(result.points[c[2]]) << ' '
                    << str(result.points[c[3]]),
                function
            );
        }
        tetVolumeSum += v6;
    }

    // Every surface triangle is the outward face of exactly one tet
    std::unordered_map<triKey, label, triKeyHash> triangleIndex;
    triangleIndex.reserve(surfaceTriangles.size());
    for (std::size_t i = 0; i < surfaceTriangles.size(); ++i)
    {
        triangleIndex.emplace(triKey(surfaceTriangles[i]), label(i));
    }
    std::vector<label> nUses(surfaceTriangles.size(), 0);

    // Outward faces of a positive tet (a, b, c, d)
    static const int tetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (std::size_t t = 0; t < result.tets.size(); ++t)
    {
        const tetCell& c = result.tets[t];
        for (const auto& lf : tetFaces)
        {
            const triFace f{c[lf[0]], c[lf[1]], c[lf[2]]};
            if (f[0] >= nSurface || f[1] >= nSurface || f[2] >= nSurface)
            {
                continue;
            }
            const auto it = triangleIndex.find(triKey(f));
            if (it == triangleIndex.end())
            {
                continue;
            }
            const label i = it->second;
            if (!sameOrientation(f, surfaceTriangles[i]))
            {
                throw FatalError
                (
                    msg()
                        << what << ": surface triangle " << i << " is the face"
                        << " of tet " << t << " from the outside (the tet lies"
                        << " outside the surface)",
                    function
                );
            }
            ++nUses[i];
        }
    }
    for (std::size_t i = 0; i < nUses.size(); ++i)
    {
        if (nUses[i] != 1)
        {
            const triFace& f = surfaceTriangles[i];
            throw FatalError
            (
                msg()
                    << what << ": surface triangle " << i << ' '
                    << str(surfacePoints[f[0]]) << ' ' << str(surfacePoints[f[1]])
                    << ' ' << str(surfacePoints[f[2]]) << " is the face of "
                    << nUses[i] << " tets instead of exactly one",
                function
            );
        }
    }

    // Tets fill the surface exactly: no gaps, no overlaps
    double surfaceVolume6 = 0;
    for (const triFace& f : surfaceTriangles)
    {
        surfaceVolume6 += tetVolume6
        (
            surfacePoints[0], surfacePoints[f[0]], surfacePoints[f[1]], surfacePoints[f[2]]
        );
    }
    if (!(std::abs(tetVolumeSum - surfaceVolume6) <= 1e-8*std::abs(surfaceVolume6)))
    {
        throw FatalError
        (
            msg()
                << what << ": the tets' volume " << tetVolumeSum/6 << " differs"
                << " from the volume the surface encloses, " << surfaceVolume6/6
                << " (tets missing or overlapping)",
            function
        );
    }

    // Conforming: every tet face is shared with exactly one other tet or is
    // one surface triangle. Volumes add up even when a backend duplicates an
    // interior point (Gmsh 4.8's multithreaded HXT does), leaving faces that
    // match nothing: this is what catches it.
    std::vector<triFace> faces;
    faces.reserve(4*result.tets.size() + surfaceTriangles.size());
    auto sortedFace = [](triFace f)
    {
        std::sort(f.begin(), f.end());
        return f;
    };
    for (const tetCell& t : result.tets)
    {
        for (const triFace& f : outwardTetFaces(t))
        {
            faces.push_back(sortedFace(f));
        }
    }
    for (const triFace& f : surfaceTriangles)
    {
        faces.push_back(sortedFace(f));     // pairs with its one tet face
    }
    std::sort(faces.begin(), faces.end());
    std::size_t nUnmatched = 0;
    for (std::size_t i = 0; i < faces.size(); )
    {
        std::size_t j = i + 1;
        while (j < faces.size() && faces[j] == faces[i]) ++j;
        nUnmatched += (j - i != 2);
        i = j;
    }
    if (nUnmatched > 0)
    {
        throw FatalError
        (
            msg()
                << what << " is not conforming: " << nUnmatched << " faces are"
                << " not shared by exactly two tets (or one tet and the surface)",
            function
        );
    }

}


// ************************************************************************* //
