/*---------------------------------------------------------------------------*\
  pmshFoam: Netgen volume mesher (Netgen itself is behind netgenInterface).
\*---------------------------------------------------------------------------*/

#include "netgenVolumeMesher.H"
#include "netgenInterface.H"
#include "error.H"

#include <algorithm>
#include <sstream>

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace pmsh
{
namespace
{

std::string str(const point& p)
{
    std::ostringstream os;
    os  << '(' << p[0] << ' ' << p[1] << ' ' << p[2] << ')';
    return os.str();
}


//- FatalError unless the triangles form a closed, manifold, consistently
//  oriented surface enclosing a positive volume, using every point.
void checkSurface
(
    const std::vector<point>& points,
    const std::vector<triFace>& triangles,
    const std::string& what
)
{
    const char* function = "pmsh::netgenVolumeMesher::mesh";
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

    std::vector<bool> used(points.size(), false);
    for (std::size_t t = 0; t < triangles.size(); ++t)
    {
        const triFace& f = triangles[t];
        for (label p : f)
        {
            if (p < 0 || p >= np)
            {
                throw FatalError
                (
                    msg()
                        << "Triangle " << t << " of " << what << " refers to"
                        << " point " << p << ": valid points are 0.." << np - 1,
                    function
                );
            }
            used[p] = true;
        }
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
    const auto unused = std::find(used.begin(), used.end(), false);
    if (unused != used.end())
    {
        const std::size_t i = unused - used.begin();
        throw FatalError
        (
            msg()
                << "Point " << i << ' ' << str(points[i]) << " of " << what
                << " is used by no triangle: Netgen would drop and renumber it",
            function
        );
    }

    // Directed edges: each must appear once, with its reverse once
    struct edgeUse
    {
        label lo, hi;
        bool forward;
    };
    std::vector<edgeUse> uses;
    uses.reserve(3*triangles.size());
    for (const triFace& f : triangles)
    {
        for (int k = 0; k < 3; ++k)
        {
            const label a = f[k];
            const label b = f[(k + 1) % 3];
            uses.push_back({std::min(a, b), std::max(a, b), a < b});
        }
    }
    std::sort
    (
        uses.begin(), uses.end(),
        [](const edgeUse& x, const edgeUse& y)
        {
            return x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi;
        }
    );
    for (std::size_t i = 0; i < uses.size(); )
    {
        std::size_t j = i;
        int nForward = 0;
        while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi)
        {
            nForward += uses[j].forward;
            ++j;
        }
        const std::size_t n = j - i;
        if (n != 2 || nForward != 1)
        {
            const char* problem =
                n == 1 ? "is not closed: an edge is used by one triangle only"
              : n > 2 ? "is not manifold: an edge is used by more than two triangles"
              : "is inconsistently oriented: an edge is traversed twice in the same direction";
            throw FatalError
            (
                msg()
                    << "Cannot mesh the volume of " << what << ": the surface "
                    << problem << ", e.g. the edge " << str(points[uses[i].lo])
                    << '-' << str(points[uses[i].hi]),
                function
            );
        }
        i = j;
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

} // End anonymous namespace
} // End namespace pmsh


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

pmsh::TetMesh pmsh::netgenVolumeMesher::mesh
(
    const std::vector<point>& surfacePoints,
    const std::vector<triFace>& surfaceTriangles,
    const volumeMeshParameters& parameters
) const
{
    std::ostringstream whatStream;
    whatStream
        << "a closed surface of " << surfacePoints.size() << " points and "
        << surfaceTriangles.size() << " triangles";
    const std::string what = whatStream.str();

    checkSurface(surfacePoints, surfaceTriangles, what);

    ng::meshParameters mp;
    mp.maxh = parameters.maxCellSize;
    mp.grading = parameters.grading;
    mp.optimisationSteps = parameters.optimisationSteps;

    ng::volumeMesh m = ng::surfaceVolumeMesh(surfacePoints, surfaceTriangles, mp, what);

    TetMesh result;
    result.points = std::move(m.points);
    result.tets = std::move(m.tets);

    verifyVolumeMesh(surfacePoints, surfaceTriangles, result, "Netgen's mesh of " + what);

    return result;
}


// ************************************************************************* //
