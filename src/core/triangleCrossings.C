#include "triangleCrossings.H"
#include "triangleGrid.H"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace pmsh
{

namespace
{

bool sharePoint(const triVerts& a, const triVerts& b)
{
    for (label u : a)
    {
        if (u == b[0] || u == b[1] || u == b[2]) return true;
    }
    return false;
}


bool trianglesCross(const std::vector<point3>& x, const triVerts& a, const triVerts& b)
{
    for (int i = 0; i < 3; ++i)
    {
        if
        (
            segmentCrossesTriangle(x[a[i]], x[a[(i + 1) % 3]], x[b[0]], x[b[1]], x[b[2]])
         || segmentCrossesTriangle(x[b[i]], x[b[(i + 1) % 3]], x[a[0]], x[a[1]], x[a[2]])
        )
        {
            return true;
        }
    }
    return false;
}


//- About two mean edges: a triangle touches few cells, a cell holds few
double gridCell(const std::vector<point3>& x, const std::vector<triVerts>& triangles)
{
    double edges = 0;
    for (const triVerts& f : triangles)
    {
        edges += std::sqrt(magSqr(x[f[1]] - x[f[0]]));
    }
    return triangles.empty() ? 1 : std::max(2*edges/triangles.size(), 1e-300);
}

} // End anonymous namespace


bool segmentCrossesTriangle
(
    const point3& a,
    const point3& b,
    const point3& p,
    const point3& q,
    const point3& r
)
{
    // The segment's parameter, its ends excluded
    const double t = rayTriangle(a, b - a, p, q, r);
    return t > 1e-9 && t < 1 - 1e-9;
}


std::vector<label> crossingTriangles
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles,
    const std::vector<bool>& tested
)
{
    std::vector<label> crossing(triangles.size(), 0);
    const triangleGrid grid(points, triangles, gridCell(points, triangles));
    for (label t = 0; t < label(triangles.size()); ++t)
    {
        if (!tested[t]) continue;
        const box3 bt = boxOf(points, triangles[t]);
        grid.near(bt, [&](label u)
        {
            if
            (
                u == t
             || sharePoint(triangles[t], triangles[u])
             || !bt.overlaps(boxOf(points, triangles[u]))
             || !trianglesCross(points, triangles[t], triangles[u])
            )
            {
                return;
            }
            const auto mark = [](label& c, label other)
            {
                c = c == 0 ? other + 1 : std::min(c, other + 1);
            };
            mark(crossing[t], u);
            mark(crossing[u], t);
        });
    }
    return crossing;
}

} // End namespace pmsh


// ************************************************************************* //
