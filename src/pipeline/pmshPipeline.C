#include "pmshPipeline.H"
#include "streamManip.H"
#include "stageClock.H"
#include "pmshError.H"
#include "meshPatch.H"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <ostream>

using Foam::Info;
using Foam::Pout;
using Foam::fixed;
using Foam::setprecision;
using Foam::setw;

std::string pmsh::rankPrefix(const Communicator& comm)
{
    return comm.parallel() ? "[" + std::to_string(comm.rank()) + "] " : "";
}


pmsh::volumeMeshParameters pmsh::volumeParameters
(
    const meshSettings& settings,
    const FineSurface& surface,
    int rank
)
{
    volumeMeshParameters p;
    p.interfaceTriangles.resize(surface.region.size());
    for (std::size_t t = 0; t < surface.region.size(); ++t)
    {
        // Cells lie behind processor faces and faces between zones
        p.interfaceTriangles[t] =
            isInterfaceRegion(surface.region[t]) || isBetweenZones(surface.region[t]);
    }
    p.what = "partition " + std::to_string(rank);
    const double toFine = double(1 << settings.refinementLevels);
    p.maxCellSize = settings.maxCellSize/toFine;
    for (const sizeRegion& r : settings.refinementRegions)
    {
        p.regions.push_back(r.scaled(toFine));
    }
    p.grading = settings.grading;
    p.optimisationSteps = settings.optimisationSteps;
    p.threads = settings.volumeMesherThreads;
    return p;
}


std::vector<std::array<pmsh::label, 2>> pmsh::zonePairsOf(const CoarseMesh& coarse)
{
    std::vector<std::array<label, 2>> pairs;
    for (const coarseZoneFace& f : coarse.zoneFaces)
    {
        pairs.push_back({std::min(f.inside, f.outside), std::max(f.inside, f.outside)});
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
}


void pmsh::dropFacesBetweenZones(FineSurface& surface)
{
    if (surface.zone.empty())
    {
        return;
    }
    std::size_t kept = 0;
    for (std::size_t t = 0; t < surface.triangles.size(); ++t)
    {
        if (!isBetweenZones(surface.region[t]))
        {
            surface.triangles[kept] = surface.triangles[t];
            surface.region[kept] = surface.region[t];
            surface.zone[kept] = surface.zone[t];
            ++kept;
        }
    }
    surface.triangles.resize(kept);
    surface.region.resize(kept);
    surface.zone.resize(kept);
}


void pmsh::setPatchTypes(CoarseMesh& coarse, const meshSettings& settings)
{
    for (meshPatch& p : coarse.patches)
    {
        const meshSettings::patchTypeChoice choice = settings.choosePatchType(p.name);
        p.type = choice.type;
        p.typeOrigin = choice.origin;
    }
    // The geometry's periodic pairs are cyclic, whatever pmshDict says
    for (const periodicPatchPair& pp : coarse.periodicPatches)
    {
        meshPatch& first = coarse.patches[pp.first];
        meshPatch& second = coarse.patches[pp.second];
        first.type = second.type = "cyclic";
        first.typeOrigin = second.typeOrigin = "identify periodic in the geometry";
        first.neighbourPatch = second.name;
        second.neighbourPatch = first.name;
        first.separation = pp.separation;
        second.separation = -1.0*pp.separation;
    }
}


void pmsh::logCoarseMesh(const CoarseMesh& coarse)
{
    Info
        << "    volume filled by " << coarse.volumeMesher.c_str() << '\n'
        << "    coarse cells: " << coarse.nCells()
        << ", points: " << coarse.nPoints()
        << ", boundary faces: " << coarse.boundary.size() << '\n'
        << "    patches (coarse boundary faces):";
    std::vector<label> faces(coarse.patches.size(), 0);
    for (const coarseBoundaryFace& f : coarse.boundary)
    {
        ++faces[f.patch];
    }
    for (std::size_t p = 0; p < coarse.patches.size(); ++p)
    {
        Info << ' ' << coarse.patches[p].name.c_str() << " (" << faces[p] << ')';
    }
    Info << '\n';
    if (coarse.zones.empty())
    {
        return;
    }
    std::vector<label> cells(coarse.zones.size(), 0);
    for (label z : coarse.cellZone)
    {
        ++cells[z];
    }
    Info << "    zones (cellZones, coarse cells):";
    for (std::size_t z = 0; z < coarse.zones.size(); ++z)
    {
        Info << ' ' << coarse.zones[z].c_str() << " (" << cells[z] << ')';
    }
    Info << "\n    coarse faces between zones: " << coarse.zoneFaces.size() << '\n';
}


void pmsh::logLocalSizes(const CoarseMesh& coarse, const meshSettings& settings)
{
    auto edge = [&coarse](label a, label b)
    {
        return std::sqrt(magSqr(coarse.points[a] - coarse.points[b]));
    };
    auto note = [&settings](double size)
    {
        return
            size < settings.maxCellSize
          ? std::string()
          : " (not below the global maxCellSize: no effect)";
    };

    for (const sizeRegion& r : settings.refinementRegions)
    {
        label nCells = 0;
        double sum = 0;
        for (const tetVerts& t : coarse.tets)
        {
            const point3 centroid =
                0.25*(coarse.points[t[0]] + coarse.points[t[1]]
                    + coarse.points[t[2]] + coarse.points[t[3]]);
            if (r.contains(centroid))
            {
                ++nCells;
                sum +=
                    edge(t[0], t[1]) + edge(t[0], t[2]) + edge(t[0], t[3])
                  + edge(t[1], t[2]) + edge(t[1], t[3]) + edge(t[2], t[3]);
            }
        }
        Info
            << "    region " << r.name.c_str() << " (" << r.shapeName()
            << ", maxCellSize " << r.size << note(r.size).c_str() << "): " << nCells
            << " coarse cells, mean edge "
            << (nCells ? sum/(6*nCells) : 0) << '\n';
    }

    if (!settings.hasPatchSizes())
    {
        return;
    }
    for (std::size_t p = 0; p < coarse.patches.size(); ++p)
    {
        const double size = settings.patchMaxCellSize(coarse.patches[p].name);
        if (!(size > 0))
        {
            continue;
        }
        label nFaces = 0;
        double sum = 0;
        for (const coarseBoundaryFace& f : coarse.boundary)
        {
            if (f.patch == label(p))
            {
                ++nFaces;
                sum += edge(f.v[0], f.v[1]) + edge(f.v[1], f.v[2]) + edge(f.v[2], f.v[0]);
            }
        }
        Info
            << "    patch " << coarse.patches[p].name.c_str() << " (maxCellSize " << size
            << note(size).c_str() << "): " << nFaces << " coarse boundary faces, mean edge "
            << (nFaces ? sum/(3*nFaces) : 0) << '\n';
    }
}


void pmsh::logPartSizes(const Communicator& comm, const std::vector<label>& cellPart)
{
    std::vector<label> size(comm.size(), 0);
    for (label p : cellPart)
    {
        ++size[p];
    }
    const auto [small, large] = std::minmax_element(size.begin(), size.end());
    Info
        << "    coarse cells per part min/avg/max: " << *small << " / "
        << double(cellPart.size())/comm.size() << " / " << *large << '\n';
}


void pmsh::logSurfaceSizes(const Communicator& comm, const FineSurface& surface)
{
    const minAvgMax n = reduceMinAvgMax(comm, double(surface.triangles.size()));
    Info << fixed << setprecision(0);
    if (comm.parallel())
    {
        Info
            << "    fine surface triangles per rank min/avg/max: "
            << n.min << " / " << n.avg << " / " << n.max << '\n';
    }
    else
    {
        Info << "    fine surface triangles: " << n.max << '\n';
    }
    Info << defaultfloat;
}


pmsh::projectionRepairSummary pmsh::logProjectionRepair
(
    const Communicator& comm,
    const projectionRepairStats& repair
)
{
    projectionRepairSummary total;
    total.nPointsOff = comm.sum(std::int64_t(repair.nPointsOff));
    total.maxDistance = comm.max(repair.maxDistance);
    const double sumDistance = comm.sum(repair.sumDistance);
    total.meanDistance = total.nPointsOff ? sumDistance/total.nPointsOff : 0;
    if (total.nPointsOff)
    {
        Info
            << "    refined points left off the geometry (their projection"
            << " folded the surface): " << total.nPointsOff
            << ", distance from the geometry max " << total.maxDistance
            << ", mean " << total.meanDistance << '\n';
    }
    return total;
}


pmsh::rankTets pmsh::rankShareOf
(
    partitionVolumeResult& volume,
    FineSurface& surface,
    globalPointNumbering& numbering,
    bool keepPointIds
)
{
    dropFacesBetweenZones(surface);
    rankTets share;
    share.points = std::move(volume.mesh.points);
    share.tets = std::move(volume.mesh.tets);
    volume.mesh = TetMesh();
    share.tetZone = std::move(volume.tetZone);
    share.triangles = std::move(surface.triangles);
    share.region = std::move(surface.region);
    share.globalIds = numbering.releaseGlobalIds();
    if (keepPointIds)
    {
        share.pointIds = std::move(surface.ids);
        share.pointIds.resize(share.points.size());
    }
    surface = FineSurface();
    return share;
}


void pmsh::balanceAndLog
(
    const Communicator& comm,
    rankTets& share,
    partitionVolumeResult& volume
)
{
    if (!comm.parallel())
    {
        Info << "    serial: nothing to balance\n";
        return;
    }
    const fineBalanceStats stats = balanceFineCells(comm, share);
    volume.nCells = label(share.tets.size());
    const minAvgMax n = reduceMinAvgMax(comm, double(share.tets.size()));
    Info
        << fixed << setprecision(3)
        << "    largest rank's fine cells over the mean: " << stats.before
        << " -> " << stats.after << " (" << stats.moved << " cells moved)\n"
        << setprecision(0)
        << "    fine cells per rank min/avg/max: " << n.min << " / " << n.avg
        << " / " << n.max << '\n' << defaultfloat;
}


std::string pmsh::failedSurfaceFile(const std::string& caseDir, int rank)
{
    return caseDir + "/postProcessing/pmshFoam/failedPartition" + std::to_string(rank) + ".stl";
}


pmsh::coarseMeshParameters pmsh::coarseParameters
(
    const meshSettings& settings,
    const std::string& caseDir
)
{
    coarseMeshParameters p;
    p.maxCellSize = settings.maxCellSize;
    p.grading = settings.grading;
    p.mesher = settings.coarseMesher;
    p.failedSurfaceFile = caseDir + "/postProcessing/pmshFoam/failedCoarseSurface.stl";
    p.regions = settings.refinementRegions;
    p.curvatureRefinement = settings.curvatureRefinement;
    p.minCellSize = settings.minCellSize;
    p.coarseTimeLimit = settings.coarseTimeLimit;
    if (settings.hasPatchSizes())
    {
        p.patchMaxCellSize = [settings](const std::string& patch)
        {
            return settings.patchMaxCellSize(patch);
        };
    }
    return p;
}


std::int64_t pmsh::logVolumeMeshing
(
    const Communicator& comm,
    const partitionVolumeResult& volume
)
{
    const TetMesh& tets = volume.mesh;
    if (volume.attempts > 1)
    {
        Pout
            << "    partition " << comm.rank() << " meshed by " << volume.backend.c_str()
            << " at attempt " << volume.attempts << "; earlier attempts:"
            << volume.failures.c_str() << '\n';
    }
    const std::int64_t nCells = comm.sum(std::int64_t(tets.tets.size()));
    const minAvgMax n = reduceMinAvgMax(comm, double(tets.tets.size()));
    Info << fixed << setprecision(0);
    if (comm.parallel())
    {
        Info
            << "    fine cells per rank min/avg/max: "
            << n.min << " / " << n.avg << " / " << n.max << '\n';
    }
    Info << "    fine cells: " << nCells << '\n' << defaultfloat;
    return nCells;
}


pmsh::meshSizes pmsh::meshSizesOf(const tetPolyMesh& mesh)
{
    meshSizes sizes{double(mesh.nFaces()), double(mesh.points.size()), {}};
    for (const meshPatch& p : mesh.patches)
    {
        if (p.isPhysical())
        {
            sizes.patches.push_back(p);
        }
    }
    sizes.zones = mesh.zoneNames;
    sizes.zoneCells.assign(mesh.zoneNames.size(), 0);
    for (label z : mesh.cellZone)
    {
        ++sizes.zoneCells[z];
    }
    // A cyclic patch's faces whose image is on another rank count too
    for (const meshPatch& p : mesh.patches)
    {
        if (p.isProcessorCyclic())
        {
            for (meshPatch& q : sizes.patches)
            {
                q.size += q.name == p.neighbourPatch ? p.size : 0;
            }
        }
    }
    return sizes;
}


void pmsh::logWritten
(
    const Communicator& comm,
    const std::string& caseDir,
    const meshSizes& sizes
)
{
    Info
        << "    written to " << caseDir.c_str()
        << (comm.parallel() ? "/processor*" : "/constant/polyMesh") << '\n';
    const minAvgMax faces = reduceMinAvgMax(comm, sizes.faces);
    const minAvgMax points = reduceMinAvgMax(comm, sizes.points);
    Info << fixed << setprecision(0);
    if (comm.parallel())
    {
        Info
            << "    faces per rank min/avg/max: " << faces.min << " / " << faces.avg
            << " / " << faces.max << '\n'
            << "    points per rank min/avg/max: " << points.min << " / " << points.avg
            << " / " << points.max << '\n';
    }
    else
    {
        Info << "    faces: " << faces.max << ", points: " << points.max << '\n';
    }

    // Every physical patch (every rank has all of them, some empty)
    std::size_t width = 4;
    for (const meshPatch& p : sizes.patches)
    {
        width = std::max(width, p.name.size());
    }
    if (!sizes.zones.empty())
    {
        Info << "    cellZones (cells):";
        for (std::size_t z = 0; z < sizes.zones.size(); ++z)
        {
            Info << ' ' << sizes.zones[z].c_str() << ' ' << comm.sum(sizes.zoneCells[z]);
        }
        Info << '\n';
    }
    Info << "    patches (faces, type and why):\n";
    for (const meshPatch& p : sizes.patches)
    {
        const std::int64_t nFaces = comm.sum(std::int64_t(p.size));
        Info
            << "        " << left << setw(int(width)) << p.name.c_str() << ' '
            << right << setw(10) << nFaces << "  " << left
            << setw(13) << p.type.c_str() << right << ' ' << p.typeOrigin.c_str() << '\n';
    }
    Info << defaultfloat;
}


namespace
{

// A JSON array of numbers
template<class T>
std::string jsonArray(const std::vector<T>& values)
{
    std::ostringstream os;
    os << std::setprecision(10) << '[';
    for (std::size_t i = 0; i < values.size(); ++i)
    {
        os << (i ? ", " : "") << values[i];
    }
    os << ']';
    return os.str();
}

// A JSON string (the values here hold no control characters)
std::string jsonString(const std::string& s)
{
    std::string quoted = "\"";
    for (char c : s)
    {
        if (c == '"' || c == '\\') quoted += '\\';
        quoted += c;
    }
    return quoted + '"';
}

} // End anonymous namespace


void pmsh::reportSummary
(
    const Communicator& comm,
    const std::string& caseDir,
    const meshSettings& settings,
    label coarseCells,
    const std::string& coarseMesher,
    const partitionVolumeResult& volume,
    std::int64_t nFineCells,
    const meshQualityReport& quality,
    const stageLog& stages,
    const memoryEstimate& estimate,
    const projectionRepairSummary& repair
)
{
    const double total = stages.total();
    const std::vector<double> memory = comm.allGather(double(peakMemoryBytes()));
    const std::vector<double> cellsPerRank =
        comm.allGather(double(volume.nCells));
    const std::vector<double> attemptsPerRank = comm.allGather(double(volume.attempts));
    const trafficCounts traffic = comm.traffic();
    const std::vector<double> messagesPerRank = comm.allGather(traffic.messages);
    const std::vector<double> bytesSentPerRank = comm.allGather(traffic.bytes);
    const std::vector<std::string> backends = VolumeMesher::names();
    const std::vector<double> backendPerRank = comm.allGather
    (
        double(std::find(backends.begin(), backends.end(), volume.backend) - backends.begin())
    );
    const minAvgMax memoryBytes = minAvgMaxOf(memory);
    const minAvgMax memoryMiB
        {memoryBytes.min/1048576.0, memoryBytes.avg/1048576.0, memoryBytes.max/1048576.0};

    // The paper's split: the coarse mesh, then everything up to the fine
    // mesh (writing excluded)
    const double coarseTime = stages.time("coarse");
    const double fineTime =
        stages.time("partition") + stages.time("surface")
      + stages.time("volume") + stages.time("numbering") + stages.time("balance");
    const double perCore =
        fineTime > 0 ? nFineCells/fineTime/comm.size() : 0;
    double memorySum = 0;
    for (double m : memory) memorySum += m;

    // What a fine cell costs a rank once the base is paid (the largest
    // rank's peak after stage 1: libraries, MPI, the coarse mesh)
    const double base = stages.peakMemory("coarse");
    double bytesAboveBase = 0;
    for (std::size_t i = 0; i < memory.size(); ++i)
    {
        if (cellsPerRank[i] > 0)
        {
            bytesAboveBase = std::max(bytesAboveBase, (memory[i] - base)/cellsPerRank[i]);
        }
    }

    Info
        << "Summary\n"
        << "    ranks:        " << comm.size() << '\n'
        << "    coarse cells: " << coarseCells << '\n'
        << "    fine cells:   " << nFineCells << '\n'
        << fixed << setprecision(2);
    for (const stageLog::stageTime& t : stages.times())
    {
        Info << "    " << left << setw(12) << t.key.c_str()
            << right << setw(9) << t.max << " s\n";
    }
    Info
        << "    total time:   " << total << " s\n"
        << setprecision(0)
        << "    fine cells/s per core (stages 2-6): " << perCore << '\n'
        << setprecision(1)
        << "    peak memory per rank (MiB) min/avg/max: "
        << memoryMiB.min << " / " << memoryMiB.avg << " / " << memoryMiB.max << '\n'
        << "    bytes per fine cell (all ranks): "
        << (nFineCells > 0 ? memorySum/nFineCells : 0)
        << ", above the stage 1 base (largest per rank): " << bytesAboveBase << '\n'
        << "    max non-orthogonality (checkMesh): "
        << quality.overall.maxNonOrthogonality << " degrees, average "
        << quality.overall.avgNonOrthogonality << '\n'
        << setprecision(3)
        << "    max skewness (checkMesh): " << quality.overall.maxSkewness << '\n'
        << defaultfloat << setprecision(6);
    logEstimateAccuracy
    (
        estimate, double(nFineCells),
        *std::max_element(cellsPerRank.begin(), cellsPerRank.end()),
        memoryBytes.max
    );
    Info << "\nEnd\n\n";

    if (!comm.master())
    {
        return;
    }
    const std::string dir = caseDir + "/postProcessing/pmshFoam";
    std::filesystem::create_directories(dir);
    std::ofstream os(dir + "/summary.json");
    os  << std::setprecision(10)
        << "{\n"
        << "  \"application\": \"pmshFoam\",\n"
        << "  \"ranks\": " << comm.size() << ",\n"
        << "  \"geometry\": " << jsonString(settings.geometryFile) << ",\n"
        << "  \"maxCellSize\": " << settings.maxCellSize << ",\n"
        << "  \"grading\": " << settings.grading << ",\n"
        << "  \"refinementLevels\": " << settings.refinementLevels << ",\n"
        << "  \"coarseMesher\": " << jsonString(coarseMesher) << ",\n"
        << "  \"volumeMesher\": " << jsonString(settings.volumeMesher) << ",\n"
        << "  \"coarseCells\": " << coarseCells << ",\n"
        << "  \"fineCells\": " << nFineCells << ",\n"
        << "  \"pointsOffGeometry\": " << repair.nPointsOff << ",\n"
        << "  \"maxDistanceOffGeometry\": " << repair.maxDistance << ",\n"
        << "  \"meanDistanceOffGeometry\": " << repair.meanDistance << ",\n"
        << "  \"fineCellsPerRank\": " << jsonArray(cellsPerRank) << ",\n"
        << "  \"volumeMesherPerRank\": [";
    for (std::size_t i = 0; i < backendPerRank.size(); ++i)
    {
        os  << (i ? ", " : "") << jsonString(backends.at(std::size_t(backendPerRank[i])));
    }
    os  << "],\n"
        << "  \"volumeAttemptsPerRank\": " << jsonArray(attemptsPerRank) << ",\n"
        << "  \"stages\": {\n";
    const auto& times = stages.times();
    for (std::size_t i = 0; i < times.size(); ++i)
    {
        os  << "    " << jsonString(times[i].key) << ": {\"seconds\": " << times[i].max
            << ", \"secondsPerRank\": " << jsonArray(times[i].perRank)
            << ", \"peakMemoryBytes\": " << times[i].peakMemoryBytes << "}"
            << (i + 1 < times.size() ? ",\n" : "\n");
    }
    os  << "  },\n"
        << "  \"coarseTime\": " << coarseTime << ",\n"
        << "  \"fineTime\": " << fineTime << ",\n"
        << "  \"writeTime\": " << stages.time("write") << ",\n"
        << "  \"totalTime\": " << total << ",\n"
        << "  \"fineCellsPerSecondPerCore\": " << perCore << ",\n"
        << "  \"peakMemoryPerRankBytes\": " << jsonArray(memory) << ",\n"
        << "  \"bytesPerFineCell\": " << (nFineCells > 0 ? memorySum/nFineCells : 0) << ",\n"
        << "  \"bytesPerFineCellAboveBase\": " << bytesAboveBase << ",\n"
        << "  \"broadcastBytes\": " << traffic.broadcastBytes << ",\n"
        << "  \"messagesPerRank\": " << jsonArray(messagesPerRank) << ",\n"
        << "  \"bytesSentPerRank\": " << jsonArray(bytesSentPerRank) << ",\n"
        << "  \"estimatedFineCells\": " << estimate.fineCells << ",\n"
        << "  \"estimatedCellsPerWeighted\": " << estimate.cellsPerWeighted << ",\n"
        << "  \"estimatedFineCellsLargestRank\": " << estimate.fineCellsPerRank << ",\n"
        << "  \"estimateShares\": {\"volume\": " << estimate.volumeShare
        << ", \"regions\": " << estimate.regionShare << ", \"boundary\": "
        << estimate.boundaryShare << "},\n"
        << "  \"estimatedPeakMemoryPerRankBytes\": " << estimate.bytesPerRank << ",\n"
        << "  \"quality\": {\n";
    // One entry per measure: overall, then per rank
    using measure = double meshQuality::*;
    const std::vector<std::pair<const char*, measure>> measures
    {
        {"maxNonOrthogonality", &meshQuality::maxNonOrthogonality},
        {"avgNonOrthogonality", &meshQuality::avgNonOrthogonality},
        {"maxProcessorNonOrthogonality", &meshQuality::maxProcessorNonOrthogonality},
        {"maxSkewness", &meshQuality::maxSkewness},
        {"minVolume", &meshQuality::minVolume},
        {"minDihedral", &meshQuality::minDihedral},
        {"maxDihedral", &meshQuality::maxDihedral},
        {"maxAspectRatio", &meshQuality::maxAspectRatio}
    };
    for (const auto& [name, m] : measures)
    {
        std::vector<double> perRank;
        for (const meshQuality& q : quality.perRank) perRank.push_back(q.*m);
        os  << "    " << jsonString(name) << ": " << quality.overall.*m << ",\n"
            << "    " << jsonString(std::string(name) + "PerRank") << ": "
            << jsonArray(perRank) << ",\n";
    }
    std::vector<double> severe;
    for (const meshQuality& q : quality.perRank) severe.push_back(double(q.nSevereNonOrthogonal));
    os  << "    \"severelyNonOrthogonalFaces\": " << quality.overall.nSevereNonOrthogonal << ",\n"
        << "    \"severelyNonOrthogonalFacesPerRank\": " << jsonArray(severe) << "\n"
        << "  }\n"
        << "}\n";
}
