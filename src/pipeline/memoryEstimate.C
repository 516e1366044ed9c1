/*---------------------------------------------------------------------------*\
  pmshFoam: how big will the mesh be, will it fit? (see memoryEstimate.H)

  The figures, measured by bench/memoryFigures.py (this pmshFoam, binary
  output, bench/results/memory-figures.md) on the tutorial geometries at
  maxCellSize 0.3 (sphere, sphereSTL) and 0.45 (shaft):

      geometry   volume coarse  r  P  coarse    fine   fine/    B/cell  base  peak
                                      cells     cells  regular  >base   MiB   MiB
      sphere     netgen netgen 2  1    498     35801  1.519    112   114   118
      sphere     netgen netgen 3  2    498    275934  1.463    549   113   192
      sphere     netgen hxt    2  2    700     31579  0.900    222   112   115
      sphere     hxt    netgen 3  1    498    317120  1.682    108   113   146
      sphere     hxt    netgen 4  2    498   2415266  1.601    149   113   297
      sphere     hxt    hxt    3  2    706    308007  1.098    159   112   136
      sphere     hxt    hxt    4  1    727   2502266  1.087    134   113   432
      shaft      netgen netgen 2  1    869     31111  0.729     87   115   117
      shaft      netgen netgen 3  2    869    203843  0.597    164   114   130
      shaft      netgen hxt    2  2   1088     31559  0.579    217   112   116
      shaft      hxt    netgen 3  1    869    463750  1.358    106   114   161
      shaft      hxt    netgen 4  2    869   2928474  1.072    154   114   335
      shaft      hxt    hxt    3  2   1086    382314  0.883    157   112   140
      shaft      hxt    hxt    4  1   1051   3656780  1.091    150   113   634
      sphereSTL  netgen netgen 2  1    428     34363  1.620     91   115   118
      sphereSTL  netgen netgen 3  2    428    290049  1.710    395   114   170
      sphereSTL  netgen hxt    2  2    619     31209  0.967    179   113   116
      sphereSTL  hxt    netgen 3  1    428    300301  1.770    106   115   145
      sphereSTL  hxt    netgen 4  2    428   2340505  1.724    148   114   282
      sphereSTL  hxt    hxt    3  2    619    293217  1.152    158   113   134
      sphereSTL  hxt    hxt    4  1    612   2393611  1.200    131   114   412

  "fine/regular" is fine cells over weightedFineCells: the factor of the
  volume and coarse meshers (an HXT coarse mesh has more, shorter edges for
  the same fine mesh). "B/cell >base" is the largest rank's peak above the
  stage-1 base per fine cell of that rank: Netgen's volume mesher holds
  2-4 times what HXT's does. Each pair of meshers gets its mean factor as
  expected and, as least, a figure below every measured one; the bytes per
  cell likewise (from the runs of 100k cells or more, where the base does
  not hide them).
\*---------------------------------------------------------------------------*/

#include "memoryEstimate.H"

#include "Info.H"
#include "OSspecific.H"
#include "Pstream.H"
#include "stageClock.H"
#include "pmshError.H"
#include "VolumeMesher.H"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

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

const mesherFigures figures[] =
{
    {"netgen", "netgen", 1.2, 0.5, 400, 120},
    {"netgen", "hxt", 0.8, 0.5, 400, 120},
    {"hxt", "netgen", 1.5, 0.95, 150, 100},
    {"hxt", "hxt", 1.05, 0.8, 150, 100}
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

} // End anonymous namespace


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

pmsh::memoryEstimate pmsh::estimateMemory
(
    double weightedFineCells,
    const std::string& volumeMesher,
    const std::string& coarseMesher,
    int nRanks,
    double baseBytes
)
{
    const mesherFigures& f = figuresOf(volumeMesher, coarseMesher);
    nRanks = std::max(nRanks, 1);
    memoryEstimate e;
    e.fineCells = f.cellsPerWeighted*weightedFineCells;
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
    globalLabel coarseCells,
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

    // The entry, as every other pmshDict error names it
    os  << "Entry 'refinementLevels' in dictionary \"" << settings.dictFile
        << "\"";
    if (settings.refinementLevelsLine > 0)
    {
        os  << " (line " << settings.refinementLevelsLine << ") is " << r;
    }
    else
    {
        os  << " is not given: the default " << r;
    }
    os  << ": the mesh cannot fit in the memory of this machine.\n";

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


int pmsh::ranksOnThisMachine(const Communicator& comm)
{
    if (!comm.parallel())
    {
        return 1;
    }
    // Ranks whose host name is this rank's
    Foam::List<Foam::string> hosts(Foam::UPstream::nProcs());
    hosts[Foam::UPstream::myProcNo()] = Foam::hostName();
    Foam::Pstream::gatherList(hosts);
    Foam::Pstream::scatterList(hosts);
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
    globalLabel coarseCells,
    double weightedFineCells,
    bool check
)
{
    const int ranksOnMachine = ranksOnThisMachine(comm);
    const double baseBytes = comm.max(double(peakMemoryBytes()));
    const memoryEstimate e = estimateMemory
    (
        weightedFineCells, settings.volumeMesher, settings.coarseMesher,
        comm.size(), baseBytes
    );
    const double machineBytes = double(machineMemoryBytes());

    Info()
        << "    expected fine cells: " << count(e.fineCells) << " (largest rank "
        << count(e.fineCellsPerRank) << "), peak memory per rank: "
        << memorySizeName(e.bytesPerRank) << ", "
        << memorySizeName(ranksOnMachine*e.bytesPerRank) << " for the "
        << plural(ranksOnMachine, "rank") << " on the master's machine of "
        << memorySizeName(machineBytes) << '\n';

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
        Info() << "    memory check skipped (-noMemoryCheck)\n";
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
    Info()
        << "    estimate after stage 1 (measured/expected): fine cells "
        << ratio(fineCells, estimate.fineCells) << ", largest rank's cells "
        << ratio(largestRankFineCells, estimate.fineCellsPerRank)
        << ", peak memory per rank " << ratio(largestPeakBytes, estimate.bytesPerRank)
        << " (" << memorySizeName(largestPeakBytes) << " of "
        << memorySizeName(estimate.bytesPerRank) << ")\n";
}


// ************************************************************************* //
