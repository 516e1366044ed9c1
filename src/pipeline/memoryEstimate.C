/*---------------------------------------------------------------------------*\
  pmshFoam: will the run fit in memory? (see memoryEstimate.H)

  The figures, measured with this pmshFoam (Release, 32-bit labels, ascii)
  from postProcessing/pmshFoam/summary.json ("peakMemoryPerRankBytes",
  "fineCells", "fineCellsPerRank"; the peak is each rank's VmHWM), on the
  tutorials at their own maxCellSize:

      tutorial   r  ranks  coarse  fine cells  largest peak  marginal
      sphere     0    1      917        675      49 MiB          -
      sphere     1    1      917       5388      53 MiB          -
      sphere     2    1      917      44745      93 MiB    1031 B/cell
      sphere     3    1      917     360321     386 MiB     981 B/cell
      sphere     3    2      917     383824     268 MiB    1175 B/cell
      shaft      0    1      932       1059      49 MiB          -
      shaft      2    1      932      43640      99 MiB    1201 B/cell
      shaft      3    2      932     273997     216 MiB    1284 B/cell
      sphereSTL  0    1      840        581      51 MiB          -
      sphereSTL  2    1      840      45199      92 MiB     998 B/cell
      sphereSTL  3    4      840     385911     182 MiB    1274 B/cell

  "marginal" is (peak - 49 MiB) / fine cells of the rank with the largest
  peak: the cost of a fine cell once the base (executable, Netgen, MPI:
  49-51 MiB at r = 0) is paid. The largest is 1284 B/cell (in parallel:
  halo and numbering data); bytesPerFineCell = 1500 is 1.17 times that.
  coarseCells * 8^r is itself an upper estimate of the fine cells (0.57 to
  0.90 of it were measured), which also covers uneven partitions (the
  largest part of sphereSTL on 4 ranks had 1.14 times the average); the
  estimate was 1.2 to 2 times the measured peak of every run above. The
  base is taken as 64 MiB.
\*---------------------------------------------------------------------------*/

#include "memoryEstimate.H"

#include "OSspecific.H"
#include "Pstream.H"
#include "stageClock.H"
#include "pmshError.H"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

// * * * * * * * * * * * * * * * * Local helpers  * * * * * * * * * * * * * //

namespace
{

//- Peak bytes per fine cell a rank holds: a safe upper figure (1.17 times
//  the largest measured, 1284).
constexpr double bytesPerFineCell = 1500;

//- Peak bytes of a rank with (almost) no cells: executable, Netgen, MPI
//  (measured 49-51 MiB).
constexpr double baseBytesPerRank = 64.0*1048576;


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
    globalLabel coarseCells,
    int refinementLevels,
    int nRanks
)
{
    memoryEstimate e;
    e.fineCells = double(coarseCells)*std::pow(8.0, refinementLevels);
    e.bytesPerRank =
        baseBytesPerRank + bytesPerFineCell*e.fineCells/std::max(nRanks, 1);
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
    int nRanks,
    int ranksOnMachine,
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
    const memoryEstimate e = estimateMemory(coarseCells, r, nRanks);
    const double onMachine = ranksOnMachine*e.bytesPerRank;
    if (onMachine <= machineBytes)
    {
        return;
    }

    auto fits = [&](int levels)
    {
        return
            ranksOnMachine*estimateMemory(coarseCells, levels, nRanks).bytesPerRank
         <= machineBytes;
    };

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
    os  << ": the mesh would not fit in the memory of this machine.\n";

    os  << "The fine mesh would have about " << count(e.fineCells) << " cells ("
        << coarseCells << " coarse cells x 8^" << r << "); at "
        << count(bytesPerFineCell) << " bytes per fine cell that is about "
        << memorySizeName(e.bytesPerRank) << " per rank on "
        << plural(nRanks, "rank") << ", " << memorySizeName(onMachine)
        << " for the " << plural(ranksOnMachine, "rank") << " on this"
        << " machine, which has " << memorySizeName(machineBytes)
        << " of memory.\n";

    os  << "To fit, use\n";

    // Fewer levels, with these ranks
    int fitLevels = -1;
    for (int l = r - 1; l >= 0; --l)
    {
        if (fits(l))
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
    const double perMachine = machineBytes - ranksOnMachine*baseBytesPerRank;
    if (perMachine > 0)
    {
        const double machines =
            std::ceil(bytesPerFineCell*e.fineCells/perMachine);
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

    // A larger maxCellSize: coarse cells scale with 1/maxCellSize^3
    const double cellsThatFit =
        (machineBytes/ranksOnMachine - baseBytesPerRank)*nRanks
       /(bytesPerFineCell*std::pow(8.0, r));
    if (cellsThatFit >= 1 && coarseCells > 0)
    {
        // Three significant digits, rounded up so that it does fit
        const double h =
            settings.maxCellSize*std::cbrt(double(coarseCells)/cellsThatFit);
        const double unit = std::pow(10.0, std::floor(std::log10(h)) - 2);
        os  << "    - a larger maxCellSize: about "
            << std::ceil(h/unit)*unit << " or more (it is "
            << settings.maxCellSize << "; each doubling gives about 8 times"
            << " fewer cells).";
    }
    else
    {
        os  << "    - a larger maxCellSize: not enough alone, even one coarse"
            << " cell refined " << r << " times would not fit (maxCellSize is "
            << settings.maxCellSize << ").";
    }

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


void pmsh::checkMemoryEstimate
(
    const Communicator& comm,
    const meshSettings& settings,
    globalLabel coarseCells
)
{
    const int ranksOnMachine = ranksOnThisMachine(comm);
    checkMemoryEstimate
    (
        settings, coarseCells, comm.size(), ranksOnMachine,
        double(machineMemoryBytes())
    );
}


// ************************************************************************* //
