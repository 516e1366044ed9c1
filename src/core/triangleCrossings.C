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


//- How many points two triangles share
int nShared(const triVerts& a, const triVerts& b)
{
    int n = 0;
    for (label u : a) n += u == b[0] || u == b[1] || u == b[2];
    return n;
}


//- Sign of the turn (p, q, r) in the plane of two axes: 0 within `tol` of
//  the scale of its edges
int turn2d(const double p[2], const double q[2], const double r[2], double tol)
{
    const double d = (q[0] - p[0])*(r[1] - p[1]) - (q[1] - p[1])*(r[0] - p[0]);
    return d > tol ? 1 : d < -tol ? -1 : 0;
}


//- Do triangles a and b lie in one plane and overlap there (beyond the
//  points they share)? A surface folded back onto itself does: its two
//  sides coincide, and no edge passes through the other side, so
//  trianglesCross does not see it.
bool coplanarOverlap(const std::vector<point3>& x, const triVerts& a, const triVerts& b)
{
    const vector3 n = cross(x[a[1]] - x[a[0]], x[a[2]] - x[a[0]]);
    const double area2 = std::sqrt(magSqr(n));
    double longest2 = 0;
    for (const triVerts* t : {&a, &b})
    {
        for (int i = 0; i < 3; ++i)
        {
            longest2 = std::max(longest2, magSqr(x[(*t)[i]] - x[(*t)[(i + 1) % 3]]));
        }
    }
    if (!(area2 > 0)) return false;
    const double tolerance = 1e-9*std::sqrt(longest2);
    for (label p : b)
    {
        if (std::abs(dot(n, x[p] - x[a[0]]))/area2 > tolerance) return false;
    }
    // In the plane of the two axes most across the normal
    int drop = 0;
    for (int k = 1; k < 3; ++k)
    {
        if (std::abs(n[k]) > std::abs(n[drop])) drop = k;
    }
    const int i0 = (drop + 1) % 3, i1 = (drop + 2) % 3;
    double pa[3][2], pb[3][2];
    for (int i = 0; i < 3; ++i)
    {
        pa[i][0] = x[a[i]][i0]; pa[i][1] = x[a[i]][i1];
        pb[i][0] = x[b[i]][i0]; pb[i][1] = x[b[i]][i1];
    }
    const double tol2 = 1e-9*longest2;
    // An edge of one properly through an edge of the other (edges with a
    // shared end only meet there)
    for (int i = 0; i < 3; ++i)
    {
        for (int j = 0; j < 3; ++j)
        {
            const label e[2] = {a[i], a[(i + 1) % 3]}, f[2] = {b[j], b[(j + 1) % 3]};
            if (e[0] == f[0] || e[0] == f[1] || e[1] == f[0] || e[1] == f[1]) continue;
            const double *p = pa[i], *q = pa[(i + 1) % 3], *r = pb[j], *s = pb[(j + 1) % 3];
            const int t1 = turn2d(p, q, r, tol2), t2 = turn2d(p, q, s, tol2);
            const int t3 = turn2d(r, s, p, tol2), t4 = turn2d(r, s, q, tol2);
            if (t1*t2 < 0 && t3*t4 < 0) return true;
        }
    }
    // A point of one strictly inside the other
    const auto inside = [&](const double (*t)[2], const double* p)
    {
        const int s0 = turn2d(t[0], t[1], p, tol2);
        const int s1 = turn2d(t[1], t[2], p, tol2);
        const int s2 = turn2d(t[2], t[0], p, tol2);
        return s0 != 0 && s0 == s1 && s1 == s2;
    };
    for (int i = 0; i < 3; ++i)
    {
        const bool bShares = b[i] == a[0] || b[i] == a[1] || b[i] == a[2];
        if (!bShares && inside(pa, pb[i])) return true;
        const bool aShares = a[i] == b[0] || a[i] == b[1] || a[i] == b[2];
        if (!aShares && inside(pb, pa[i])) return true;
    }
    return false;
}


//- Do triangles a and b, which share `shared` points, overlap: an edge
//  through the other, or (alsoFolds) a fold onto each other? Triangles
//  sharing a point cross only by the edge opposite it.
bool trianglesOverlap
(
    const std::vector<point3>& x,
    const triVerts& a,
    const triVerts& b,
    const int shared,
    const bool alsoFolds
)
{
    if (shared == 0 && trianglesCross(x, a, b)) return true;
    if (!alsoFolds || shared == 3) return false;
    // The edge of one opposite the shared point through the other
    const auto oppositeCrosses = [&](const triVerts& t, const triVerts& u)
    {
        label e[2];
        int n = 0;
        for (label p : t)
        {
            if (p != u[0] && p != u[1] && p != u[2]) e[n++] = p;
        }
        return segmentCrossesTriangle(x[e[0]], x[e[1]], x[u[0]], x[u[1]], x[u[2]]);
    };
    if (shared == 1 && (oppositeCrosses(a, b) || oppositeCrosses(b, a))) return true;
    return coplanarOverlap(x, a, b);
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


std::vector<std::pair<label, label>> crossingPairs
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles,
    const std::vector<bool>& tested,
    const bool alsoFolds,
    const std::vector<label>& group
)
{
    std::vector<std::pair<label, label>> pairs;
    const triangleGrid grid(points, triangles, gridCell(points, triangles));
    for (label t = 0; t < label(triangles.size()); ++t)
    {
        if (!tested[t]) continue;
        const box3 bt = boxOf(points, triangles[t]);
        grid.near(bt, [&](label u)
        {
            // A pair of tested triangles is kept from its first triangle
            // only; the grid meets u once per cell the two share (the
            // sort and unique below)
            if
            (
                u == t
             || (tested[u] && u < t)
             || (!group.empty() && group[u] != group[t])
             || !bt.overlaps(boxOf(points, triangles[u]))
             || !trianglesOverlap
                (
                    points, triangles[t], triangles[u],
                    nShared(triangles[t], triangles[u]), alsoFolds
                )
            )
            {
                return;
            }
            pairs.emplace_back(std::min(t, u), std::max(t, u));
        });
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
}


std::vector<label> crossingTriangles
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles,
    const std::vector<bool>& tested,
    const bool alsoFolds
)
{
    std::vector<label> crossing(triangles.size(), 0);
    const auto mark = [](label& c, label other)
    {
        c = c == 0 ? other + 1 : std::min(c, other + 1);
    };
    for (const auto& [t, u] : crossingPairs(points, triangles, tested, alsoFolds))
    {
        mark(crossing[t], u);
        mark(crossing[u], t);
    }
    return crossing;
}

} // End namespace pmsh


// ************************************************************************* //
