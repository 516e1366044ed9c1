/*---------------------------------------------------------------------------*\
  pmshFoam: Gmsh HXT volume mesher: the choice between the two ways into
  HXT (src/hxt/hxtBackends.H), then the quality pass (src/qualityPass/).
\*---------------------------------------------------------------------------*/

#include "hxtVolumeMesher.H"
#include "hxtBackends.H"
#include "pmshError.H"
#include "tetQualityPass.H"
#include "gradientCondition.H"
#include "meshingStep.H"
#include "netgenInterface.H"

#include <string>


// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * //

namespace pmsh
{
    defineTypeNameAndDebug(hxtVolumeMesher, 0);
    addToRunTimeSelectionTable(VolumeMesher, hxtVolumeMesher, word);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

bool pmsh::hxtVolumeMesher::dependsOnTheHeap() const
{
    return !hxtLibraryAvailable();
}


pmsh::TetMesh pmsh::hxtVolumeMesher::generate
(
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const volumeMeshParameters& parameters
) const
{
    const shellVolumes volumes = findShellVolumes(surfacePoints, surfaceTriangles);
    if (volumes.volumes.empty())
    {
        throw FatalError
        (
            msg() << "Gmsh HXT could not mesh the volume of " << parameters.what
                << ": none of its " << volumes.shells.size() << " closed shells"
                " encloses a positive volume (are its triangles wound inwards?)",
            "pmsh::hxtVolumeMesher::generate"
        );
    }

    reportMeshingStep
    (
        parameters.optimisationSteps > 0
      ? "Gmsh HXT: tetrahedra, then HXT's optimiser"
      : "Gmsh HXT: tetrahedra"
    );
    TetMesh result =
        hxtLibraryAvailable()
      ? hxtLibraryMesh(surfacePoints, surfaceTriangles, volumes, parameters)
      : gmshModelMesh(surfacePoints, surfaceTriangles, volumes, parameters);

    // HXT's interior points where Netgen's smoothing puts them, when asked
    // (netgenSmoothingFromSteps): meshes the tutorials' schemes converge
    // on where HXT's own points made simpleFoam blow up, at 1.46x the time
    if (parameters.netgenSmoothing)
    {
        reportMeshingStep("Netgen's smoothing of HXT's interior points");
        ng::smoothInteriorPoints
        (
            result.points, result.tets, surfaceTriangles,
            ng::meshParametersOf(parameters), parameters.what
        );
    }

    // HXT's worst cells are far worse than Netgen's: improve them, with
    // the partition's surface fixed; with no steps, remove only the slivers
    // that checkMesh (and the contract) would refuse
    const label nSurface = label(surfacePoints.size());
    if (parameters.optimisationSteps > 0)
    {
        reportMeshingStep
        (
            "quality pass on " + std::to_string(result.tets.size()) + " cells, "
          + std::to_string(parameters.optimisationSteps) + " steps"
        );
        improveWorstCells
        (
            result, nSurface, surfaceTriangles,
            parameters.interfaceTriangles, parameters.optimisationSteps
        );
        // Then the tets no face measure sees are bad for the solver: a
        // tet of fair faces whose leastSquares gradient is badly posed
        // seeded a local blow-up of simpleFoam (gradientCondition.H)
        if (parameters.mendGradients)
        {
            reportMeshingStep("points moved where leastSquares gradients are badly posed");
            mendGradientConditions(result, nSurface);
        }
    }
    else
    {
        reportMeshingStep("sliver removal on " + std::to_string(result.tets.size()) + " cells");
        removeSlivers(result, nSurface, surfaceTriangles, parameters.interfaceTriangles);
    }

    return result;
}


// ************************************************************************* //
