/*---------------------------------------------------------------------------*\
  pmshFoam: a partition interface rises with the layer stacks beside it,
  and a flat unlayered wall slides with them (slideAlongFlatWalls).

  A partition interface meets the wall at a line of wall points, which the
  stacks lift by their thickness; the interface's points off the wall stay
  where the coarse mesh put them, often closer to the wall than the stacks
  are thick. Left there, the lifted interface triangles squash or the
  stacks' tops run through them: the layers had to be thinned there, and
  only where there is an interface, so the layers depended on the number
  of ranks, and the tets beside the squashed triangles were slivers.

  The interface is free (any surface between the parts will do), the
  layers are not: so the interface's own points move instead, those
  inside the domain (all their triangles are interface triangles). The
  first ring, the points with an edge to a lifted boundary point, rises
  by the mean lift of those neighbours, so that it ends above the stacks
  however close to the wall it was. Every other such point takes `decay`
  times the mean of its interface neighbours' displacement, in `sweeps`
  Jacobi sweeps from the first ring and the boundary points (their lift,
  0 where they have none), which stay fixed: a displacement that dies out
  a few rings from the wall (by about 0.63 a ring with 0.9), so that the
  rings keep their order. A point of an interface triangle that still
  squashes or crosses a stack's top is promoted by the validity rounds
  (wallLayers.C): it then rises as far as the neighbour that rises most,
  in the mean direction of its neighbours' rise (the largest neighbour's
  own direction would carry a far wall's normal round the interface).
  Should the risen interface still cross itself where no stack is there
  to thin (thick stacks in a narrow pipe, whose interface is squeezed
  from all sides; a groove whose walls lift toward each other), the
  rounds scale down the shift of the crossing triangles' points, on every
  rank alike (wallLayers.C, selfCrossingScale).

  Every rank that holds a point computes the same bits: a sweep's mean is
  over the point's interface triangles of all ranks (stars.gather), each
  triangle counted once (both parts hold an interface triangle, and give
  the same value for it, from displacements that agree), summed in the
  order of their keys.
\*---------------------------------------------------------------------------*/
#include "layerStars.H"
#include "wallLayers.H"

#include <algorithm>
#include <cmath>

namespace pmsh
{

namespace
{

constexpr int sweeps = 12;
constexpr double decay = 0.9;

//- Wall triangles within this of one plane (cos 0.25 degrees) let their
//  points slide in it: a flat wall, projected onto exactly
constexpr double flatCos = 0.99999;

//- The sliding points' moves in their planes: `sweeps` Jacobi sweeps of
//  `decay` times the mean of their wall neighbours' moves, from the lifts
//  of the stacks' feet beside them (u), which stay fixed. Where a stack
//  ends against an unlayered wall, its foot slides along the wall by its
//  thickness; the wall's points beside it follow, so that its triangles
//  are not squashed. A cylinder spanning a channel, 5 layers on it: the
//  squashed triangles thinned 33-208 points and gave the worst tets;
//  with the slide none thins. Moving the first ring by its neighbours'
//  whole lift, as the interface does, pushed the squash a ring out: max
//  non-orthogonality up to 73 against 65 (bench: three sizes, both
//  meshers).
void slideAlongFlatWalls
(
    const layerStars& stars,
    const std::vector<vector3>& plane,
    std::vector<vector3>& u
)
{
    const layerSurface& surface = stars.surface();
    const label nPoints = surface.points.size();
    for (int sweep = 0; sweep < sweeps; ++sweep)
    {
        const auto around = stars.gather
        (
            [&](label t, label p, label& tag, vector3& value)
            {
                if (magSqr(plane[p]) == 0 || stars.isInterface(t)) return false;
                tag = 0;
                value = {0, 0, 0};
                for (const label q : surface.triangles[t])
                {
                    if (q != p) value = value + 0.5*u[q];
                }
                return true;
            }
        );
        std::vector<vector3> next(u);
        for (label p = 0; p < nPoints; ++p)
        {
            if (magSqr(plane[p]) == 0) continue;
            // Wall triangles only: each is held by one part, counted once
            vector3 sum{0, 0, 0};
            for (const keyedContribution& c : around[p])
            {
                sum = sum + c.value;
            }
            const label n = around[p].size();
            const vector3 mean = n > 0 ? (decay/n)*sum : vector3{0, 0, 0};
            next[p] = mean - dot(mean, plane[p])*plane[p];
        }
        u.swap(next);
    }
}

} // End anonymous namespace


// A point slides when it has no layers, is not inside the domain, and its
// wall triangles on every rank lie in one plane and one patch: it then
// stays on the wall, and the patch keeps its border.
std::vector<vector3> slidingPlanes
(
    const layerStars& stars,
    const wallLayers& layers,
    const std::vector<bool>& interfaceOnly
)
{
    const layerSurface& surface = stars.surface();
    const label nPoints = surface.points.size();
    const auto candidate = [&](label t, label p)
    {
        return !interfaceOnly[p] && layers.nLayers[p] == 0 && !stars.isInterface(t);
    };
    // Unit normals summed per patch: one patch, one sum (a wall triangle
    // is held by one part, so each counts once)
    const auto perPatch = stars.sums
    (
        [&](label t, label p, label& tag, vector3& value)
        {
            if (!candidate(t, p)) return false;
            tag = surface.region[t];
            value = normalised(stars.areaVector(t));
            return true;
        }
    );
    std::vector<vector3> normal(nPoints, vector3{0, 0, 0});
    for (label p = 0; p < nPoints; ++p)
    {
        if (perPatch[p].size() == 1)
        {
            normal[p] = normalised(perPatch[p][0].second);
        }
    }
    const std::vector<double> bent = stars.minimum
    (
        [&](label t, label p)
        {
            if (!candidate(t, p) || magSqr(normal[p]) == 0) return layerStars::none;
            return dot(normalised(stars.areaVector(t)), normal[p]) >= flatCos
                ? layerStars::none : -1.0;
        }
    );
    bool any = false;
    for (label p = 0; p < nPoints; ++p)
    {
        if (bent[p] < 0)
        {
            normal[p] = {0, 0, 0};
        }
        any = any || magSqr(normal[p]) > 0;
    }
    return stars.anyRank(any) ? normal : std::vector<vector3>();
}


std::vector<vector3> interfaceShift
(
    const layerStars& stars,
    const wallLayers& layers,
    const std::vector<bool>& interfaceOnly,
    const std::vector<bool>& promoted,
    const std::vector<vector3>& slidePlanes,
    const std::vector<double>& scale
)
{
    const layerSurface& surface = stars.surface();
    const auto& x = surface.points;
    const label nPoints = x.size();
    std::vector<vector3> u(nPoints, vector3{0, 0, 0});
    bool moves = false;
    for (label p = 0; p < nPoints; ++p)
    {
        if (!interfaceOnly[p] && layers.nLayers[p] > 0)
        {
            u[p] = layers.topPoint(x, p) - x[p];
            moves = true;
        }
    }
    if (!stars.anyRank(moves))
    {
        return {};
    }

    // Flat walls first: their slid points then hold the interface's foot
    const bool slides = !slidePlanes.empty();
    if (slides)
    {
        slideAlongFlatWalls(stars, slidePlanes, u);
    }

    // The first ring: the points with a lifted boundary neighbour rise as
    // far as those do (their mean lift), whatever their height, so that
    // they end above the stacks; they stay so in the sweeps
    std::vector<bool> anchored(nPoints, false);
    {
        const auto around = stars.gather
        (
            [&](label t, label p, label& tag, vector3& value)
            {
                if (!interfaceOnly[p]) return false;
                tag = 0;
                value = {0, 0, 0};
                for (const label q : surface.triangles[t])
                {
                    if (q != p && !interfaceOnly[q] && layers.nLayers[q] > 0)
                    {
                        ++tag;
                        value = value + u[q];
                    }
                }
                return true;
            }
        );
        for (label p = 0; p < nPoints; ++p)
        {
            vector3 sum{0, 0, 0};
            label n = 0;
            for (std::size_t i = 0; i < around[p].size(); ++i)
            {
                const keyedContribution& c = around[p][i];
                if (i > 0 && c.key == around[p][i - 1].key && c.tag == around[p][i - 1].tag) continue;
                sum = sum + c.value;
                n += c.tag;
            }
            if (n > 0)
            {
                u[p] = (1.0/n)*sum;
                anchored[p] = true;
            }
        }
    }

    for (int sweep = 0; sweep < sweeps; ++sweep)
    {
        const auto around = stars.gather
        (
            [&](label t, label p, label& tag, vector3& value)
            {
                if (!interfaceOnly[p]) return false;
                tag = 0;
                value = {0, 0, 0};
                double largest = 0;
                for (const label q : surface.triangles[t])
                {
                    if (q == p) continue;
                    value = value + 0.5*u[q];
                    largest = std::max(largest, magSqr(u[q]));
                }
                // A promoted point's: the mean's direction, the largest length
                if (promoted[p]) value = std::sqrt(largest)*normalised(value);
                return true;
            }
        );
        std::vector<vector3> next(u);
        for (label p = 0; p < nPoints; ++p)
        {
            if (!interfaceOnly[p] || anchored[p]) continue;
            vector3 sum{0, 0, 0}, largest{0, 0, 0};
            label n = 0;
            for (std::size_t i = 0; i < around[p].size(); ++i)
            {
                const vector3& v = around[p][i].value;
                if (magSqr(v) > magSqr(largest)) largest = v;
                if (i > 0 && around[p][i].key == around[p][i - 1].key) continue;
                sum = sum + v;
                ++n;
            }
            // A promoted point whose neighbours rise in opposed directions
            // (their mean much shorter than they are) has no direction to
            // rise in: it keeps the mean
            const vector3 mean = n > 0 ? (decay/n)*sum : vector3{0, 0, 0};
            next[p] =
                promoted[p] && 4*magSqr(mean) > magSqr(largest)
              ? std::sqrt(magSqr(largest))*normalised(sum)
              : mean;
        }
        u.swap(next);
    }
    for (label p = 0; p < nPoints; ++p)
    {
        if (interfaceOnly[p])
        {
            u[p] = scale[p]*u[p];
        }
        else if (!slides || magSqr(slidePlanes[p]) == 0)
        {
            u[p] = {0, 0, 0};
        }
    }
    return u;
}


std::vector<bool> interfaceOnlyPoints(const layerStars& stars)
{
    const std::vector<double> boundary = stars.minimum
    (
        [&](label t, label) { return stars.isInterface(t) ? layerStars::none : -1.0; }
    );
    std::vector<bool> only(boundary.size());
    for (std::size_t p = 0; p < boundary.size(); ++p)
    {
        only[p] = boundary[p] == layerStars::none;
    }
    return only;
}

} // End namespace pmsh


// ************************************************************************* //
