/*---------------------------------------------------------------------------*\
  pmshFoam: Netgen volume mesher (Netgen itself is behind netgenInterface).
\*---------------------------------------------------------------------------*/

#include "netgenVolumeMesher.H"
#include "netgenInterface.H"
#include "pmshError.H"

// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

pmsh::TetMesh pmsh::netgenVolumeMesher::generate
(
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const volumeMeshParameters& parameters
) const
{
    ng::meshParameters mp;
    mp.maxh = parameters.maxCellSize;
    mp.grading = parameters.grading;
    mp.optimisationSteps = parameters.optimisationSteps;
    mp.regions = parameters.regions;

    ng::volumeMesh m =
        ng::surfaceVolumeMesh(surfacePoints, surfaceTriangles, mp, parameters.what);

    TetMesh result;
    result.points = std::move(m.points);
    result.tets = std::move(m.tets);
    return result;
}


// ************************************************************************* //
