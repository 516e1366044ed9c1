#include "runSummary.H"
#include "stageClock.H"
#include "streamManip.H"
#include "VolumeMesher.H"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

using Foam::Info;
using Foam::fixed;
using Foam::setprecision;
using Foam::setw;

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

// A JSON array of strings
std::string jsonStrings(const std::vector<std::string>& values)
{
    std::string list = "[";
    for (std::size_t i = 0; i < values.size(); ++i)
    {
        list += (i ? ", " : "") + jsonString(values[i]);
    }
    return list + ']';
}

// The run's figures from every rank (collective)
struct runFigures
{
    double total = 0;
    double coarseTime = 0;
    double fineTime = 0;
    double perCore = 0;
    double memorySum = 0;
    double bytesAboveBase = 0;
    std::vector<double> memory;
    std::vector<double> cellsPerRank;
    std::vector<double> attemptsPerRank;
    std::vector<double> callsPerRank;
    std::vector<double> largestCallPerRank;
    std::vector<double> messagesPerRank;
    std::vector<double> bytesSentPerRank;
    std::vector<double> backendPerRank;
    std::vector<std::string> backends;
    pmsh::trafficCounts traffic;
    pmsh::minAvgMax memoryBytes;
};


runFigures gatherFigures
(
    const pmsh::Communicator& comm,
    const pmsh::partitionVolumeResult& volume,
    std::int64_t nFineCells,
    const pmsh::stageLog& stages
)
{
    using namespace pmsh;
    runFigures f;
    f.total = stages.total();
    f.traffic = comm.traffic();
    f.backends = VolumeMesher::names();

    // One collective for this rank's figures, as meshQuality gathers its own
    struct rankRun
    {
        double memory, cells, attempts, calls, largestCall, messages, bytesSent, backend;
    };
    const rankRun mine
    {
        double(peakMemoryBytes()), double(volume.nCells), double(volume.attempts),
        double(volume.nCalls), double(volume.largestCall),
        f.traffic.messages, f.traffic.bytes,
        double
        (
            std::find(f.backends.begin(), f.backends.end(), volume.backend)
          - f.backends.begin()
        )
    };
    for (const rankRun& r : comm.allGather(mine))
    {
        f.memory.push_back(r.memory);
        f.cellsPerRank.push_back(r.cells);
        f.attemptsPerRank.push_back(r.attempts);
        f.callsPerRank.push_back(r.calls);
        f.largestCallPerRank.push_back(r.largestCall);
        f.messagesPerRank.push_back(r.messages);
        f.bytesSentPerRank.push_back(r.bytesSent);
        f.backendPerRank.push_back(r.backend);
    }
    f.memoryBytes = minAvgMaxOf(f.memory);

    // The paper's split: the coarse mesh, then everything up to the fine
    // mesh (writing excluded)
    f.coarseTime = stages.time("coarse");
    f.fineTime =
        stages.time("partition") + stages.time("surface") + stages.time("layers")
      + stages.time("volume") + stages.time("numbering") + stages.time("balance");
    f.perCore = f.fineTime > 0 ? nFineCells/f.fineTime/comm.size() : 0;
    for (double m : f.memory) f.memorySum += m;

    // What a fine cell costs a rank once the base is paid (the largest
    // rank's peak after stage 1: libraries, MPI, the coarse mesh)
    const double base = stages.peakMemory("coarse");
    for (std::size_t i = 0; i < f.memory.size(); ++i)
    {
        if (f.cellsPerRank[i] > 0)
        {
            f.bytesAboveBase =
                std::max(f.bytesAboveBase, (f.memory[i] - base)/f.cellsPerRank[i]);
        }
    }
    return f;
}


// The summary block of the log
void logSummary
(
    const pmsh::Communicator& comm,
    const runFigures& f,
    pmsh::label coarseCells,
    std::int64_t nFineCells,
    const pmsh::meshQualityReport& quality,
    const pmsh::stageLog& stages,
    const pmsh::memoryEstimate& estimate
)
{
    using namespace pmsh;
    const double MiB = 1048576.0;
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
        << "    total time:   " << f.total << " s\n"
        << setprecision(0)
        << "    fine cells/s per core (stages 2-6): " << f.perCore << '\n'
        << setprecision(1)
        << "    peak memory per rank (MiB) min/avg/max: "
        << f.memoryBytes.min/MiB << " / " << f.memoryBytes.avg/MiB << " / "
        << f.memoryBytes.max/MiB << '\n'
        << "    bytes per fine cell (all ranks): "
        << (nFineCells > 0 ? f.memorySum/nFineCells : 0)
        << ", above the stage 1 base (largest per rank): " << f.bytesAboveBase << '\n'
        << "    max non-orthogonality (checkMesh): "
        << quality.overall.maxNonOrthogonality << " degrees, average "
        << quality.overall.avgNonOrthogonality << '\n'
        << setprecision(3)
        << "    max skewness (checkMesh): " << quality.overall.maxSkewness << '\n'
        << defaultfloat << setprecision(6);
    logEstimateAccuracy
    (
        estimate, double(nFineCells),
        *std::max_element(f.cellsPerRank.begin(), f.cellsPerRank.end()),
        f.memoryBytes.max
    );
    Info << "\nEnd\n\n";
}


// The same figures for programs (bench/), and more
void writeSummaryJson
(
    const std::string& caseDir,
    const runFigures& f,
    const pmsh::Communicator& comm,
    const pmsh::meshSettings& settings,
    pmsh::label coarseCells,
    const std::string& coarseMesher,
    std::int64_t nFineCells,
    const pmsh::meshQualityReport& quality,
    const pmsh::stageLog& stages,
    const pmsh::memoryEstimate& estimate,
    const pmsh::projectionRepairSummary& repair,
    const pmsh::surfaceWrapReport& wrap,
    const pmsh::layerReport& layers
)
{
    using namespace pmsh;
    const std::string dir = caseDir + "/postProcessing/pmshFoam";
    std::filesystem::create_directories(dir);
    std::ofstream os(dir + "/summary.json");
    // One file as it is; several joined by " + " (all in geometryFiles)
    std::string geometry;
    for (const std::string& f : settings.geometryFiles)
    {
        geometry += (geometry.empty() ? "" : " + ") + f;
    }
    os  << std::setprecision(10)
        << "{\n"
        << "  \"application\": \"pmshFoam\",\n"
        << "  \"ranks\": " << comm.size() << ",\n"
        << "  \"geometry\": " << jsonString(geometry) << ",\n"
        << "  \"geometryFiles\": " << jsonStrings(settings.geometryFiles) << ",\n"
        << "  \"maxCellSize\": " << settings.maxCellSize << ",\n"
        << "  \"grading\": " << settings.grading << ",\n"
        << "  \"refinementLevels\": " << settings.refinementLevels << ",\n"
        << "  \"coarseMesher\": " << jsonString(coarseMesher) << ",\n"
        << "  \"volumeMesher\": " << jsonString(settings.volumeMesher) << ",\n"
        << "  \"coarseCells\": " << coarseCells << ",\n"
        << "  \"fineCells\": " << nFineCells << ",\n"
        << "  \"pointsOffGeometry\": " << repair.nPointsOff << ",\n"
        << "  \"maxDistanceOffGeometry\": " << repair.maxDistance << ",\n"
        << "  \"wrap\": {\"wrapped\": " << (wrap.wrapped ? "true" : "false")
        << ", \"reason\": " << jsonString(wrap.reason) << ", \"size\": " << wrap.size
        << ", \"offset\": " << wrap.offset << ", \"inputTriangles\": " << wrap.nInputTriangles
        << ", \"triangles\": " << wrap.nTriangles << ", \"tidied\": " << wrap.nTidied
        << ", \"maxDistance\": " << wrap.maxDistance
        << ", \"featureEdges\": " << wrap.nFeatureEdges
        << ", \"featureDistance\": " << wrap.featureDistance
        << ", \"featureShareWithinSize\": " << wrap.featureShareWithinSize
        << ", \"seconds\": " << wrap.seconds << "},\n"
        << "  \"meanDistanceOffGeometry\": " << repair.meanDistance << ",\n"
        << "  \"fineCellsPerRank\": " << jsonArray(f.cellsPerRank) << ",\n"
        << "  \"volumeMesherPerRank\": [";
    for (std::size_t i = 0; i < f.backendPerRank.size(); ++i)
    {
        os  << (i ? ", " : "") << jsonString(f.backends.at(std::size_t(f.backendPerRank[i])));
    }
    os  << "],\n"
        << "  \"volumeAttemptsPerRank\": " << jsonArray(f.attemptsPerRank) << ",\n"
        << "  \"volumeMesherCallsPerRank\": " << jsonArray(f.callsPerRank) << ",\n"
        << "  \"largestVolumeMesherCallPerRank\": " << jsonArray(f.largestCallPerRank) << ",\n"
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
        << "  \"coarseTime\": " << f.coarseTime << ",\n"
        << "  \"fineTime\": " << f.fineTime << ",\n"
        << "  \"writeTime\": " << stages.time("write") << ",\n"
        << "  \"totalTime\": " << f.total << ",\n"
        << "  \"fineCellsPerSecondPerCore\": " << f.perCore << ",\n"
        << "  \"peakMemoryPerRankBytes\": " << jsonArray(f.memory) << ",\n"
        << "  \"bytesPerFineCell\": " << (nFineCells > 0 ? f.memorySum/nFineCells : 0) << ",\n"
        << "  \"bytesPerFineCellAboveBase\": " << f.bytesAboveBase << ",\n"
        << "  \"broadcastBytes\": " << f.traffic.broadcastBytes << ",\n"
        << "  \"messagesPerRank\": " << jsonArray(f.messagesPerRank) << ",\n"
        << "  \"bytesSentPerRank\": " << jsonArray(f.bytesSentPerRank) << ",\n"
        << "  \"estimatedFineCells\": " << estimate.fineCells << ",\n"
        << "  \"estimatedPrisms\": " << estimate.prisms << ",\n"
        << "  \"estimatedCellsPerWeighted\": " << estimate.cellsPerWeighted << ",\n"
        << "  \"estimatedFineCellsLargestRank\": " << estimate.fineCellsPerRank << ",\n"
        << "  \"estimateShares\": {\"sizeField\": " << estimate.sizeFieldShare
        << ", \"interfaces\": " << estimate.interfaceShare << "},\n"
        << "  \"estimatedPeakMemoryPerRankBytes\": " << estimate.bytesPerRank << ",\n"
        << "  \"prisms\": " << layers.prisms << ",\n"
        << "  \"layers\": {";
    for (std::size_t i = 0; i < layers.patches.size(); ++i)
    {
        const patchLayerReport& r = layers.patches[i];
        os  << (i ? ",\n" : "\n") << "    " << jsonString(r.patch) << ": {\"faces\": "
            << r.faces << ", \"layers\": " << r.layers << ", \"coverage\": "
            << r.coverage() << ", \"firstLayer\": "
            << jsonArray(std::vector<double>(r.firstLayer, r.firstLayer + 3))
            << ", \"thickness\": "
            << jsonArray(std::vector<double>(r.thickness, r.thickness + 3)) << "}";
    }
    os  << (layers.patches.empty() ? "},\n" : "\n  },\n")
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
    const projectionRepairSummary& repair,
    const surfaceWrapReport& wrap,
    const layerReport& layers
)
{
    const runFigures figures = gatherFigures(comm, volume, nFineCells, stages);
    logSummary(comm, figures, coarseCells, nFineCells, quality, stages, estimate);
    if (comm.master())
    {
        writeSummaryJson
        (
            caseDir, figures, comm, settings, coarseCells, coarseMesher,
            nFineCells, quality, stages, estimate, repair, wrap, layers
        );
    }
}


// ************************************************************************* //
