/*---------------------------------------------------------------------------*\
  Tests of the memory estimate checked after the coarse mesh
  (src/forecast/memoryEstimate).
\*---------------------------------------------------------------------------*/

#include "memoryEstimate.H"
#include "fineMeshForecast.H"
#include "stageClock.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

using namespace pmsh;
using pmsh::test::errorOf;

namespace
{

const double GiB = 1024.0*1024*1024;
const double MiB = 1024.0*1024;

//- A rank's base memory after stage 1 (measured: 112-120 MiB)
const double base = 115*MiB;

meshSettings sphereSettings(int levels, const std::string& mesher = "netgen", int line = 19)
{
    meshSettings s;
    s.dictFile = "/cases/sphere/system/pmshDict";
    s.geometryFiles = {"/cases/sphere/constant/geometry/sphere.geo"};
    s.maxCellSize = 0.25;
    s.refinementLevels = levels;
    s.refinementLevelsLine = line;
    s.volumeMesher = mesher;
    return s;
}

//- weightedFineCells of a coarse mesh for which `mesher` is expected to
//  make `fineCells` cells
double weightedFor(double fineCells, const std::string& mesher)
{
    return fineCells/estimateMemory(1, mesher, "netgen", 1, 0).fineCells;
}

//- The sphere tutorial's coarse mesh (917 cells) refined r times: about
//  45k fine cells at r = 2 with Netgen
double sphereWeighted(int r)
{
    return weightedFor(45000*std::pow(8.0, r - 2), "netgen");
}

void check
(
    const meshSettings& s,
    double regular,
    int nRanks,
    int ranksOnMachine,
    double machineBytes
)
{
    checkMemoryEstimate(s, 917, regular, nRanks, ranksOnMachine, base, machineBytes);
}

} // End anonymous namespace


TEST(memoryEstimate, theHxtRunTheOldEstimateRefusedFitsAndARunTwentyTimesLargerDoesNot)
{
    // Sphere, maxCellSize 0.215, r = 5, hxt, 2 ranks: some 42 million
    // cells, ~7 GiB in all, was refused on 23.5 GiB (Netgen's figures).
    // The check refuses on the least figures (2.2 of 3.4 cells a weight,
    // 100 bytes a cell): ten times as many still may fit, twenty not
    const double regular = weightedFor(42e6, "hxt");
    EXPECT_NO_THROW(check(sphereSettings(5, "hxt"), regular, 2, 2, 23.5*GiB));
    EXPECT_THROW(check(sphereSettings(5, "hxt"), 20*regular, 2, 2, 23.5*GiB), FatalError);
}


TEST(memoryEstimate, aMeasuredRunPassesOnItsPeakAndIsRefusedWellBelowIt)
{
    // The shaft at r = 4, hxt, one rank (bench/results/memory-figures.md):
    // base 113 MiB, peak 634 MiB, measured. A machine with just its peak
    // ran it, so the check must let it through; one with a tenth of what
    // it added to the base surely cannot, so the check must refuse it
    const meshSettings s = sphereSettings(4, "hxt");
    const double regular = 276695, baseBytes = 113*MiB, peak = 634*MiB;
    const auto checkOn = [&](double machineBytes)
    {
        checkMemoryEstimate(s, 917, regular, 1, 1, baseBytes, machineBytes);
    };
    EXPECT_NO_THROW(checkOn(1.01*peak));
    EXPECT_THROW(checkOn(baseBytes + 0.1*(peak - baseBytes)), FatalError);
}


TEST(memoryEstimate, theLargestRankHoldsAtLeastAnEvenShare)
{
    const memoryEstimate one = estimateMemory(1e6, "hxt", "netgen", 1, base);
    const memoryEstimate four = estimateMemory(1e6, "hxt", "netgen", 4, base);
    EXPECT_DOUBLE_EQ(one.fineCells, four.fineCells);
    EXPECT_DOUBLE_EQ(one.fineCellsPerRank, one.fineCells);
    EXPECT_GE(four.fineCellsPerRank, four.fineCells/4);
    EXPECT_LT(four.fineCellsPerRank, four.fineCells/2);
    EXPECT_GE(four.leastBytesPerRank, base);
}


TEST(memoryEstimate, countsThePrismsOfEachLayeredFaceAtTheFineLevel)
{
    // Three coarse faces on patch 0 (5 layers), two on patch 1 (none), one
    // on patch 2 (2 layers): at r = 2 each is 16 fine triangles
    CoarseMesh coarse;
    for (label patch : {0, 0, 0, 1, 1, 2})
    {
        coarse.boundary.push_back({{0, 1, 2}, patch, 0});
    }
    std::map<label, layerSpecification> specs;
    specs[0].nLayers = 5;
    specs[2].nLayers = 2;
    EXPECT_DOUBLE_EQ(expectedPrisms(coarse, specs, 2), (3*5 + 2)*16.0);
    EXPECT_DOUBLE_EQ(expectedPrisms(coarse, {}, 2), 0);

    // Prisms add to the cells and the memory, once, on any number of ranks
    const memoryEstimate tets = estimateMemory(1e6, "hxt", "netgen", 4, base);
    const memoryEstimate layered = estimateMemory(1e6, "hxt", "netgen", 4, base, 2e5);
    EXPECT_DOUBLE_EQ(layered.fineCells, tets.fineCells + 2e5);
    EXPECT_DOUBLE_EQ(layered.prisms, 2e5);
    EXPECT_GT(layered.fineCellsPerRank, tets.fineCellsPerRank);
    EXPECT_GT(layered.bytesPerRank, tets.bytesPerRank);
}


TEST(memoryEstimate, aRunRefusedOnOneRankPassesOnMoreMachinesOrACoarserMesh)
{
    // The sphere at r = 6 (some 12 million cells with Netgen) does not fit
    // one 4 GiB machine; spread over 16 such machines it does, and so does
    // a coarse mesh 50 times smaller on one
    EXPECT_THROW(check(sphereSettings(6), sphereWeighted(6), 1, 1, 4*GiB), FatalError);
    EXPECT_NO_THROW(check(sphereSettings(6), sphereWeighted(6), 16, 1, 4*GiB));
    EXPECT_NO_THROW(check(sphereSettings(6), sphereWeighted(6)/50, 1, 1, 4*GiB));

    // What does not fit at a level does not fit at any higher one
    for (int r = 7; r <= 10; ++r)
    {
        EXPECT_THROW(check(sphereSettings(r), sphereWeighted(r), 1, 1, 4*GiB), FatalError) << r;
    }
}


TEST(memoryEstimate, coversTheMeasuredRuns)
{
    // Measured peaks (bench/results/memory-figures.md): the least must be
    // below every one of them (or a run that fits would be refused), the
    // expected peak within a factor of two (the shaft with HXT is the
    // hardest). Each run's weightedFineCells as if its mesher had made the
    // most tets per weighted seen (bench/results/estimates.md: Netgen 3.7,
    // HXT 4.2), where the least figures are furthest below the run
    struct run
    {
        const char* volumeMesher; const char* coarseMesher; double fineCells; int np;
        double baseMiB; double peakMiB;
    };
    const run runs[] =
    {
        {"netgen", "netgen", 267209, 2, 113, 172},  // sphere r=3
        {"hxt", "netgen", 317185, 1, 114, 146},  // sphere r=3
        {"hxt", "netgen", 2433451, 2, 112, 288},  // sphere r=4
        {"hxt", "hxt", 308084, 2, 112, 135},  // sphere r=3
        {"hxt", "hxt", 2504511, 1, 113, 432},  // sphere r=4
        {"netgen", "netgen", 189273, 2, 114, 128},  // shaft r=3
        {"hxt", "netgen", 463527, 1, 115, 162},  // shaft r=3
        {"hxt", "netgen", 2789550, 2, 114, 329},  // shaft r=4
        {"hxt", "hxt", 386677, 2, 112, 142},  // shaft r=3
        {"hxt", "hxt", 3654028, 1, 113, 634},  // shaft r=4
        {"netgen", "netgen", 256782, 2, 114, 170},  // sphereSTL r=3
        {"hxt", "netgen", 299709, 1, 115, 145},  // sphereSTL r=3
        {"hxt", "netgen", 2326791, 2, 114, 280},  // sphereSTL r=4
        {"hxt", "hxt", 290405, 2, 113, 135},  // sphereSTL r=3
        {"hxt", "hxt", 2394048, 1, 114, 413},  // sphereSTL r=4
    };
    for (const run& x : runs)
    {
        const double mostCellsPerWeighted = std::string(x.volumeMesher) == "hxt" ? 4.2 : 3.7;
        const memoryEstimate e = estimateMemory
        (
            x.fineCells/mostCellsPerWeighted, x.volumeMesher, x.coarseMesher,
            x.np, x.baseMiB*MiB
        );
        const double peak = x.peakMiB*MiB;
        EXPECT_LT(e.leastBytesPerRank, peak) << x.volumeMesher << '/' << x.coarseMesher << ' ' << x.fineCells << " np=" << x.np;
        EXPECT_GT(e.bytesPerRank, 0.5*peak) << x.volumeMesher << '/' << x.coarseMesher << ' ' << x.fineCells << " np=" << x.np;
        EXPECT_LT(e.bytesPerRank, 2*peak) << x.volumeMesher << '/' << x.coarseMesher << ' ' << x.fineCells << " np=" << x.np;
    }
}


TEST(memoryEstimate, hugeLevelsDoNotOverflow)
{
    const memoryEstimate e = estimateMemory(2000000000*std::pow(8.0, 10), "netgen", "netgen", 1, base);
    EXPECT_TRUE(std::isfinite(e.bytesPerRank));
    EXPECT_GT(e.bytesPerRank, 1e21);
}


TEST(memoryEstimate, sizesAreHumanReadable)
{
    EXPECT_EQ(memorySizeName(512), "512 bytes");
    EXPECT_EQ(memorySizeName(64.0*1048576), "64.0 MiB");
    EXPECT_EQ(memorySizeName(1.5*GiB), "1.5 GiB");
    EXPECT_EQ(memorySizeName(2048*GiB), "2.0 TiB");
}


TEST(memoryEstimate, tooManyLevelsNameTheEntryTheEstimateTheMemoryAndTheWayOut)
{
    const std::string m = errorOf
    (
        [] { check(sphereSettings(10), sphereWeighted(10), 1, 1, 16*GiB); }
    );
    ASSERT_FALSE(m.empty()) << "refinementLevels 10 on 917 coarse cells passed";
    EXPECT_NE(m.find("/cases/sphere/system/pmshDict"), std::string::npos) << m;
    EXPECT_NE(m.find("'refinementLevels'"), std::string::npos) << m;
    EXPECT_NE(m.find("(line 19) is 10"), std::string::npos) << m;
    EXPECT_NE(m.find("917 coarse cells refined 10 times"), std::string::npos) << m;
    EXPECT_NE(m.find("volumeMesher netgen"), std::string::npos) << m;
    EXPECT_NE(m.find("TiB per rank"), std::string::npos) << m;
    EXPECT_NE(m.find("16.0 GiB of memory"), std::string::npos) << m;

    // What to do: fewer levels, more ranks, larger maxCellSize,
    // or go on regardless
    EXPECT_NE(m.find("at most "), std::string::npos) << m;
    EXPECT_NE(m.find("more ranks"), std::string::npos) << m;
    EXPECT_NE(m.find("larger maxCellSize"), std::string::npos) << m;
    EXPECT_NE(m.find("-noMemoryCheck"), std::string::npos) << m;
}


TEST(memoryEstimate, suggestedLevelsFitAndOneMoreDoesNot)
{
    // Each suggestion must be right: at the level it proposes the check
    // passes, one level more it fails
    const std::string m = errorOf
    (
        [] { check(sphereSettings(9), sphereWeighted(9), 2, 2, 16*GiB); }
    );
    const auto at = m.find("at most ");
    ASSERT_NE(at, std::string::npos) << m;
    const int levels = std::stoi(m.substr(at + 8));
    EXPECT_NO_THROW(check(sphereSettings(levels), sphereWeighted(levels), 2, 2, 16*GiB));
    EXPECT_THROW
    (
        check(sphereSettings(levels + 1), sphereWeighted(levels + 1), 2, 2, 16*GiB),
        FatalError
    );
}


TEST(memoryEstimate, suggestedMachineCountFits)
{
    // 4 ranks per machine: the suggested number of ranks, 4 per machine,
    // must pass the check
    const std::string m = errorOf
    (
        [] { check(sphereSettings(7), sphereWeighted(7), 4, 4, 16*GiB); }
    );
    const auto at = m.find("at least ", m.find("more ranks"));
    ASSERT_NE(at, std::string::npos) << m;
    const double ranks = std::stod(m.substr(at + 9));
    EXPECT_EQ(std::fmod(ranks, 4), 0) << m;
    EXPECT_NO_THROW(check(sphereSettings(7), sphereWeighted(7), int(ranks), 4, 16*GiB));
    EXPECT_THROW
    (
        check(sphereSettings(7), sphereWeighted(7), int(ranks) - 4, 4, 16*GiB),
        FatalError
    );
}


TEST(memoryEstimate, suggestedMaxCellSizeFits)
{
    const std::string m = errorOf
    (
        [] { check(sphereSettings(7), sphereWeighted(7), 1, 1, 16*GiB); }
    );
    const auto at = m.find("maxCellSize: about ");
    ASSERT_NE(at, std::string::npos) << m;
    const double h = std::stod(m.substr(at + 19));
    EXPECT_GT(h, 0.25);

    // Fine cells scale with 1/h^3
    const double regular = sphereWeighted(7)*std::pow(0.25/h, 3);
    EXPECT_NO_THROW(check(sphereSettings(7), 0.99*regular, 1, 1, 16*GiB));
}


TEST(memoryEstimate, ranksSharingAMachineShareItsMemory)
{
    // Four ranks that each fit a machine of their own do not all fit one
    const memoryEstimate e = estimateMemory(sphereWeighted(6), "netgen", "netgen", 4, base);
    const double machine = 2*e.leastBytesPerRank;
    EXPECT_NO_THROW(check(sphereSettings(6), sphereWeighted(6), 4, 1, machine));
    const std::string m = errorOf
    (
        [&] { check(sphereSettings(6), sphereWeighted(6), 4, 4, machine); }
    );
    EXPECT_NE(m.find("for the 4 ranks on this machine"), std::string::npos) << m;
}


TEST(memoryEstimate, aDefaultedEntrySaysSo)
{
    const std::string m = errorOf
    (
        [] { check(sphereSettings(9, "netgen", 0), sphereWeighted(9), 1, 1, 16*GiB); }
    );
    EXPECT_NE(m.find("'refinementLevels'"), std::string::npos) << m;
    EXPECT_NE(m.find("is not given: the default 9"), std::string::npos) << m;
}


TEST(memoryEstimate, unknownMachineMemoryIsNotChecked)
{
    EXPECT_NO_THROW(check(sphereSettings(10), sphereWeighted(10), 1, 1, 0));
}


TEST(memoryEstimate, theSerialRunIsOneRankOnItsMachineAndNoMemoryCheckGoesOn)
{
    const Communicator serial;
    EXPECT_EQ(ranksOnThisMachine(serial), 1);
    EXPECT_GT(machineMemoryBytes(), 0);

    // The sphere tutorial at 10 levels cannot fit on any machine today
    const std::string m = errorOf
    (
        [&] { estimateAndCheckMemory(serial, sphereSettings(10), 917, sphereWeighted(10), 0, true); }
    );
    EXPECT_NE(m.find("'refinementLevels'"), std::string::npos) << m;
    EXPECT_NO_THROW(estimateAndCheckMemory(serial, sphereSettings(1), 917, sphereWeighted(1), 0, true));

    // -noMemoryCheck goes on; labels are a limit of the build, no option
    // skips them: 10 levels (some 10^12 cells) pass 32-bit labels
    auto noMemoryCheck = [&]
    {
        estimateAndCheckMemory(serial, sphereSettings(10), 917, sphereWeighted(10), 0, false);
    };
    if (labelBits == 64)
    {
        EXPECT_NO_THROW(noMemoryCheck());
    }
    else
    {
        EXPECT_HAS(errorOf(noMemoryCheck), "32-bit labels");
    }
}


TEST(labelEstimate, aMeshSurelyPastTheLabelLimitStopsNamingTheEntryAndWhatFits)
{
    // The sphere at r = 2 expects 45k cells, at least 1.8/2.8 of them, two
    // faces a cell: at least 57857 faces. Scaled to just above and just
    // below the build's own largest label
    const meshSettings s = sphereSettings(2);
    const double facesPerWeighted = 2*45000*1.8/2.8/sphereWeighted(2);
    const double atLimit = double(labelLimit)/facesPerWeighted;
    EXPECT_NO_THROW(checkLabelEstimate(s, 917, 0.99*atLimit));
    const std::string m = errorOf([&] { checkLabelEstimate(s, 917, 1.01*atLimit); });
    EXPECT_HAS(m, "Entry 'refinementLevels' in dictionary \"/cases/sphere/system/pmshDict\" (line 19) is 2");
    EXPECT_HAS(m, "too large for this OpenFOAM's " + std::to_string(labelBits) + "-bit labels (largest label " + std::to_string(labelLimit) + ")");
    EXPECT_HAS(m, "WM_LABEL_SIZE=64");
    EXPECT_HAS(m, "at most 1 refinementLevels");
}


TEST(labelEstimate, threeBillionCellsStopAtTheLabelsWith32BitsAndAtTheMemoryWith64)
{
    // The sphere at the level where Netgen gives some 3 billion cells: a
    // 32-bit build cannot hold its faces (at least 3.9 billion), a 64-bit
    // one goes on to the memory check, which refuses it on a machine of
    // 24 GiB (at least 120 bytes a cell)
    const double weighted = weightedFor(3e9, "netgen");
    const meshSettings s = sphereSettings(7);
    const std::string m = errorOf
    (
        [&] { estimateAndCheckMemory(Communicator(), s, 917, weighted, 0, false); }
    );
    if (labelBits == 32)
    {
        EXPECT_HAS(m, "too large for this OpenFOAM's 32-bit labels");
        EXPECT_HAS(m, "at least 3.86e+09 faces");
    }
    else
    {
        EXPECT_EQ(m, "");
        EXPECT_NO_THROW(checkLabelEstimate(s, 917, weighted));
        EXPECT_HAS
        (
            errorOf([&] { check(s, weighted, 1, 1, 24*GiB); }),
            "cannot fit in the memory of this machine"
        );
    }
}


// ************************************************************************* //
