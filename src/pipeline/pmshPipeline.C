#include "pmshPipeline.H"
#include "Info.H"
#include "clock.H"
#include "error.H"

#include <algorithm>
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


std::vector<pmsh::patchNameType> pmsh::patchNamesAndTypes(const PolyMesh& mesh)
{
    std::vector<patchNameType> patches;
    for (const polyPatchInfo& p : mesh.patches)
    {
        patches.emplace_back(p.name, p.type);
    }
    return patches;
}


void pmsh::checkFieldTemplates
(
    const std::vector<fieldTemplate>& fields,
    const std::vector<polyPatchInfo>& patches
)
{
    std::vector<patchNameType> physical;
    for (const polyPatchInfo& p : patches)
    {
        physical.emplace_back(p.name, p.type);
    }
    for (const fieldTemplate& field : fields)
    {
        checkPatchCoverage(field, physical);
    }
}


void pmsh::logCoarseMesh(const CoarseMesh& coarse)
{
    Info()
        << "    coarse cells: " << coarse.nCells()
        << ", points: " << coarse.nPoints()
        << ", boundary faces: " << coarse.boundary.size() << '\n'
        << "    patches:";
    for (const std::string& name : coarse.patchNames)
    {
        Info() << ' ' << name;
    }
    Info() << '\n';
}


void pmsh::logPartSizes(const Communicator& comm, const std::vector<label>& cellPart)
{
    std::vector<label> size(comm.size(), 0);
    for (label p : cellPart)
    {
        ++size[p];
    }
    const auto [small, large] = std::minmax_element(size.begin(), size.end());
    Info()
        << "    coarse cells per part min/avg/max: " << *small << " / "
        << double(cellPart.size())/comm.size() << " / " << *large << '\n';
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


void pmsh::logWritten
(
    const Communicator& comm,
    const std::string& caseDir,
    const PolyMesh& mesh
)
{
    Info()
        << "    written to " << caseDir
        << (comm.parallel() ? "/processor*" : "/constant/polyMesh") << '\n';
    const minAvgMax faces = reduceMinAvgMax(comm, double(mesh.nFaces()));
    const minAvgMax points = reduceMinAvgMax(comm, double(mesh.points.size()));
    Info() << std::fixed << std::setprecision(0);
    if (comm.parallel())
    {
        Info()
            << "    faces per rank min/avg/max: " << faces.min << " / " << faces.avg
            << " / " << faces.max << '\n'
            << "    points per rank min/avg/max: " << points.min << " / " << points.avg
            << " / " << points.max << '\n';
    }
    else
    {
        Info() << "    faces: " << faces.max << ", points: " << points.max << '\n';
    }
    Info() << std::defaultfloat;
}
