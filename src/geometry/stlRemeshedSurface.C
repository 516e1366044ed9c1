/*---------------------------------------------------------------------------*\
  pmshFoam: STL geometry: the coarse surface remeshed from the triangles
  (coarseSurface remesh; surfaceRemesh.H), for a volume mesher to fill.
\*---------------------------------------------------------------------------*/

#include "stlGeometry.H"
#include "stlGeometryImpl.H"
#include "surfaceRemesh.H"

#include <algorithm>

using Foam::Info;

pmsh::CoarseMesh pmsh::stlGeometry::remeshedSurface
(
    const coarseMeshParameters& parameters
) const
{
    const impl& d = *impl_;
    const stlSurface& s = d.surface;

    // Gap sizing changed the remesher's rounds of halving over the whole
    // surface: the DTC hull's max non-orthogonality went from 85 to 89,
    // with a face above checkMesh's skewness limit, the wrapped wigley
    // hull's from 60 to 71
    if (parameters.cellsAcrossGap > 0)
    {
        Info<< "    gap sizing: not on a remeshed coarse surface\n";
    }
    const std::vector<double> size = localTriangleSizes(parameters);

    // curvatureRefinement cells a radian: chords sag by at most
    // 1/(8 curvatureRefinement) of their length
    const double sagFraction =
        parameters.curvatureRefinement > 0 ? 1/(8*parameters.curvatureRefinement) : 0;
    const remeshedTriangulation remeshed = remeshSurface
    (
        s, d.allTriangles, d.region, d.featureEdges, size, sagFraction,
        parameters.minCellSize, what_
    );
    Info
        << "    coarse surface remeshed from the surface's " << s.nTriangles()
        << " triangles (coarseSurface " << parameters.coarseSurface.c_str()
        << "): " << label(remeshed.triangles.size()) << " triangles in "
        << remeshed.seconds << " s";
    if (remeshed.nRefined)
    {
        Info
            << ", " << remeshed.nRefined << " surface triangles' size halved in "
            << remeshed.nRounds - 1 << (remeshed.nRounds == 2 ? " round" : " rounds")
            << " where coarse triangles crossed or sagged (curvatureRefinement "
            << parameters.curvatureRefinement << ", minCellSize "
            << parameters.minCellSize << ")";
    }
    if (remeshed.nGradedBands)
    {
        Info
            << ", " << remeshed.nGradedBands << " band(s) graded where a size"
            << " met a coarser one more than twice its own";
    }
    if (remeshed.nBordersHeld)
    {
        Info
            << ", " << remeshed.nBordersHeld << " size(s) remeshed again with"
            << " their borders held (CGAL's remesher failed on exactly"
            << " collinear points there)";
    }
    Info<< '\n';

    CoarseMesh coarse;
    coarse.points = remeshed.points;
    coarse.boundary.reserve(remeshed.triangles.size());
    for (std::size_t t = 0; t < remeshed.triangles.size(); ++t)
    {
        const label r = remeshed.region[t];
        coarse.boundary.push_back({remeshed.triangles[t], d.regionSolid[r], r});
    }
    for (const std::string& name : s.solidNames)
    {
        coarse.patches.push_back({name});
    }
    return coarse;
}


// ************************************************************************* //
