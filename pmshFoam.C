/*---------------------------------------------------------------------------*\
  =========                 |
  \\      /  F ield         | pmshFoam: massive parallel tetrahedral meshes
   \\    /   O peration     | for OpenFOAM
    \\  /    A nd           |
     \\/     M anipulation  |
-------------------------------------------------------------------------------
Application
    pmshFoam

Group
    grpMeshGenerationUtilities

Description
    Parallel tetrahedral mesh generator following the PMSH method: a coarse
    Netgen mesh of a CSG (.geo) or STL geometry, a partition of it by the
    decomposition method of system/decomposeParDict (metis by default),
    r levels of refinement of each partition's surface with projection onto
    the geometry, prism layers grown on the walls that ask for them (the
    volume mesher fills the surface lifted to their tops), volume remeshing
    of each partition (Netgen or HXT, each attempt in a child process of
    its rank, so that a mesher's crash is a failed attempt that is retried
    another way), and global point numbering through integer barycentric
    ids (no floating-point matching); then whole fine cells move between
    ranks until every rank has its share. Several CSG top-level solids become
    cellZones, the surfaces between them faceZones (splitMeshRegions
    -cellZones makes regions of them).

    Serial runs write constant/polyMesh. Parallel runs write
    processorN/constant/polyMesh (or processors<N>/ with the collated
    fileHandler) with the procAddressing files, processorN/<startTime>/
    fields from the case's templates and system/decomposeParDict, so that a
    solver runs with -parallel at once, without decomposePar.

Usage
    \b pmshFoam [OPTION]
    \b mpirun -np N pmshFoam -parallel [OPTION]

    Options:
      - \par -dict \<file\>
        Alternative mesh dictionary (default system/pmshDict)

      - \par -overwrite
        Replace an existing mesh (only once meshing succeeded on every rank)

      - \par -noMemoryCheck
        Go on even when the memory estimate after the coarse mesh says the
        fine mesh cannot fit in this machine's memory

      - \par -decomposeParDict \<file\>
        Alternative decomposition dictionary

    Reads system/pmshDict (geometry, maxCellSize, grading, refinementLevels,
    coarseMesher, volumeMesher, optimisationSteps, volumeMesherThreads,
    curvatureRefinement, minCellSize, coarseTimeLimit, patches,
    refinementRegions: README.md says what each does) and, as every
    OpenFOAM utility, system/controlDict (writeFormat, writePrecision,
    startTime) and the fileHandler settings.

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "Time.H"

#include "caseControl.H"
#include "caseInputs.H"
#include "caseOutput.H"
#include "coarseMeshGeneration.H"
#include "Communicator.H"
#include "failTogether.H"
#include "fieldTemplates.H"
#include "foamShims.H"
#include "fineMeshForecast.H"
#include "Geometry.H"
#include "globalNumbering.H"
#include "layerStage.H"
#include "memoryEstimate.H"
#include "meshPieces.H"
#include "meshSettings.H"
#include "partitionCoarseMesh.H"
#include "partitionVolume.H"
#include "mesherChild.H"
#include "processSettings.H"
#include "patchTypes.H"
#include "runSummary.H"
#include "stageData.H"
#include "stageParameters.H"
#include "stageReports.H"
#include "stageLog.H"
#include "surfaceCrossings.H"
#include "surfaceRefinement.H"
#include "writeRankMesh.H"

#include <mpi.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>
#include <numeric>
#include <optional>

using namespace Foam;

// End MPI (also a serial run's, started for Netgen) and exit. A failure
// every rank agreed on ends MPI normally too: UPstream::exit would abort
// for a non-zero code, and returning from main would let argList end a
// parallel run with 0.
[[noreturn]] static void endRun(int exitCode)
{
    if (exitCode)
    {
        MPI_Finalize();
        std::exit(exitCode);
    }
    pmsh::foam::endNullMPI();
    UPstream::exit(0);
    std::exit(0);
}

// Stage 3b, where a patch asks for prism layers: the stacks on this rank's
// fine surface, and their report for the log and summary.json.
static pmsh::wallLayers layerStage
(
    const pmsh::Communicator& comm,
    pmsh::stageLog& stages,
    const pmsh::CoarseMesh& coarse,
    const std::vector<pmsh::label>& cellPart,
    const pmsh::FineSurface& surface,
    const std::map<pmsh::label, pmsh::layerSpecification>& specs,
    const pmsh::meshSettings& settings,
    const std::string& caseDir,
    pmsh::layerReport& report
)
{
    pmsh::wallLayers layers;
    if (specs.empty())
    {
        return layers;
    }
    stages.begin("layers", "Stage 3b: prism layers");
    pmsh::failTogether(comm, [&]
    {
        layers = pmsh::growLayers
        (
            comm, coarse, cellPart, surface, specs, settings.refinementLevels
        );
    });
    report = pmsh::reportLayers(comm, layers, surface, coarse, specs);
    pmsh::writeThinnedLayers
    (
        comm, layers, surface, caseDir + "/postProcessing/pmshFoam/thinnedLayers.vtk"
    );
    stages.end();
    return layers;
}


// Stage 4: this rank's volume filled with tets, piece by piece and zone
// by zone (with layers: the surface lifted to their tops). nTets: the
// tets of all ranks.
static pmsh::partitionVolumeResult volumeStage
(
    const pmsh::Communicator& comm,
    pmsh::stageLog& stages,
    const pmsh::meshSettings& settings,
    const pmsh::CoarseMesh& coarse,
    const pmsh::FineSurface& surface,
    const pmsh::wallLayers& layers,
    const std::string& caseDir,
    std::int64_t& nTets
)
{
    stages.begin("volume", "Stage 4: volume meshing (" + settings.volumeMesher + ")");
    pmsh::partitionVolumeResult volume;
    const std::vector<pmsh::point3> lifted = pmsh::liftedSurfacePoints(layers, surface.points);
    pmsh::failTogether(comm, [&]
    {
        const std::vector<pmsh::point3>& points = lifted.empty() ? surface.points : lifted;
        const std::string failedSurface = pmsh::failedSurfaceFile(caseDir, comm.rank());
        pmsh::checkSurfaceCrossings(points, surface, coarse.patches, comm.rank(), failedSurface);
        volume = pmsh::meshVolumeInPieces
        (
            pmsh::VolumeMesher::NewAll(settings.volumeMesher),
            points,
            surface.triangles, {surface.zone, coarse.zones, surface.piece, surface.ids},
            pmsh::volumeParameters(settings, surface, comm.rank()),
            failedSurface,
            "Try a smaller maxCellSize (a finer coarse mesh) or another"
            " volumeMesher in system/pmshDict."
        );
    });
    nTets = pmsh::logVolumeMeshing(comm, volume);
    stages.end();
    return volume;
}


// Stage 7: the rank's mesh, its fields and procAddressing, committed
// once every rank has written; the decomposeParDict of a parallel run.
static pmsh::writtenMesh writeStage
(
    const pmsh::Communicator& comm,
    pmsh::stageLog& stages,
    const pmsh::caseControl& control,
    const pmsh::caseInputs& inputs,
    pmsh::rankTets& share,
    const pmsh::CoarseMesh& coarse,
    const std::vector<std::array<pmsh::label, 2>>& zonePairs,
    const pmsh::partitionVolumeResult& volume,
    const std::vector<pmsh::fieldTemplate>& fieldTemplates,
    const Time& runTime,
    pmsh::caseOutput& output
)
{
    stages.begin
    (
        "write",
        "Stage 7: writing "
      + std::string(runTime.writeFormat() == IOstream::BINARY ? "binary" : "ascii")
      + " through the " + std::string(control.outputFileHandler) + " fileHandler"
    );
    const pmsh::writtenMesh written = pmsh::writeRankMesh
    (
        comm, share, coarse, zonePairs, volume, fieldTemplates,
        control.outputFileHandler, output
    );
    output.commit();
    if (comm.parallel())
    {
        pmsh::writeDecomposeParDict(runTime, inputs.decomposition);
    }
    pmsh::logWritten(comm, runTime.globalPath(), written.sizes);
    pmsh::logMeshQuality(comm, written.quality);
    stages.end();

    return written;
}


// Stage 1's title: who makes the coarse surface, and who fills it.
static std::string coarseStageTitle
(
    const pmsh::meshSettings& settings,
    const pmsh::Geometry& geometry
)
{
    return
        std::string("Stage 1: coarse mesh (")
      + (
            geometry.remeshesCoarseSurface(settings.coarseSurface)
          ? "surface remeshed, "
          : "Netgen surface, "
        )
      + settings.coarseMesher + " volume) of " + settings.geometryText();
}


// The stages of the PMSH method, from the case's inputs to the written
// mesh and the summary. A failure stops every rank together
// (pmsh::collectiveFailure). caseTime is left to the caller.
static void meshCase
(
    const pmsh::Communicator& comm,
    const argList& args,
    std::optional<Time>& caseTime
)
{
    pmsh::caseControl control;
    pmsh::failTogether(comm, [&]
    {
        control = pmsh::readCaseControl(args);
    });
    Info<< "Create time\n" << endl;
    Time& runTime =
        caseTime.emplace(control.controlDict, args.rootPath(), args.caseName());
    // Errors of every rank are agreed on before anyone stops (failTogether)
    FatalError.throwExceptions();
    FatalIOError.throwExceptions();

    // Everything is read and validated before any meshing starts
    const pmsh::caseInputs inputs = pmsh::readCaseInputs(comm, args, runTime);
    const pmsh::meshSettings& settings = inputs.settings;
    #include "createFields.H"
    std::optional<pmsh::caseOutput> output;
    pmsh::failTogether(comm, [&]
    {
        output.emplace(comm, runTime, pmsh::foam::found(args, "overwrite"));
    });

    pmsh::stageLog stages(comm);

    stages.begin("coarse", coarseStageTitle(settings, *inputs.geometry));
    pmsh::CoarseMesh coarse = pmsh::generateCoarseMesh
    (
        comm, *inputs.geometry, pmsh::coarseParameters(settings, runTime.globalPath())
    );
    pmsh::setPatchTypes(coarse, settings);
    const std::vector<std::array<pmsh::label, 2>> zonePairs = pmsh::zonePairsOf(coarse);
    pmsh::logCoarseMesh(coarse);
    pmsh::logLocalSizes(coarse, settings);
    std::map<pmsh::label, pmsh::layerSpecification> layerSpecs;
    // The patches are known now: the fields must cover them, as OpenFOAM takes them
    pmsh::checkFieldTemplates(comm, coarse.patches, fieldTemplates, *output);
    pmsh::failTogether(comm, [&]
    {
        layerSpecs = pmsh::layerSpecsOf(settings, coarse);
    });
    pmsh::fineMeshForecast forecast = pmsh::forecastFineMesh
    (
        comm, coarse, settings, layerSpecs, !pmsh::foam::found(args, "noMemoryCheck")
    );
    stages.end();

    stages.begin("partition", "Stage 2: partition into " + std::to_string(comm.size()) + " parts");
    // No volume-mesher call meshes more than maxPieceCells: a larger part
    // is meshed in pieces
    pmsh::meshPieces pieces = pmsh::partitionIntoPieces
    (
        comm, coarse, inputs.decomposition, forecast.fineWeights,
        pmsh::numberOfPieces
        (
            forecast.estimate.fineCells - forecast.estimate.prisms, comm.size(),
            settings.maxPieceCells
        )
    );
    std::vector<pmsh::label> cellPart = std::move(pieces.cellPart);
    std::vector<double>().swap(forecast.fineWeights);
    pmsh::logPartSizes(comm, cellPart);
    stages.end();

    stages.begin
    (
        "surface",
        "Stage 3: surface refinement, "
      + std::to_string(settings.refinementLevels) + " levels, with projection"
    );
    pmsh::FineSurface surface;
    pmsh::failTogether(comm, [&]
    {
        surface = pmsh::refinePartSurface
        (
            coarse, cellPart, comm.rank(), inputs.geometry.get(), settings.refinementLevels,
            pieces.cellPiece
        );
    });
    std::vector<pmsh::label>().swap(pieces.cellPiece);
    pmsh::logSurfaceSizes(comm, surface);
    const pmsh::projectionRepairSummary repair =
        pmsh::logProjectionRepair(comm, surface.repair);
    stages.end();

    pmsh::layerReport layerReport;
    const pmsh::wallLayers layers = layerStage
    (
        comm, stages, coarse, cellPart, surface, layerSpecs, settings,
        runTime.globalPath(), layerReport
    );

    std::int64_t nTets = 0;
    pmsh::partitionVolumeResult volume = volumeStage
    (
        comm, stages, settings, coarse, surface, layers, runTime.globalPath(), nTets
    );
    const pmsh::TetMesh& tets = volume.mesh;
    const std::int64_t nFineCells = nTets + std::int64_t(layerReport.prisms);

    stages.begin("numbering", "Stage 5: global point numbering");
    pmsh::globalPointNumbering numbering
    (
        comm, coarse, cellPart, surface, pmsh::label(tets.points.size())
    );
    const pmsh::layerPointList layerPoints = pmsh::numberLayerPoints
    (
        comm, coarse, cellPart, surface, layers, !layerSpecs.empty(), numbering
    );
    const pmsh::label nCoarseCells = coarse.nCells();
    const bool cyclic = !coarse.periodicPatches.empty();
    pmsh::releaseGeometry(coarse);
    std::vector<pmsh::label>().swap(cellPart);
    stages.end();

    stages.begin("balance", "Stage 6: fine cells balanced between ranks");
    pmsh::rankTets share =
        pmsh::rankShareOf(volume, surface, numbering, cyclic, layers, layerPoints);
    pmsh::failTogether(comm, [&]
    {
        pmsh::balanceAndLog(comm, share, volume);
    });
    stages.end();

    const pmsh::writtenMesh written = writeStage
    (
        comm, stages, control, inputs, share, coarse, zonePairs, volume,
        fieldTemplates, runTime, *output
    );

    pmsh::reportSummary
    (
        comm, runTime.globalPath(), settings, nCoarseCells, coarse.volumeMesher,
        volume, nFineCells, written.quality, stages, forecast.estimate, repair,
        inputs.geometry->wrapReport(), layerReport
    );
}


// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

int main(int argc, char *argv[])
{
    // A volume mesher's fresh process (src/volume/mesherChild.H): nothing
    // of OpenFOAM's or MPI's runs there
    if (argc > 1 && std::strcmp(argv[1], pmsh::mesherChildOption) == 0)
    {
        return pmsh::mesherChildMain(argc, argv);
    }
    pmsh::prepareProcess();

    pmsh::addOptions();

    // setRootCase.H, less the processor directories (pmshFoam makes them)
    argList args(argc, argv);
    pmsh::startRun(args);

    const pmsh::Communicator comm;
    // The log goes to a file in every Allrun: write it as the run goes, as
    // Info << endl does, so that a long or killed run shows where it is
    std::cout << std::unitbuf;

    // Left to endRun's std::exit, as a failed run's: not destroyed
    std::optional<Time> caseTime;
    int exitCode = 0;
    try
    {
        meshCase(comm, args, caseTime);
    }
    catch (const pmsh::collectiveFailure& e)
    {
        // Every rank is here: leave together, one error in the log
        if (e.print())
        {
            std::cerr << pmsh::rankPrefix(comm) << e.report() << std::flush;
        }
        exitCode = 1;
    }
    catch (const std::exception& e)
    {
        // A failure the other ranks cannot know about: stop them all
        std::cerr << pmsh::rankPrefix(comm)
            << pmsh::FatalError::of(std::current_exception()).report() << std::flush;
        comm.abort(1);
    }

    endRun(exitCode);
}


// ************************************************************************* //
