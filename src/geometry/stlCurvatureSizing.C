/*---------------------------------------------------------------------------*\
  pmshFoam: STL geometry: the cell sizes that curvature asks for, graded
  over the surface (see stlGeometry.H).
\*---------------------------------------------------------------------------*/

#include "stlGeometry.H"
#include "stlGeometryImpl.H"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>

// * * * * * * * * * * * * * * Curvature sizing  * * * * * * * * * * * * * //

pmsh::stlGeometry::curvatureSizing pmsh::stlGeometry::curvatureSizes
(
    double curvatureRefinement,
    double minCellSize,
    double maxCellSize,
    double grading
) const
{
    const impl& d = *impl_;
    const stlSurface& s = d.surface;
    const label np = label(s.points.size());

    curvatureSizing result;
    result.solids.resize(s.solidNames.size());
    if (!(curvatureRefinement > 0))
    {
        return result;
    }

    // Each point's size from the curvature across its edges: the radius
    // over curvatureRefinement, never below the floor
    std::vector<double> h(np, maxCellSize);
    std::vector<char> atFloor(np, 0);
    for (const impl::curvedEdge& e : d.curvedEdges)
    {
        const double wanted = e.radius/curvatureRefinement;
        const double size = std::max(minCellSize, wanted);
        for (label v : {e.a, e.b})
        {
            if (size < h[v])
            {
                h[v] = size;
                atFloor[v] = wanted < minCellSize;
            }
        }
    }

    // Graded over the surface as `grading` lets sizes grow (Netgen's own
    // size tree grades STL sizes at 0.3 in space whatever grading says):
    // h(v) <= h(u) + grading |uv| along the STL's edges, smallest first
    std::vector<std::vector<label>> neighbours(np);
    for (const triVerts& f : s.triangles)
    {
        for (int k = 0; k < 3; ++k)
        {
            neighbours[f[k]].push_back(f[(k + 1) % 3]);
            neighbours[f[(k + 1) % 3]].push_back(f[k]);
        }
    }
    using sizeAt = std::pair<double, label>;
    std::priority_queue<sizeAt, std::vector<sizeAt>, std::greater<sizeAt>> front;
    for (label v = 0; v < np; ++v)
    {
        if (h[v] < maxCellSize)
        {
            front.push({h[v], v});
        }
    }
    while (!front.empty())
    {
        const sizeAt top = front.top();
        front.pop();
        if (top.first > h[top.second])
        {
            continue;
        }
        for (label u : neighbours[top.second])
        {
            const double graded =
                top.first
              + grading*std::sqrt(magSqr(s.points[u] - s.points[top.second]));
            if (graded < h[u])
            {
                h[u] = graded;
                atFloor[u] = 0;
                front.push({graded, u});
            }
        }
    }

    // Netgen's size is a tree over space: a point's size binds there
    std::vector<char> counted(np, 0);
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        const triVerts& f = s.triangles[t];
        curvatureSizing::solidSizes& solid = result.solids[s.solid[t]];
        double mean = 0;
        for (label v : f)
        {
            mean += h[v]/3;
            if (h[v] < maxCellSize && !counted[v])
            {
                counted[v] = 1;
                result.points.push_back({s.points[v], h[v]});
                ++solid.nPoints;
                solid.nAtFloor += atFloor[v];
                solid.smallest = std::min(solid.smallest, h[v]);
            }
        }
        // Equilateral triangles of edge h cover sqrt(3)/4 h^2 each
        const double area = 0.5*std::sqrt(magSqr(s.areaNormal(t)));
        solid.faces += area*(4/std::sqrt(3.0))/(mean*mean);
        solid.uniformFaces += area*(4/std::sqrt(3.0))/(maxCellSize*maxCellSize);
    }
    return result;
}


// ************************************************************************* //
