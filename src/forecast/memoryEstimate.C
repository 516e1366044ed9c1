/*---------------------------------------------------------------------------*\
  pmshFoam: how big will the mesh be, will it fit? (see memoryEstimate.H)

  The figures, measured by bench/memoryFigures.py (this pmshFoam, binary
  output, bench/results/memory-figures.md) on the tutorial geometries at
  maxCellSize 0.3 (sphere, sphereSTL) and 0.45 (shaft):

      geometry   volume coarse  r  P  coarse    fine   fine/    B/cell  base  peak
                                      cells     cells  weighted >base   MiB   MiB
      sphere     netgen netgen 2  1    498     35801   4.589    105   114   117
      sphere     netgen netgen 3  2    498    267209   4.699    464   113   172
      sphere     netgen hxt    2  2    696     31880   3.728    219   112   115
      sphere     hxt    netgen 3  1    498    317185   5.578    107   114   146
      sphere     hxt    netgen 4  2    498   2433451   5.624    150   112   288
      sphere     hxt    hxt    3  2    701    308084   4.852    159   112   135
      sphere     hxt    hxt    4  1    685   2504511   5.188    134   113   432
      shaft      netgen netgen 2  1    869     31111   5.352     91   115   118
      shaft      netgen netgen 3  2    869    189273   5.062    164   114   128
      shaft      netgen hxt    2  2   1036     31040   5.153    216   112   116
      shaft      hxt    netgen 3  1    869    463527  12.397    106   115   162
      shaft      hxt    netgen 4  2    869   2789550  10.619    159   114   329
      shaft      hxt    hxt    3  2   1062    386677   9.827    159   112   142
      shaft      hxt    hxt    4  1   1035   3654028  13.206    149   113   634
      sphereSTL  netgen netgen 2  1    428     34363   4.615     91   115   118
      sphereSTL  netgen netgen 3  2    428    256782   4.728    454   114   170
      sphereSTL  netgen hxt    2  2    596     30409   3.726    176   113   116
      sphereSTL  hxt    netgen 3  1    428    299709   5.519    105   115   145
      sphereSTL  hxt    netgen 4  2    428   2326791   5.628    149   114   280
      sphereSTL  hxt    hxt    3  2    599    290405   4.835    158   113   135
      sphereSTL  hxt    hxt    4  1    626   2394048   5.137    131   114   413

  "fine/weighted" is fine cells over the weights of fineCellWeights.H, by
  which the estimate once counted; it now counts from the fine size field
  (sizeFieldCells.H, below). "B/cell >base" is the largest rank's
  peak above the stage-1 base per fine cell of that rank: Netgen's volume
  mesher holds 2-4 times what HXT's does. Each mesher gets about its mean
  figure as expected and, as least, a figure below every measured one
  (from the runs of 100k cells or more, where the base does not hide
  them).
\*---------------------------------------------------------------------------*/

#include "memoryEstimate.H"
#include "foamShims.H"

#include "streamManip.H"
#include "labelLimit.H"
#include "OSspecific.H"
#include "Pstream.H"
#include "stageClock.H"
#include "pmshError.H"
#include "VolumeMesher.H"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

using Foam::Info;

// * * * * * * * * * * * * * * * * Local helpers  * * * * * * * * * * * * * //

namespace
{

//- What a volume mesher makes of a coarse mesher's mesh, and holds per
//  fine cell: expected (about the mean of the measured runs) and least
//  (below every measured run).
struct mesherFigures
{
    const char* volumeMesher;
    const char* coarseMesher;
    double cellsPerWeighted;         //!< fine cells per weightedFineCells
    double leastCellsPerWeighted;
    double bytesPerCell;            //!< peak bytes per fine cell above the base
    double leastBytesPerCell;
};

// Tets per sizeFieldTerms::weighted(), fitted on the first 26 cases of
// bench/results/estimates.md (tutorials, bodies in boxes, patch and region
// sizes, layers, r = 1..3): Netgen made 1.9-3.7, HXT 2.3-4.2; 2.8 and 3.4
// put every case within 0.67-1.5, high rather than low (all 39 now:
// 0.74-1.43). The least figures are below every run there.
const mesherFigures figures[] =
{
    {"netgen", "netgen", 2.8, 1.8, 400, 120},
    {"netgen", "hxt", 2.8, 1.8, 400, 120},
    {"hxt", "netgen", 3.4, 2.2, 150, 100},
    {"hxt", "hxt", 3.4, 2.2, 150, 100}
};

//- The largest rank's share of the fine cells: the partition balances
//  expected fine cells, each part to within a few percent.
constexpr double largestRankShare = 1.1;

const mesherFigures& figuresOf
(
    const std::string& volumeMesher,
    const std::string& coarseMesher
)
{
    for (const mesherFigures& f : figures)
    {
        if (volumeMesher == f.volumeMesher && coarseMesher == f.coarseMesher)
        {
            return f;
        }
    }
    throw pmsh::FatalError
    (
        "no memory figures for volumeMesher " + volumeMesher
      + " with coarseMesher " + coarseMesher,
        "pmsh::estimateMemory"
    );
}


//- A count as a whole number ("58600"), or "9.85e+11" when very large.
std::string count(double n)
{
    std::ostringstream os;
    if (n < 1e9)
    {
        os << std::fixed;
        os.precision(0);
    }
    else
    {
        os.precision(3);
    }
    os << n;
    return os.str();
}


std::string plural(double n, const std::string& word)
{
    return count(n) + ' ' + word + (n == 1 ? "" : "s");
}


//- The entry refinementLevels, as every other pmshDict error names it:
//  Entry 'refinementLevels' in dictionary "<file>" (line <n>) is <r>
std::string refinementLevelsEntry(const pmsh::meshSettings& settings)
{
    std::ostringstream os;
    os  << "Entry 'refinementLevels' in dictionary \"" << settings.dictFile
        << "\"";
    if (settings.refinementLevelsLine > 0)
    {
        os  << " (line " << settings.refinementLevelsLine << ") is "
            << settings.refinementLevels;
    }
    else
    {
        os  << " is not given: the default " << settings.refinementLevels;
    }
    return os.str();
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

pmsh::memoryEstimate pmsh::estimateMemory
(
    double weightedFineCells,
    const std::string& volumeMesher,
    const std::string& coarseMesher,
    int nRanks,
    double baseBytes,
    double prisms
)
{
    const mesherFigures& f = figuresOf(volumeMesher, coarseMesher);
    nRanks = std::max(nRanks, 1);
    memoryEstimate e;
    e.cellsPerWeighted = f.cellsPerWeighted;
    e.prisms = prisms;
    e.fineCells = f.cellsPerWeighted*weightedFineCells + prisms;
    e.fineCellsPerRank = std::min(e.fineCells, largestRankShare*e.fineCells/nRanks);
    e.bytesPerRank = baseBytes + f.bytesPerCell*e.fineCellsPerRank;
    e.leastBytesPerRank =
        baseBytes
      + f.leastBytesPerCell*f.leastCellsPerWeighted*weightedFineCells/nRanks;
    return e;
}


std::string pmsh::memorySizeName(double bytes)
{
    static const char* const units[] =
        {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int u = 0;
    while (bytes >= 1024 && u < 6)
    {
        bytes /= 1024;
        ++u;
    }
    char buf[64];
    if (u == 0 || bytes >= 100)
    {
        std::snprintf(buf, sizeof(buf), "%.0f %s", bytes, units[u]);
    }
    else
    {
        std::snprintf(buf, sizeof(buf), "%.1f %s", bytes, units[u]);
    }
    return buf;
}


void pmsh::checkMemoryEstimate
(
    const meshSettings& settings,
    std::int64_t coarseCells,
    double weightedFineCells,
    int nRanks,
    int ranksOnMachine,
    double baseBytes,
    double machineBytes
)
{
    if (!(machineBytes > 0))
    {
        return;
    }
    nRanks = std::max(nRanks, 1);
    ranksOnMachine = std::max(ranksOnMachine, 1);

    const int r = settings.refinementLevels;
    const std::string& mesher = settings.volumeMesher;
    const std::string& coarseMesher = settings.coarseMesher;
    const memoryEstimate e =
        estimateMemory(weightedFineCells, mesher, coarseMesher, nRanks, baseBytes);
    if (ranksOnMachine*e.leastBytesPerRank <= machineBytes)
    {
        return;
    }

    // The least memory of a rank with `regular` weightedFineCells on `ranks`
    auto least = [&](double regular, int ranks)
    {
        return estimateMemory(regular, mesher, coarseMesher, ranks, baseBytes)
            .leastBytesPerRank;
    };
    const mesherFigures& f = figuresOf(mesher, coarseMesher);
    const double leastFineCells = f.leastCellsPerWeighted*weightedFineCells;

    std::ostringstream os;
    os  << refinementLevelsEntry(settings)
        << ": the mesh cannot fit in the memory of this machine.\n";

    os  << "The " << coarseCells << " coarse cells refined " << r << " times"
        << " give about " << count(e.fineCells) << " fine cells with"
        << " volumeMesher " << mesher << " (coarseMesher " << coarseMesher
        << "), at least " << count(leastFineCells)
        << "; at no less than " << count(f.leastBytesPerCell) << " bytes per"
        << " fine cell (" << mesher << ") that is at least "
        << memorySizeName(e.leastBytesPerRank) << " per rank on "
        << plural(nRanks, "rank") << " (about "
        << memorySizeName(e.bytesPerRank) << " expected), "
        << memorySizeName(ranksOnMachine*e.leastBytesPerRank) << " for the "
        << plural(ranksOnMachine, "rank") << " on this machine, which has "
        << memorySizeName(machineBytes) << " of memory.\n";

    os  << "To fit, use\n";

    // Fewer levels, with these ranks
    int fitLevels = -1;
    for (int l = r - 1; l >= 0; --l)
    {
        if (ranksOnMachine*least(weightedFineCells/std::pow(8.0, r - l), nRanks) <= machineBytes)
        {
            fitLevels = l;
            break;
        }
    }
    if (fitLevels >= 0)
    {
        os  << "    - fewer refinementLevels: at most " << fitLevels
            << " with this maxCellSize on " << plural(nRanks, "rank") << ";\n";
    }
    else
    {
        os  << "    - fewer refinementLevels: not enough alone, even 0 levels"
            << " would not fit;\n";
    }

    // More machines, each with as many ranks as this one: the fine cells
    // are shared out, each rank keeps its base
    const double perMachine = machineBytes - ranksOnMachine*baseBytes;
    const double cellBytes = f.leastBytesPerCell*leastFineCells;
    if (perMachine > 0)
    {
        const double machines = std::ceil(cellBytes/perMachine);
        os  << "    - more ranks on more machines: at least "
            << plural(machines*ranksOnMachine, "rank") << ", "
            << ranksOnMachine << " on each of " << plural(machines, "machine")
            << " with this much memory;\n";
    }
    else
    {
        os  << "    - fewer ranks per machine (" << ranksOnMachine
            << " ranks here) on more machines;\n";
    }

    // A larger maxCellSize: fine cells scale with 1/maxCellSize^3
    const double cellsThatFit = (machineBytes/ranksOnMachine - baseBytes)*nRanks;
    if (cellsThatFit > 0 && cellBytes > 0)
    {
        // Three significant digits, rounded up so that it does fit
        const double h = settings.maxCellSize*std::cbrt(cellBytes/cellsThatFit);
        const double unit = std::pow(10.0, std::floor(std::log10(h)) - 2);
        os  << "    - a larger maxCellSize: about "
            << std::ceil(h/unit)*unit << " or more (it is "
            << settings.maxCellSize << "; each doubling gives about 8 times"
            << " fewer cells);\n";
    }
    else
    {
        os  << "    - a larger maxCellSize: not enough alone, not even the"
            << " base of a rank fits (maxCellSize is " << settings.maxCellSize
            << ");\n";
    }
    os  << "or, if you know this machine better than the estimate does, run"
        << " with -noMemoryCheck.";

    throw FatalError(os.str(), "pmsh::checkMemoryEstimate");
}


void pmsh::checkLabelEstimate
(
    const meshSettings& settings,
    std::int64_t coarseCells,
    double weightedFineCells
)
{
    const std::int64_t maxLabel = labelLimit;
    // A tet mesh has at least two faces a cell (four faces, each shared by
    // at most two cells): the least faces, from the least fine cells
    const mesherFigures& f = figuresOf(settings.volumeMesher, settings.coarseMesher);
    auto leastFaces = [&](double weighted)
    {
        return 2*f.leastCellsPerWeighted*weighted;
    };
    if (leastFaces(weightedFineCells) <= double(maxLabel))
    {
        return;
    }

    const int r = settings.refinementLevels;
    std::ostringstream os;
    os  << refinementLevelsEntry(settings)
        << ": the mesh is too large for this OpenFOAM's " << labelBits
        << "-bit labels (largest label " << maxLabel << ").\n"
        << "The " << coarseCells << " coarse cells refined " << r << " times"
        << " give about "
        << count(f.cellsPerWeighted*weightedFineCells) << " fine cells with"
        << " volumeMesher " << settings.volumeMesher << ", at least "
        << count(f.leastCellsPerWeighted*weightedFineCells) << ", so at least "
        << count(leastFaces(weightedFineCells)) << " faces.\n"
        << "Use pmshFoam built with an OpenFOAM of WM_LABEL_SIZE=64 (see"
        << " pmshFoam's README, Building), or fewer cells: ";
    int fitLevels = -1;
    for (int l = r - 1; l >= 0; --l)
    {
        if (leastFaces(weightedFineCells/std::pow(8.0, r - l)) <= double(maxLabel))
        {
            fitLevels = l;
            break;
        }
    }
    if (fitLevels >= 0)
    {
        os  << "at most " << fitLevels << " refinementLevels with this"
            << " maxCellSize, or a larger maxCellSize";
    }
    else
    {
        os  << "a larger maxCellSize";
    }
    throw FatalError(os.str(), "pmsh::checkLabelEstimate");
}


int pmsh::ranksOnThisMachine(const Communicator& comm)
{
    if (!comm.parallel())
    {
        return 1;
    }
    // Ranks whose host name is this rank's
    Foam::List<Foam::string> hosts(Foam::UPstream::nProcs());
    hosts[Foam::UPstream::myProcNo()] = Foam::hostName();
    foam::allGatherList(hosts);
    int n = 0;
    for (const Foam::string& host : hosts)
    {
        n += (host == hosts[Foam::UPstream::myProcNo()]);
    }
    return n;
}


pmsh::memoryEstimate pmsh::estimateAndCheckMemory
(
    const Communicator& comm,
    const meshSettings& settings,
    std::int64_t coarseCells,
    double weightedFineCells,
    double prisms,
    bool check
)
{
    const int ranksOnMachine = ranksOnThisMachine(comm);
    const double baseBytes = comm.max(double(peakMemoryBytes()));
    const memoryEstimate e = estimateMemory
    (
        weightedFineCells, settings.volumeMesher, settings.coarseMesher,
        comm.size(), baseBytes, prisms
    );
    const double machineBytes = double(machineMemoryBytes());

    Info
        << "    expected fine cells: " << count(e.fineCells).c_str() << " (largest rank "
        << count(e.fineCellsPerRank).c_str();
    if (e.prisms > 0)
    {
        Info << "; prisms of the layers " << count(e.prisms).c_str();
    }
    Info
        << "), peak memory per rank: "
        << memorySizeName(e.bytesPerRank).c_str() << ", "
        << memorySizeName(ranksOnMachine*e.bytesPerRank).c_str() << " for the "
        << plural(ranksOnMachine, "rank").c_str() << " on the master's machine of "
        << memorySizeName(machineBytes).c_str() << '\n';

    // Labels are a hard limit of the build: no option skips this
    checkLabelEstimate(settings, coarseCells, weightedFineCells);

    if (check)
    {
        checkMemoryEstimate
        (
            settings, coarseCells, weightedFineCells, comm.size(),
            ranksOnMachine, baseBytes, machineBytes
        );
    }
    else
    {
        Info << "    memory check skipped (-noMemoryCheck)\n";
    }
    return e;
}


void pmsh::logEstimateAccuracy
(
    const memoryEstimate& estimate,
    double fineCells,
    double largestRankFineCells,
    double largestPeakBytes
)
{
    auto ratio = [](double measured, double expected)
    {
        std::ostringstream os;
        os.precision(2);
        os << std::fixed << (expected > 0 ? measured/expected : 0);
        return os.str();
    };
    Info
        << "    estimate after stage 1 (measured/expected): fine cells "
        << ratio(fineCells, estimate.fineCells).c_str() << ", largest rank's cells "
        << ratio(largestRankFineCells, estimate.fineCellsPerRank).c_str()
        << ", peak memory per rank " << ratio(largestPeakBytes, estimate.bytesPerRank).c_str()
        << " (" << memorySizeName(largestPeakBytes).c_str() << " of "
        << memorySizeName(estimate.bytesPerRank).c_str() << ")\n";
}


// ************************************************************************* //
