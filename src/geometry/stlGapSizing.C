/*---------------------------------------------------------------------------*\
  pmshFoam: STL geometry: the cell sizes that the domain's gaps ask for
  (see stlGeometry.H).

  A slot of the domain narrower than the cells round it is spanned by one
  coarse tet, flat as the slot, and refinement halves it without making it
  rounder: two blocks 0.06 apart, their patches at 0.2, had edges 1.6
  times the slot's width in it and a max non-orthogonality of 71.8
  degrees (56.4 with gap sizing). The rays find such gaps from either
  side; Netgen's size tree then grades the sizes into the gap's interior.
\*---------------------------------------------------------------------------*/

#include "stlGeometry.H"
#include "stlGeometryImpl.H"
#include "localSize.H"

#include <algorithm>
#include <chrono>
#include <cmath>

using Foam::Info;

// * * * * * * * * * * * * * * * * Gap sizing  * * * * * * * * * * * * * * //

namespace
{

using namespace pmsh;

//- The normals of a wall and of the one it faces across a gap are within
//  this angle of opposite (cos 60 degrees): a wider wedge is a corner
constexpr double facingCos = 0.5;

//- The smallest size a gap asks for, as a fraction of the local size:
//  gaps asking for less (a wedge's apex) would refine without bound
constexpr double floorFraction = 0.25;

//- Distance along dir from x to the first triangle of s the ray meets
//  within reach, and whether that triangle faces back along dir
struct rayHit
{
    double distance = -1;
    bool facesBack = false;
};

rayHit firstHit
(
    const stlSurface& s,
    const boxTree& triangles,
    label from,
    const point3& x,
    const vector3& dir,
    double reach
)
{
    rayHit hit;
    double nearest = reach;
    triangles.alongRay
    (
        x, dir, nearest,
        [&](label t)
        {
            if (t == from)
            {
                return;
            }
            const triVerts& f = s.triangles[t];
            const double d = rayHitsTriangle
            (
                x, dir, s.points[f[0]], s.points[f[1]], s.points[f[2]]
            );
            if (d > 0 && d <= nearest)
            {
                nearest = d;
                const vector3 n = s.areaNormal(t);
                hit.distance = d;
                hit.facesBack = dot(n, dir) > facingCos*std::sqrt(magSqr(n));
            }
        }
    );
    return hit;
}

} // End anonymous namespace


pmsh::stlGeometry::gapSizing pmsh::stlGeometry::gapSizes
(
    double cellsAcrossGap,
    const std::vector<double>& localSize
) const
{
    const impl& d = *impl_;
    const stlSurface& s = d.surface;

    const auto start = std::chrono::steady_clock::now();
    gapSizing result;
    if (!(cellsAcrossGap > 0))
    {
        return result;
    }
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        const double h = localSize[t];

        // Normals point out of the domain: its gaps lie along -n
        const vector3 n = s.areaNormal(t);
        const double area2 = std::sqrt(magSqr(n));
        if (!(area2 > 0))
        {
            continue;
        }
        const vector3 into = (-1/area2)*n;

        // Starts pulled a little into the triangle, off its neighbours
        const triVerts& f = s.triangles[t];
        const point3 &a = s.points[f[0]], &b = s.points[f[1]], &c = s.points[f[2]];
        const point3 centre = (1.0/3.0)*(a + b + c);
        const double reach = cellsAcrossGap*h;
        bool inGap = false;
        const auto cast = [&](const point3& sample)
        {
            const point3 x = sample + 1e-3*(centre - sample);
            const rayHit hit = firstHit(s, d.allTriangles, t, x, into, reach);
            if (!hit.facesBack)
            {
                return;
            }
            // A gap that not even one cell of the floor size fits is a
            // contact, not a channel: refining round it only brings the
            // two sides' points closer (sized, the wrapped motorBike's
            // 1e-5 gaps gave its coarse fill slivers of aspect ratio 5e10)
            if (hit.distance < floorFraction*h)
            {
                ++result.nContacts;
                return;
            }
            const double wanted = hit.distance/cellsAcrossGap;
            const double size = std::max(floorFraction*h, wanted);
            if (size >= h)
            {
                return;
            }
            inGap = true;
            result.points.push_back({x, size});
            result.nAtFloor += wanted < floorFraction*h;
            if (hit.distance < result.narrowest)
            {
                result.narrowest = hit.distance;
                result.narrowestAt = x;
            }
        };
        const double longest = std::sqrt
        (
            std::max({magSqr(b - a), magSqr(c - b), magSqr(a - c)})
        );
        if (longest < h/2)
        {
            cast(centre);
        }
        else
        {
            sampleTriangle(a, b, c, h/2, cast);
        }
        result.nTriangles += inGap;
    }
    result.seconds = std::chrono::duration<double>
    (
        std::chrono::steady_clock::now() - start
    ).count();
    return result;
}


void pmsh::stlGeometry::gapSizing::log(double cellsAcrossGap) const
{
    Info<< "    gap sizing (cellsAcrossGap " << cellsAcrossGap << "): ";
    if (points.empty())
    {
        Info<< "no gap narrower than " << cellsAcrossGap << " local sizes";
    }
    else
    {
        Info
            << nTriangles << " STL triangles face another across a narrower"
            << " gap, " << label(points.size()) << " sizes set, " << nAtFloor
            << " held at a quarter of the local size; the narrowest gap sized "
            << narrowest << " at (" << narrowestAt[0] << ' ' << narrowestAt[1]
            << ' ' << narrowestAt[2] << ")";
    }
    if (nContacts)
    {
        Info
            << "; " << nContacts << " ray starts at contacts narrower than a"
            << " quarter of the local size, left as they are";
    }
    Info<< " (" << seconds << " s)\n";
}


// ************************************************************************* //
