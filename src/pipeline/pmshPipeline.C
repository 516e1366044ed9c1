#include "pmshPipeline.H"
#include "Info.H"
#include "clock.H"
#include "error.H"

#include <iomanip>
#include <ostream>

std::string pmsh::rankPrefix(const Communicator& comm)
{
    return comm.parallel() ? "[" + std::to_string(comm.rank()) + "] " : "";
}


void pmsh::requireMoreThanOneRank(const Communicator& comm)
{
    if (comm.parallel() && comm.size() == 1)
    {
        throw FatalError
        (
            "attempt to run parallel on 1 processor\n"
            "Start with \"mpirun -np N pmshFoam -parallel\" (N > 1),"
            " or run pmshFoam without -parallel",
            "main"
        );
    }
}


void pmsh::checkNoFoldedTriangles
(
    const CoarseMesh& coarse,
    const coarsePartSurface& partSurface,
    const FineSurface& fine,
    int levels
)
{
    const label nFolded = countFoldedTriangles(coarse, partSurface, fine, levels);
    if (nFolded > 0)
    {
        throw FatalError
        (
            msg() << nFolded << " refined surface triangles folded over when"
                << " projected onto the geometry: the coarse mesh is too coarse"
                << " for the curvature of the geometry.\n"
                << "Reduce maxCellSize in system/pmshDict.",
            "checkNoFoldedTriangles"
        );
    }
}


pmsh::volumeMeshParameters pmsh::volumeParameters(const meshSettings& settings)
{
    volumeMeshParameters p;
    p.maxCellSize = settings.maxCellSize/double(1 << settings.refinementLevels);
    p.grading = settings.grading;
    p.optimisationSteps = settings.optimisationSteps;
    return p;
}


std::vector<pmsh::polyPatchInfo> pmsh::physicalPatches
(
    const CoarseMesh& coarse,
    const meshSettings& settings
)
{
    std::vector<polyPatchInfo> patches;
    for (const std::string& name : coarse.patchNames)
    {
        polyPatchInfo p;
        p.name = name;
        p.type = settings.patchType(name);
        patches.push_back(p);
    }
    return patches;
}


void pmsh::logSurfaceSizes(const Communicator& comm, const FineSurface& surface)
{
    const minAvgMax n = reduceMinAvgMax(comm, double(surface.triangles.size()));
    Info() << std::fixed << std::setprecision(0);
    if (comm.parallel())
    {
        Info()
            << "    fine surface triangles per rank min/avg/max: "
            << n.min << " / " << n.avg << " / " << n.max << '\n';
    }
    else
    {
        Info() << "    fine surface triangles: " << n.max << '\n';
    }
    Info() << std::defaultfloat;
}


pmsh::globalLabel pmsh::logCellCounts(const Communicator& comm, const TetMesh& tets)
{
    const globalLabel nCells = comm.sum(std::int64_t(tets.tets.size()));
    const minAvgMax n = reduceMinAvgMax(comm, double(tets.tets.size()));
    Info() << std::fixed << std::setprecision(0);
    if (comm.parallel())
    {
        Info()
            << "    fine cells per rank min/avg/max: "
            << n.min << " / " << n.avg << " / " << n.max << '\n';
    }
    Info() << "    fine cells: " << nCells << '\n' << std::defaultfloat;
    return nCells;
}


void pmsh::logSummary
(
    const Communicator& comm,
    const CoarseMesh& coarse,
    globalLabel nFineCells,
    const stageLog& stages
)
{
    const double total = stages.total();
    const minAvgMax memory = reduceMinAvgMax(comm, peakMemoryBytes()/1048576.0);

    Info()
        << "Summary\n"
        << "    ranks:        " << comm.size() << '\n'
        << "    coarse cells: " << coarse.nCells() << '\n'
        << "    fine cells:   " << nFineCells << '\n'
        << std::fixed << std::setprecision(2);
    for (const auto& [name, seconds] : stages.times())
    {
        Info() << "    " << std::left << std::setw(60) << name << ' '
            << std::right << std::setw(9) << seconds << " s\n";
    }
    Info()
        << "    total time:   " << total << " s\n"
        << std::setprecision(0)
        << "    fine cells/s per core: "
        << (total > 0 ? nFineCells/total/comm.size() : 0) << '\n'
        << std::setprecision(1)
        << "    peak memory per rank (MiB) min/avg/max: "
        << memory.min << " / " << memory.avg << " / " << memory.max << '\n'
        << std::defaultfloat << std::setprecision(6)
        << "\nEnd\n\n";
}
