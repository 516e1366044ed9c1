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
    the geometry, volume remeshing of each partition (Netgen or HXT), and
    global point numbering through integer barycentric ids (no
    floating-point matching); then whole fine cells move between ranks
    until every rank has its share. Several CSG top-level solids become
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
#include "IOdictionary.H"
#include "fileOperation.H"
#include "IFstream.H"

#include "caseOutput.H"
#include "coarseMeshGeneration.H"
#include "cyclicFaces.H"
#include "Communicator.H"
#include "failTogether.H"
#include "fieldTemplates.H"
#include "foamShims.H"
#include "fineCellWeights.H"
#include "foamMeshOutput.H"
#include "Geometry.H"
#include "globalNumbering.H"
#include "Info.H"
#include "memoryEstimate.H"
#include "meshSettings.H"
#include "partitionCoarseMesh.H"
#include "partitionVolume.H"
#include "childProcess.H"
#include "pmshPipeline.H"
#include "procAddressing.H"
#include "stageLog.H"
#include "surfaceRefinement.H"
#include "tetsToPolyMesh.H"

#include <mpi.h>
#include <malloc.h>

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

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

int main(int argc, char *argv[])
{
    // A volume mesher's fresh process (src/volume/childProcess.H): nothing
    // of OpenFOAM's or MPI's runs there
    if (argc > 1 && std::strcmp(argv[1], pmsh::mesherChildOption) == 0)
    {
        return pmsh::mesherChildMain(argc, argv);
    }
    // The same case meshes the same whatever the ranks' heaps went through
    pmsh::meshInFreshProcesses();

    argList::addNote
    (
        "Generate a tetrahedral mesh in parallel (PMSH method) from a Netgen"
        " CSG (.geo) or STL geometry, straight into processor*/"
    );
    pmsh::foam::noFunctionObjects();
    // processor*/ are what pmshFoam writes: they need not exist yet
    pmsh::foam::noCheckProcessorDirectories();
    #include "addDictOption.H"
    argList::addBoolOption
    (
        "overwrite",
        "Replace an existing mesh (only once meshing succeeded on every rank)"
    );
    argList::addBoolOption
    (
        "noMemoryCheck",
        "Go on even when the memory estimate after the coarse mesh says the"
        " fine mesh cannot fit in this machine's memory"
    );
    argList::addOption
    (
        "decomposeParDict",
        "file",
        "Use specified file for the decomposition dictionary"
    );

    // Large arrays (a rank's tets, faces, addressing) are freed as soon as
    // the next stage has what it needs: keep them in their own mappings,
    // so that freeing them gives the memory back at once (glibc would
    // otherwise raise its mmap threshold after the first such free and
    // keep later arrays in the heap, where freed pages stay resident)
    mallopt(M_MMAP_THRESHOLD, 256*1024);

    // Volume meshing runs in forked children that make no MPI calls (see
    // childProcess.H): Open MPI need not warn about the fork
    ::setenv("OMPI_MCA_mpi_warn_on_fork", "0", 0);

    // setRootCase.H, less the processor directories (pmshFoam makes them)
    argList args(argc, argv);
    if (!pmsh::foam::checkRootCase(args))
    {
        FatalError.exit();
    }

    // Netgen and HXT divide by zero and take square roots of negatives on
    // purpose (and test the result): OpenFOAM's trapFpe would kill them
    pmsh::foam::unsetFpeTrapping();

    // Netgen's Mesh asks MPI for its rank, also in a serial run
    if (!Pstream::parRun())
    {
        pmsh::foam::initNullMPI();
    }

    // v1912's collated fileHandler deadlocks (every rank waiting in its
    // readDir) when it looks for the processors directory of a case that
    // has none yet, as a case pmshFoam meshes: the case is read
    // uncollated and written through the fileHandler asked for: by
    // -fileHandler, FOAM_FILEHANDLER, etc/controlDict (argList has set it)
    // or the case's controlDict (which Time would apply while it reads the
    // case: so it is taken out here, and applied at the write)
    word outputFileHandler = fileHandler().type();
    {
        autoPtr<fileOperation> reader(fileOperation::New("uncollated", false));
        pmsh::foam::setFileHandler(reader);
    }
    const fileName controlDictFile =
        args.rootPath()/args.globalCaseName()/"system"/Time::controlDictName;
    if (!isFile(controlDictFile))
    {
        // Every rank sees it: one error, and all stop together
        if (Pstream::master())
        {
            std::cerr
                << pmsh::FatalError
                   (
                       "cannot find file \"" + controlDictFile + "\"\n"
                       "A case needs system/controlDict, as for any OpenFOAM"
                       " application (see the tutorials)",
                       "pmshFoam"
                   ).report() << std::flush;
        }
        endRun(1);
    }
    IFstream controlDictStream(controlDictFile);
    dictionary controlDict(controlDictStream);
    controlDict.name() = controlDictFile;
    if (dictionary* switches = pmsh::foam::findDict(controlDict, "OptimisationSwitches"))
    {
        if (switches->readIfPresent("fileHandler", outputFileHandler))
        {
            switches->remove("fileHandler");
        }
    }

    Info<< "Create time\n" << endl;
    Time runTime(controlDict, args.rootPath(), args.caseName());
    // Errors of every rank are agreed on before anyone stops (failTogether)
    FatalError.throwExceptions();
    FatalIOError.throwExceptions();

    const pmsh::Communicator comm;
    pmsh::setLogRank(comm.rank(), comm.parallel());

    int exitCode = 0;
    try
    {
        // Everything is read and validated before any meshing starts
        pmsh::meshSettings settings;
        dictionary decomposition;
        std::vector<pmsh::fieldTemplate> fieldTemplates;
        std::unique_ptr<pmsh::Geometry> geometry;
        pmsh::failTogether(comm, [&]
        {
            const IOobject dictIO = pmsh::foam::systemDictIO("pmshDict", args, runTime);
            // Every rank stops on a missing file: reading it would leave
            // the others waiting for the master's copy
            const fileName dictFile = pmsh::foam::globalObjectPath(dictIO, runTime);
            if (!isFile(dictFile))
            {
                FatalErrorIn("pmshFoam")
                    << "The mesh dictionary " << dictFile << " does not exist." << nl
                    << "Create system/pmshDict (see the tutorials), or name"
                    << " another file with -dict <file>"
                    << exit(FatalError);
            }
            settings = pmsh::readMeshSettings(IOdictionary(dictIO), runTime.globalPath());
            if (comm.parallel())
            {
                decomposition = pmsh::decompositionDict(args, comm.size());
                fieldTemplates = pmsh::readFieldTemplates(runTime);
            }
            geometry = pmsh::Geometry::New(settings.geometryFile);
        });
        std::optional<pmsh::caseOutput> output;
        pmsh::failTogether(comm, [&]
        {
            output.emplace(comm, runTime, pmsh::foam::found(args, "overwrite"));
        });

        pmsh::stageLog stages(comm);

        stages.begin
        (
            "coarse",
            "Stage 1: coarse mesh (Netgen surface, " + settings.coarseMesher
          + " volume) of " + settings.geometryFile
        );
        pmsh::CoarseMesh coarse = pmsh::generateCoarseMesh
        (
            comm, *geometry, pmsh::coarseParameters(settings, runTime.globalPath())
        );
        pmsh::setPatchTypes(coarse, settings);
        const std::vector<std::array<pmsh::label, 2>> zonePairs = pmsh::zonePairsOf(coarse);
        pmsh::logCoarseMesh(coarse);
        pmsh::logLocalSizes(coarse, settings);
        // Expected fine cells of every coarse cell (the master's): the
        // partition balances them, the memory estimate sums them
        std::vector<double> fineWeights;
        pmsh::fineCellWeightTerms weightTerms;
        pmsh::failTogether(comm, [&]
        {
            if (comm.master())
            {
                fineWeights = pmsh::fineCellWeights
                (
                    coarse, settings.maxCellSize, settings.refinementLevels,
                    settings.refinementRegions, &weightTerms
                );
            }
        });
        pmsh::memoryEstimate estimate;
        pmsh::failTogether(comm, [&]
        {
            // The sizes of the cells graded from a small body to
            // maxCellSize count more than the partition's weights say
            const double weightSum = comm.sum
            (
                weightTerms.volumeGraded + weightTerms.regionsGraded
              + weightTerms.boundary
            );

            // Stop before the expensive stages if the fine mesh cannot fit
            estimate = pmsh::estimateAndCheckMemory
            (
                comm, settings, coarse.nCells(),
                weightSum*std::pow(8.0, settings.refinementLevels),
                !pmsh::foam::found(args, "noMemoryCheck")
            );
            const double termSum =
                weightTerms.volumeGraded + weightTerms.regionsGraded
              + weightTerms.boundary;
            if (termSum > 0)
            {
                estimate.volumeShare = weightTerms.volumeGraded/termSum;
                estimate.regionShare = weightTerms.regionsGraded/termSum;
                estimate.boundaryShare = weightTerms.boundary/termSum;
            }
            // The patches are known now: every field must cover them all
            pmsh::checkPatchCoverage(fieldTemplates, coarse.patches);
        });
        stages.end();

        stages.begin("partition", "Stage 2: partition into " + std::to_string(comm.size()) + " parts");
        std::vector<pmsh::label> cellPart =
            pmsh::partitionCoarseMesh(comm, coarse, decomposition, fineWeights);
        std::vector<double>().swap(fineWeights);
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
                coarse, cellPart, comm.rank(), geometry.get(), settings.refinementLevels
            );
        });
        pmsh::logSurfaceSizes(comm, surface);
        const pmsh::projectionRepairSummary repair =
            pmsh::logProjectionRepair(comm, surface.repair);
        stages.end();

        stages.begin("volume", "Stage 4: volume meshing (" + settings.volumeMesher + ")");
        pmsh::partitionVolumeResult volume;
        pmsh::failTogether(comm, [&]
        {
            volume = pmsh::meshVolumeByZone
            (
                pmsh::VolumeMesher::NewAll(settings.volumeMesher),
                surface.points, surface.triangles, surface.zone, coarse.zones,
                pmsh::volumeParameters(settings, surface, comm.rank()),
                pmsh::failedSurfaceFile(runTime.globalPath(), comm.rank()),
                "Try a smaller maxCellSize (a finer coarse mesh) or another"
                " volumeMesher in system/pmshDict."
            );
        });
        const pmsh::TetMesh& tets = volume.mesh;
        const std::int64_t nFineCells = pmsh::logVolumeMeshing(comm, volume);
        stages.end();

        stages.begin("numbering", "Stage 5: global point numbering");
        pmsh::globalPointNumbering numbering
        (
            comm, coarse, cellPart, surface, pmsh::label(tets.points.size())
        );
        const pmsh::label nCoarseCells = coarse.nCells();
        const bool cyclic = !coarse.periodicPatches.empty();
        pmsh::releaseGeometry(coarse);
        std::vector<pmsh::label>().swap(cellPart);
        stages.end();

        stages.begin("balance", "Stage 6: fine cells balanced between ranks");
        pmsh::rankTets share = pmsh::rankShareOf(volume, surface, numbering, cyclic);
        pmsh::failTogether(comm, [&]
        {
            pmsh::balanceAndLog(comm, share, volume);
        });
        stages.end();

        stages.begin
        (
            "write",
            "Stage 7: writing "
          + std::string(runTime.writeFormat() == IOstream::BINARY ? "binary" : "ascii")
          + " through the " + std::string(outputFileHandler) + " fileHandler"
        );
        pmsh::tetPolyMesh rankMesh;
        pmsh::meshQualityReport quality;
        pmsh::failTogether(comm, [&]
        {
            rankMesh = pmsh::tetsToPolyMesh
            (
                std::move(share.points), share.tets,
                share.triangles, share.region,
                coarse.patches, comm.parallel() ? comm.rank() : -1,
                share.globalIds
            );
            share.tets = {};
            share.triangles = {};
            share.region = {};
            rankMesh.zoneNames = coarse.zones;
            rankMesh.cellZone = std::move(share.tetZone);
            rankMesh.zonePairs = zonePairs;
        });
        if (cyclic)
        {
            // Collective: in its own failTogether
            pmsh::failTogether(comm, [&]
            {
                pmsh::orderCyclicFaces(comm, rankMesh, share.pointIds, coarse);
            });
            share.pointIds = {};
        }
        const pmsh::meshSizes sizes = pmsh::meshSizesOf(rankMesh);
        pmsh::procAddressing addressing;
        if (comm.parallel())
        {
            addressing = pmsh::buildProcAddressing(comm, rankMesh, share.globalIds);
        }
        share = pmsh::rankTets();
        pmsh::failTogether(comm, [&]
        {
            if (fileHandler().type() != outputFileHandler)
            {
                autoPtr<fileOperation> writer(fileOperation::New(outputFileHandler, false));
                pmsh::foam::setFileHandler(writer);
            }
            if (comm.parallel())
            {
                pmsh::writeProcAddressing(output->time(), std::move(addressing));
            }
            const pmsh::foamRankMesh foamMesh(output->time(), std::move(rankMesh));
            const fvMesh& mesh = foamMesh();
            foamMesh.write();
            if (comm.parallel())
            {
                #include "createFields.H"
            }
            // Last, once the fields are gone: the mesh geometry it needs is
            // the peak of this stage
            quality = pmsh::meshQualityOf(comm, mesh, {volume.minDihedral, volume.maxDihedral, volume.maxAspectRatio});
        });
        output->commit();
        if (comm.parallel())
        {
            pmsh::writeDecomposeParDict(runTime, decomposition);
        }
        pmsh::logWritten(comm, runTime.globalPath(), sizes);
        pmsh::logMeshQuality(comm, quality);
        stages.end();

        pmsh::reportSummary
        (
            comm, runTime.globalPath(), settings, nCoarseCells, coarse.volumeMesher,
            volume, nFineCells, quality, stages, estimate, repair
        );
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
            << pmsh::asFatalError(std::current_exception()).report() << std::flush;
        comm.abort(1);
    }

    endRun(exitCode);
}


// ************************************************************************* //
