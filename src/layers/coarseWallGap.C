/*---------------------------------------------------------------------------*\
  pmshFoam: the gap query over the coarse mesh (coarseWallGap.H).
\*---------------------------------------------------------------------------*/

#include "coarseWallGap.H"

#include <algorithm>
#include <limits>


pmsh::coarseWallGap::coarseWallGap
(
    const CoarseMesh& coarse,
    const std::map<label, layerSpecification>& specs,
    double reach
)
:
    points_(coarse.points),
    reach_(reach),
    triangles_(trianglesOf(coarse, specs)),
    grid_(points_, triangles_, reach)
{}


double pmsh::coarseWallGap::operator()
(
    const point3& origin,
    const vector3& d,
    double skip
) const
{
    const point3 end = origin + reach_*d;
    box3 segment{origin, origin};
    for (int k = 0; k < 3; ++k)
    {
        segment.lo[k] = std::min(origin[k], end[k]);
        segment.hi[k] = std::max(origin[k], end[k]);
    }
    double nearest = std::numeric_limits<double>::infinity();
    grid_.near(segment, [&](label i)
    {
        const triVerts& f = triangles_[i];
        const point3& p = points_[f[0]];
        const bool boundary = i < nBoundary_;
        if (boundary && dot(cross(points_[f[1]] - p, points_[f[2]] - p), d) <= 0) return;
        const double t = rayTriangle(origin, d, p, points_[f[1]], points_[f[2]]);
        if (t > skip && t <= reach_) nearest = std::min(nearest, t);
    });
    return nearest;
}


std::vector<pmsh::triVerts> pmsh::coarseWallGap::trianglesOf
(
    const CoarseMesh& coarse,
    const std::map<label, layerSpecification>& specs
)
{
    // The box of the layered faces, grown by the reach and by their
    // longest edge (the fine wall's points are projected off the coarse
    // faces, by less than an edge)
    const auto& x = coarse.points;
    constexpr double huge = std::numeric_limits<double>::max();
    box3 layered{{huge, huge, huge}, {-huge, -huge, -huge}};
    bool any = false;
    double longest = 0;
    for (const coarseBoundaryFace& f : coarse.boundary)
    {
        if (!specs.count(f.patch)) continue;
        const box3 b = boxOf(x, f.v);
        for (int k = 0; k < 3; ++k)
        {
            layered.lo[k] = std::min(layered.lo[k], b.lo[k]);
            layered.hi[k] = std::max(layered.hi[k], b.hi[k]);
            longest = std::max(longest, b.hi[k] - b.lo[k]);
        }
        any = true;
    }
    for (int k = 0; k < 3; ++k)
    {
        layered.lo[k] -= reach_ + longest;
        layered.hi[k] += reach_ + longest;
    }
    const auto withinReach = [&](const triVerts& f)
    {
        return any && boxOf(x, f).overlaps(layered);
    };

    std::vector<triVerts> triangles;
    for (const coarseBoundaryFace& f : coarse.boundary)
    {
        if (withinReach(f.v)) triangles.push_back(f.v);
    }
    nBoundary_ = triangles.size();
    for (const coarseZoneFace& f : coarse.zoneFaces)
    {
        if (withinReach(f.v)) triangles.push_back(f.v);
    }
    return triangles;
}


// ************************************************************************* //
