/*---------------------------------------------------------------------------*\
  =========                 |
  \\      /  F ield         | pmshFoam: massive parallel tetrahedral meshes
   \\    /   O peration     | for OpenFOAM
    \\  /    A nd           |
     \\/     M anipulation  |
-------------------------------------------------------------------------------
Application
    pmshFoam

Description
    Parallel tetrahedral mesh generator following the PMSH method: a coarse
    Netgen mesh of a CSG (.geo) or STL geometry, a METIS partition of it,
    r levels of refinement of each partition's surface with projection onto
    the geometry, Netgen volume remeshing of each partition, and global
    point numbering through integer barycentric ids (no floating-point
    matching).

    Serial runs write constant/polyMesh. Parallel runs write
    processorN/constant/polyMesh with the procAddressing files,
    processorN/<startTime>/ fields from the case's templates and
    system/decomposeParDict, so that a solver runs with -parallel at once,
    without decomposePar.

Usage
    pmshFoam [-case dir] [-dict file] [-overwrite]
    mpirun -np N pmshFoam -parallel [-case dir] [-dict file] [-overwrite]

    Reads system/pmshDict (geometry, maxCellSize, grading, refinementLevels,
    volumeMesher, optimisationSteps, patches) and system/controlDict
    (writeFormat, writePrecision, startTime).

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "caseOutput.H"
#include "clock.H"
#include "coarseMesh.H"
#include "Communicator.H"
#include "error.H"
#include "failTogether.H"
#include "fieldTemplates.H"
#include "Geometry.H"
#include "globalNumbering.H"
#include "Info.H"
#include "memoryEstimate.H"
#include "meshSettings.H"
#include "partitionCoarseMesh.H"
#include "polyMeshWriter.H"
#include "pmshPipeline.H"
#include "procAddressing.H"
#include "stageLog.H"
#include "surfaceRefinement.H"
#include "tetsToPolyMesh.H"
#include "partitionVolume.H"

#include <iostream>
#include <memory>
#include <optional>

using namespace pmsh;

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

int main(int argc, char* argv[])
{
    std::unique_ptr<Communicator> commPtr
    (
        argList::parallelRequested(argc, argv)
      ? new Communicator(argc, argv)
      : new Communicator()
    );
    const Communicator& comm = *commPtr;
    setLogRank(comm.rank(), comm.parallel());

    try
    {
        const argList args(argc, argv);
        args.printBanner(comm.size());

        // Everything is read and validated before any meshing starts
        meshSettings settings;
        writeSettings output;
        std::vector<fieldTemplate> fields;
        std::unique_ptr<Geometry> geometry;
        failTogether(comm, [&]
        {
            requireMoreThanOneRank(comm);
            settings = readMeshSettings(args.caseDir(), args.dictFile());
            output = readWriteSettings(args.caseDir());
            if (comm.parallel())
            {
                fields = readFieldTemplates(args.caseDir() + "/" + output.startTime);
            }
            geometry = Geometry::New(settings.geometryFile);
        });
        std::optional<caseOutput> target;
        failTogether(comm, [&]
        {
            target.emplace(comm, args.caseDir(), args.overwrite());
        });

        stageLog stages(comm);

        stages.begin("coarse", "Stage 1: coarse mesh (Netgen) of " + settings.geometryFile);
        const CoarseMesh coarse = generateCoarseMesh
        (
            comm, *geometry, {settings.maxCellSize, settings.grading}
        );
        logCoarseMesh(coarse);
        failTogether(comm, [&]
        {
            // Stop before the expensive stages if the fine mesh cannot fit
            checkMemoryEstimate(comm, settings, coarse.nCells());
        });
        const std::vector<polyPatchInfo> patches = physicalPatches(coarse, settings);
        failTogether(comm, [&]
        {
            // The patches are known now: every field must cover them all
            checkFieldTemplates(fields, patches);
        });
        stages.end();

        stages.begin("partition", "Stage 2: partition into " + std::to_string(comm.size()) + " parts");
        const std::vector<label> cellPart = partitionCoarseMesh(comm, coarse);
        logPartSizes(comm, cellPart);
        stages.end();

        stages.begin
        (
            "surface",
            "Stage 3: surface refinement, "
          + std::to_string(settings.refinementLevels) + " levels, with projection"
        );
        FineSurface surface;
        failTogether(comm, [&]
        {
            surface = refinePartSurface
            (
                coarse, cellPart, comm.rank(), geometry.get(), settings.refinementLevels
            );
        });
        logSurfaceSizes(comm, surface);
        stages.end();

        stages.begin("volume", "Stage 4: volume meshing (" + settings.volumeMesher + ")");
        partitionVolumeResult volume;
        failTogether(comm, [&]
        {
            volume = meshPartitionVolume
            (
                settings.volumeMesher, surface.points, surface.triangles,
                volumeParameters(settings, comm.rank()), comm.rank(),
                failedSurfaceFile(args.caseDir(), comm.rank())
            );
        });
        TetMesh& tets = volume.mesh;
        const globalLabel nFineCells = logVolumeMeshing(comm, volume);
        stages.end();

        stages.begin("numbering", "Stage 5: global point numbering");
        const globalPointNumbering numbering
        (
            comm, coarse, cellPart, surface, label(tets.points.size())
        );
        stages.end();

        stages.begin("write", "Stage 6: writing " + std::string(output.binary ? "binary" : "ascii"));
        PolyMesh mesh;
        failTogether(comm, [&]
        {
            mesh = tetsToPolyMesh
            (
                std::move(tets.points), tets.tets,
                surface.triangles, surface.region,
                patches, comm.parallel() ? comm.rank() : -1,
                numbering.globalIds()
            );
        });
        const procAddressing addressing = comm.parallel()
            ? buildProcAddressing(comm, mesh, numbering.globalIds())
            : procAddressing();
        failTogether(comm, [&]
        {
            const foamFileFormat format
                {output.binary, settings.labelBits, output.writePrecision};
            writePolyMesh(target->polyMeshDir(), mesh, format, target->polyMeshLocation());
            if (comm.parallel())
            {
                writeProcAddressing
                (
                    target->polyMeshDir(), addressing, format, target->polyMeshLocation()
                );
                #include "createFields.H"
            }
        });
        target->commit(true);
        if (comm.parallel() && comm.master())
        {
            writeDecomposeParDict(args.caseDir(), comm.size());
        }
        logWritten(comm, args.caseDir(), mesh);
        stages.end();

        reportSummary
        (
            comm, args.caseDir(), settings, coarse, volume, nFineCells, stages
        );
    }
    catch (const collectiveFailure& e)
    {
        // Every rank is here: leave together, one error in the log
        if (e.print())
        {
            std::cerr << rankPrefix(comm) << e.report();
        }
        return 1;
    }
    catch (const std::exception& e)
    {
        // A failure the other ranks cannot know about: stop them all
        const FatalError* fatal = dynamic_cast<const FatalError*>(&e);
        std::cerr << rankPrefix(comm)
            << (fatal ? fatal->report() : FatalError(e.what(), "main").report());
        comm.abort(1);
    }

    return 0;
}


// ************************************************************************* //
