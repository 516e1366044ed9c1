#include "surfaceTopology.H"

#include "matchByPoints.H"

#include <algorithm>

pmsh::surfaceEdgeDefects pmsh::findSurfaceEdgeDefects
(
    const std::vector<triFace>& triangles
)
{
    // Edge k of triangle t, directed as the triangle goes round, is 3*t + k
    auto edgeOf = [&](matchId id)
    {
        const triFace& f = triangles[id/3];
        return std::array<label, 2>{f[id % 3], f[(id + 1) % 3]};
    };
    label nPoints = 0;
    for (const triFace& f : triangles)
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
    const std::vector<triFace>& triangles
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
