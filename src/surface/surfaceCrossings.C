#include "surfaceCrossings.H"
#include "triangleCrossings.H"
#include "partitionVolume.H"
#include "pmshError.H"

void pmsh::checkSurfaceCrossings
(
    const std::vector<point3>& points,
    const FineSurface& surface,
    const std::vector<meshPatch>& patches,
    const label part,
    const std::string& failedSurfaceFile
)
{
    const std::vector<label> crossing = crossingTriangles
    (
        points, surface.triangles, std::vector<bool>(surface.triangles.size(), true), true
    );
    label first = -1;
    label nCrossing = 0;
    for (label t = 0; t < label(crossing.size()); ++t)
    {
        if (crossing[t] == 0) continue;
        ++nCrossing;
        if (first < 0) first = t;
    }
    if (first < 0)
    {
        return;
    }

    const label other = crossing[first] - 1;
    const triVerts& tri = surface.triangles[first];
    bool lifted = false;
    for (label t : {first, other})
    {
        for (label p : surface.triangles[t])
        {
            lifted = lifted || points[p] != surface.points[p];
        }
    }
    const point3 at = (1.0/3.0)*(points[tri[0]] + points[tri[1]] + points[tri[2]]);
    writeSurfaceStl(failedSurfaceFile, "partition" + std::to_string(part), points, surface.triangles);

    msg m;
    m   << "The surface of partition " << part << " crosses itself before"
        << " volume meshing: " << nCrossing << " of its triangles pass through"
        << " others, the first at " << str(at) << " on "
        << regionDescription(surface.region[first], patches) << ", through a"
        << " triangle on " << regionDescription(surface.region[other], patches)
        << ". No volume mesher can fill a surface that overlaps itself; it is"
        << " written to " << failedSurfaceFile << ".\n";
    if (lifted)
    {
        m   << "The tops of the prism layers cross there: in system/pmshDict"
            << " make the layers there thinner (layers, firstLayerThickness or"
            << " totalThickness), or lower maxThicknessToGapRatio";
    }
    else
    {
        m   << "The refined surface folds there: the geometry has features"
            << " smaller than the coarse cells round them. In system/pmshDict"
            << " reduce maxCellSize (or the patch's maxCellSize), or for an STL"
            << " raise curvatureRefinement or lower minCellSize";
    }
    throw FatalError(m, "pmsh::checkSurfaceCrossings");
}


// ************************************************************************* //
