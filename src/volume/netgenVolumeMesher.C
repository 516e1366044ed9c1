/*---------------------------------------------------------------------------*\
  pmshFoam: Netgen volume mesher (Netgen itself is behind netgenInterface).
\*---------------------------------------------------------------------------*/

#include "netgenVolumeMesher.H"
#include "netgenInterface.H"
#include "error.H"

// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

pmsh::TetMesh pmsh::netgenVolumeMesher::mesh
(
    const std::vector<point>& surfacePoints,
    const std::vector<triFace>& surfaceTriangles,
    const volumeMeshParameters& parameters
) const
{
    const std::string& what = parameters.what;
    checkClosedSurface(surfacePoints, surfaceTriangles, what);

    ng::meshParameters mp;
    mp.maxh = parameters.maxCellSize;
    mp.grading = parameters.grading;
    mp.optimisationSteps = parameters.optimisationSteps;

    ng::volumeMesh m = ng::surfaceVolumeMesh(surfacePoints, surfaceTriangles, mp, what);

    TetMesh result;
    result.points = std::move(m.points);
    result.tets = std::move(m.tets);

    verifyVolumeMesh(surfacePoints, surfaceTriangles, result, "Netgen's mesh of " + what);

    return result;
}


// ************************************************************************* //
