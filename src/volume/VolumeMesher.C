/*---------------------------------------------------------------------------*\
  pmshFoam: volume mesher selection (OpenFOAM's run-time selection table,
  which each backend adds itself to) and the check of its contract.
\*---------------------------------------------------------------------------*/

#include "VolumeMesher.H"
#include "tetShape.H"
#include "surfaceTopology.H"
#include "pmshError.H"
#include "tetFaceMatching.H"
#include "matchByPoints.H"
#include "acrossFace.H"
#include "meshingStep.H"

#include <algorithm>
#include <cmath>
#include <cstring>

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * //

namespace pmsh
{
    defineTypeNameAndDebug(VolumeMesher, 0);
    defineRunTimeSelectionTable(VolumeMesher, word);
}


// * * * * * * * * * * * * * * * Local functions * * * * * * * * * * * * * //

namespace
{

using namespace pmsh;

const char* const function = "pmsh::VolumeMesher::mesh";


//- Throw FatalError (naming `what`) unless the triangles form a closed,
//  manifold, consistently oriented surface enclosing a positive volume and
//  using every point: what every backend needs (Netgen may crash on less).
//  Returns 6 times the enclosed volume.
double checkClosedSurface
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles,
    const std::string& what
)
{
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
        const triVerts& f = triangles[t];
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
    for (const triVerts& f : triangles)
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
    return v6;
}


//- The contract's face check when the backend says what lies across each
//  tet face (TetMesh::across, the quality pass's own matching): one pass
//  instead of matching all faces again. Each claim must hold: a tet across
//  has the same three points the other way round and claims this tet back;
//  a surface triangle across is the face, outward, and is claimed once; no
//  triangle is left. Pairs that hold everywhere make the tets a closed
//  complex on the surface, which covers the inside once (positive tets,
//  the surface claimed once); as a second guard the tets' volumes (filled6,
//  6 times their sum) must add up to the enclosed volume, not to twice or
//  more.
void checkClaimedAcross
(
    const std::vector<triVerts>& surfaceTriangles,
    const double enclosed6,
    const double filled6,
    const TetMesh& result,
    const std::string& what
)
{
    const std::string notConforming = what + " is not conforming to the surface";
    const label nTets = label(result.tets.size());
    const label nTris = label(surfaceTriangles.size());
    std::vector<char> claimed(surfaceTriangles.size(), 0);
    auto refuse = [&](label t, int k, const std::string& why)
    {
        const triVerts f = tetFace(result.tets[t], k);
        throw FatalError
        (
            msg() << notConforming << ":\n    tet " << t << " face (" << f[0] << ' '
                << f[1] << ' ' << f[2] << "): " << why,
            function
        );
    };
    for (label t = 0; t < nTets; ++t)
    {
        for (int k = 0; k < 4; ++k)
        {
            const triVerts f = tetFace(result.tets[t], k);
            const label a = result.across[4*t + k];
            if (isAcrossBoundary(a))
            {
                const label b = boundaryAcross(a);
                if (b < 0 || b >= nTris)
                {
                    refuse(t, k, "on no surface triangle (boundary face not in the surface)");
                }
                if (sortedPoints(f) != sortedPoints(surfaceTriangles[b]))
                {
                    refuse(t, k, "not surface triangle " + std::to_string(b) + ", which is claimed across it");
                }
                if (!sameOrientation(f, surfaceTriangles[b]))
                {
                    refuse(t, k, "surface triangle " + std::to_string(b) + " is not oriented outward from it");
                }
                if (claimed[b]++)
                {
                    refuse(t, k, "surface triangle " + std::to_string(b) + " is on two tet faces (duplicates)");
                }
                continue;
            }
            if (a >= nTets || a == t)
            {
                refuse(t, k, "claims tet " + std::to_string(a) + " across it");
            }
            // u's face opposite its apex, the one point of u off f, must be
            // f (had u two points off f, that face would not be)
            const tetVerts& u = result.tets[a];
            const int l = 3 - int(std::find(u.begin(), u.end(), tetApex(u, f)) - u.begin());
            const bool shared = l >= 0 && sortedPoints(tetFace(u, l)) == sortedPoints(f);
            if (!shared || result.across[4*a + l] != t)
            {
                refuse(t, k, "tet " + std::to_string(a) + " across it does not have it across (overlapping or open tets)");
            }
            if (sameOrientation(f, tetFace(u, l)))
            {
                refuse(t, k, "tet " + std::to_string(a) + " lies on the same side (overlapping tets)");
            }
        }
    }
    for (label b = 0; b < nTris; ++b)
    {
        if (!claimed[b])
        {
            throw FatalError
            (
                msg() << notConforming << ":\n    surface triangle " << b
                    << " is not a tet face",
                function
            );
        }
    }

    // A whole number of times the inside: once, or at least twice
    if (!(std::abs(filled6 - enclosed6) < 0.5*enclosed6))
    {
        throw FatalError
        (
            msg() << notConforming << ":\n    its tets fill " << filled6/enclosed6
                << " times the volume inside the surface (overlapping tets)",
            function
        );
    }
}


//- Throw FatalError (naming `what`) unless `result` meets the contract of
//  VolumeMesher.H; enclosed6 is checkClosedSurface's.
void verifyVolumeMesh
(
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const double enclosed6,
    const TetMesh& result,
    const std::string& what
)
{
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
        if (std::memcmp(result.points[i].data(), surfacePoints[i].data(), sizeof(point3)) != 0)
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

    // Positive tets (their volumes summed for checkClaimedAcross)
    double filled6 = 0;
    for (std::size_t t = 0; t < result.tets.size(); ++t)
    {
        const tetVerts& c = result.tets[t];
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
        filled6 += v6;
        const double aspectRatio = tetAspectRatio
        (
            result.points[c[0]], result.points[c[1]],
            result.points[c[2]], result.points[c[3]]
        );
        if (!(aspectRatio <= maxAcceptedAspectRatio))
        {
            throw FatalError
            (
                msg()
                    << what << ": tet " << t << " is a sliver that checkMesh"
                    << " would reject (aspect ratio " << aspectRatio << ", above "
                    << maxAcceptedAspectRatio << "), points "
                    << str(result.points[c[0]]) << ' '
                    << str(result.points[c[1]]) << ' '
                    << str(result.points[c[2]]) << ' '
                    << str(result.points[c[3]]),
                function
            );
        }
    }

    // Conforming and filling the surface exactly: every tet face is shared
    // with one other tet from the other side or is one surface triangle,
    // outward. (With positive tets this also rules out gaps and overlaps.
    // Volumes alone would add up even when a backend duplicates an interior
    // point, as Gmsh 4.8's multithreaded HXT does.)
    if (result.across.size() == 4*result.tets.size())
    {
        checkClaimedAcross(surfaceTriangles, enclosed6, filled6, result, what);
        return;
    }
    fittingTetFaces
    (
        np, result.tets, surfaceTriangles, what + " is not conforming to the surface", function
    );
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Selectors  * * * * * * * * * * * * * * * //

std::vector<std::string> pmsh::VolumeMesher::names()
{
    std::vector<std::string> result;
    if (wordConstructorTablePtr_)
    {
        for (const word& name : wordConstructorTablePtr_->sortedToc())
        {
            result.push_back(name);
        }
    }
    std::stable_partition
    (
        result.begin(), result.end(),
        [](const std::string& name) { return name == preferred; }
    );
    return result;
}


std::unique_ptr<pmsh::VolumeMesher> pmsh::VolumeMesher::New(const std::string& name)
{
    const word key(name, false);
    if (!wordConstructorTablePtr_ || !wordConstructorTablePtr_->found(key))
    {
        msg m;
        m   << "Unknown volumeMesher \"" << name << "\".\nValid volume meshers:";
        for (const std::string& n : names())
        {
            m   << "\n    " << n;
        }
        throw FatalError(m, "pmsh::VolumeMesher::New");
    }
    return (*wordConstructorTablePtr_)[key]();
}


std::vector<std::unique_ptr<pmsh::VolumeMesher>> pmsh::VolumeMesher::NewAll
(
    const std::string& first
)
{
    std::vector<std::unique_ptr<VolumeMesher>> meshers;
    meshers.push_back(New(first));
    for (const std::string& name : names())
    {
        if (name != first)
        {
            meshers.push_back(New(name));
        }
    }
    return meshers;
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

pmsh::TetMesh pmsh::VolumeMesher::mesh
(
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const volumeMeshParameters& parameters
) const
{
    reportMeshingStep("checking the surface");
    const double enclosed6 = checkClosedSurface(surfacePoints, surfaceTriangles, parameters.what);
    reportMeshingStep(title() + ": " + std::to_string(surfaceTriangles.size()) + " surface triangles");
    TetMesh result = generate(surfacePoints, surfaceTriangles, parameters);
    reportMeshingStep
    (
        "checking " + title() + "'s " + std::to_string(result.tets.size()) + " cells"
    );
    verifyVolumeMesh
    (
        surfacePoints, surfaceTriangles, enclosed6, result,
        title() + "'s mesh of " + parameters.what
    );
    freeStorage(result.across);
    return result;
}




// ************************************************************************* //
