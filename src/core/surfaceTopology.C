#include "surfaceTopology.H"

#include "matchByPoints.H"

#include <algorithm>
#include <cmath>
#include <unordered_map>

pmsh::surfaceEdgeDefects pmsh::findSurfaceEdgeDefects
(
    const std::vector<triVerts>& triangles
)
{
    auto edgeOf = [&](matchId id) { return triangleEdge(triangles, id); };
    label nPoints = 0;
    for (const triVerts& f : triangles)
    {
        nPoints = std::max({nPoints, f[0] + 1, f[1] + 1, f[2] + 1});
    }

    surfaceEdgeDefects d;
    forEachSamePointsGroup
    (
        std::size_t(nPoints), matchId(3*triangles.size()), edgeOf,
        [&](const matchId* ids, std::size_t n)
        {
            const auto e = sortedPoints(edgeOf(ids[0]));
            const std::pair<label, label> edge{e[0], e[1]};
            if (n == 1)
            {
                if (!d.nOpen++) d.firstOpen = edge;
            }
            else if (n > 2)
            {
                if (!d.nNonManifold++) d.firstNonManifold = edge;
            }
            else if (edgeOf(ids[0]) == edgeOf(ids[1]))
            {
                if (!d.nInconsistent++) d.firstInconsistent = edge;
            }
        }
    );
    return d;
}


pmsh::surfacePointDefects pmsh::findSurfacePointDefects
(
    label nPoints,
    const std::vector<triVerts>& triangles
)
{
    surfacePointDefects defects;
    std::vector<bool> used(nPoints, false);
    for (std::size_t t = 0; t < triangles.size(); ++t)
    {
        for (label p : triangles[t])
        {
            if (p < 0 || p >= nPoints)
            {
                defects.badTriangle = label(t);
                defects.badPoint = p;
                return defects;
            }
            used[p] = true;
        }
    }
    const auto unused = std::find(used.begin(), used.end(), false);
    if (unused != used.end())
    {
        defects.firstUnused = label(unused - used.begin());
    }
    return defects;
}


std::vector<pmsh::label> pmsh::surfaceShells
(
    const label nPoints,
    const std::vector<triVerts>& triangles,
    label& nShells
)
{
    // Union-find over the points: triangles sharing a point share a shell
    std::vector<label> parent(nPoints);
    for (std::size_t i = 0; i < parent.size(); ++i)
    {
        parent[i] = label(i);
    }
    auto root = [&parent](label i)
    {
        while (parent[i] != i)
        {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        return i;
    };
    for (const triVerts& f : triangles)
    {
        for (int k = 1; k < 3; ++k)
        {
            const label a = root(f[0]);
            const label b = root(f[k]);
            if (a != b)
            {
                parent[std::max(a, b)] = std::min(a, b);
            }
        }
    }

    // Shells numbered in the order of their first triangle
    std::unordered_map<label, label> shellOfRoot;
    std::vector<label> shell(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
    {
        shell[t] = shellOfRoot.emplace
        (
            root(triangles[t][0]), label(shellOfRoot.size())
        ).first->second;
    }
    nShells = label(shellOfRoot.size());
    return shell;
}


double pmsh::windingNumber
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles,
    const std::vector<label>& shellTriangles,
    const point3& x
)
{
    // Sum of the solid angles of the triangles seen from x (Van Oosterom
    // and Strackee), over 4 pi: +-1 inside a closed surface, 0 outside
    double omega = 0;
    for (label t : shellTriangles)
    {
        const triVerts& f = triangles[t];
        const vector3 a = points[f[0]] - x;
        const vector3 b = points[f[1]] - x;
        const vector3 c = points[f[2]] - x;
        const double la = std::sqrt(magSqr(a));
        const double lb = std::sqrt(magSqr(b));
        const double lc = std::sqrt(magSqr(c));
        const double numerator = dot(a, cross(b, c));
        const double denominator =
            la*lb*lc + dot(a, b)*lc + dot(a, c)*lb + dot(b, c)*la;
        omega += 2*std::atan2(numerator, denominator);
    }
    return omega/(4*M_PI);
}
