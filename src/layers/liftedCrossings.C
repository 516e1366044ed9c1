#include "liftedCrossings.H"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace pmsh
{

namespace
{

struct box
{
    point3 lo, hi;
};


box boxOf(const std::vector<point3>& x, const triVerts& f)
{
    box b{x[f[0]], x[f[0]]};
    for (int i = 1; i < 3; ++i)
    {
        for (int k = 0; k < 3; ++k)
        {
            b.lo[k] = std::min(b.lo[k], x[f[i]][k]);
            b.hi[k] = std::max(b.hi[k], x[f[i]][k]);
        }
    }
    return b;
}


bool overlap(const box& a, const box& b)
{
    for (int k = 0; k < 3; ++k)
    {
        if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
    }
    return true;
}


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


//- Triangles binned by the grid cells their boxes touch.
class triangleGrid
{
public:

    triangleGrid(const std::vector<point3>& x, const std::vector<triVerts>& triangles)
    {
        double edges = 0;
        for (const triVerts& f : triangles)
        {
            edges += std::sqrt(magSqr(x[f[1]] - x[f[0]]));
        }
        cell_ = triangles.empty() ? 1 : std::max(2*edges/triangles.size(), 1e-300);
        origin_ = x.empty() ? point3{0, 0, 0} : x[0];
        for (const point3& p : x)
        {
            for (int k = 0; k < 3; ++k) origin_[k] = std::min(origin_[k], p[k]);
        }
        std::vector<std::pair<long, label>> entries;
        for (label t = 0; t < label(triangles.size()); ++t)
        {
            forCells(boxOf(x, triangles[t]), [&](long c) { entries.push_back({c, t}); });
        }
        std::sort(entries.begin(), entries.end());
        for (const auto& [c, t] : entries)
        {
            keys_.push_back(c);
            items_.push_back(t);
        }
    }

    //- Each triangle in a cell the box touches (a triangle may come more
    //  than once).
    template<class Visit>
    void near(const box& b, const Visit& visit) const
    {
        forCells(b, [&](long c)
        {
            const auto [first, last] = std::equal_range(keys_.begin(), keys_.end(), c);
            for (auto it = first; it != last; ++it)
            {
                visit(items_[it - keys_.begin()]);
            }
        });
    }

private:

    template<class Visit>
    void forCells(const box& b, const Visit& visit) const
    {
        std::array<long, 3> lo, hi;
        for (int k = 0; k < 3; ++k)
        {
            lo[k] = long(std::floor((b.lo[k] - origin_[k])/cell_));
            hi[k] = long(std::floor((b.hi[k] - origin_[k])/cell_));
        }
        for (long i = lo[0]; i <= hi[0]; ++i)
        for (long j = lo[1]; j <= hi[1]; ++j)
        for (long k = lo[2]; k <= hi[2]; ++k)
        {
            // 21 bits an axis
            visit((i << 42) | (j << 21) | k);
        }
    }

    double cell_ = 1;
    point3 origin_{0, 0, 0};
    std::vector<long> keys_;
    std::vector<label> items_;
};

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
    // Moller-Trumbore on the segment's parameter, ends excluded
    const vector3 d = b - a;
    const vector3 e1 = q - p;
    const vector3 e2 = r - p;
    const vector3 h = cross(d, e2);
    const double det = dot(e1, h);
    const double scale = std::sqrt(magSqr(d)*magSqr(e1)*magSqr(e2));
    if (std::abs(det) <= 1e-12*scale) return false;
    const vector3 s = a - p;
    const double u = dot(s, h)/det;
    if (u < 0 || u > 1) return false;
    const vector3 w = cross(s, e1);
    const double v = dot(d, w)/det;
    if (v < 0 || u + v > 1) return false;
    const double t = dot(e2, w)/det;
    return t > 1e-9 && t < 1 - 1e-9;
}


std::vector<label> liftedCrossings
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles,
    const std::vector<bool>& moved
)
{
    std::vector<label> crossing(triangles.size(), 0);
    const triangleGrid grid(points, triangles);
    for (label t = 0; t < label(triangles.size()); ++t)
    {
        if (!moved[t]) continue;
        const box bt = boxOf(points, triangles[t]);
        grid.near(bt, [&](label u)
        {
            if
            (
                u == t
             || sharePoint(triangles[t], triangles[u])
             || !overlap(bt, boxOf(points, triangles[u]))
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
