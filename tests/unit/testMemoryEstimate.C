/*---------------------------------------------------------------------------*\
  Tests of the memory estimate checked after the coarse mesh
  (src/pipeline/memoryEstimate).
\*---------------------------------------------------------------------------*/

#include "memoryEstimate.H"
#include "stageClock.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace pmsh;
using pmsh::test::errorOf;

namespace
{

const double GiB = 1024.0*1024*1024;

meshSettings sphereSettings(int levels, int line = 19)
{
    meshSettings s;
    s.dictFile = "/cases/sphere/system/pmshDict";
    s.geometryFile = "/cases/sphere/constant/geometry/sphere.geo";
    s.maxCellSize = 0.25;
    s.refinementLevels = levels;
    s.refinementLevelsLine = line;
    return s;
}

} // End anonymous namespace


TEST(memoryEstimate, aRunRefusedOnOneRankPassesOnMoreMachinesOrACoarserMesh)
{
    // 917 coarse cells at r = 5 (some 30 million cells) do not fit one
    // 4 GiB machine; spread over 16 such machines they do, and so does a
    // coarse mesh of 20 cells on one
    EXPECT_THROW(checkMemoryEstimate(sphereSettings(5), 917, 1, 1, 4*GiB), FatalError);
    EXPECT_NO_THROW(checkMemoryEstimate(sphereSettings(5), 917, 16, 1, 4*GiB));
    EXPECT_NO_THROW(checkMemoryEstimate(sphereSettings(5), 20, 1, 1, 4*GiB));

    // What does not fit at a level does not fit at any higher one
    for (int r = 6; r <= 10; ++r)
    {
        EXPECT_THROW(checkMemoryEstimate(sphereSettings(r), 917, 1, 1, 4*GiB), FatalError) << r;
    }
}


TEST(memoryEstimate, coversTheMeasuredRuns)
{
    // Measured peaks (memoryEstimate.C): the estimate must not be below any
    // of them, nor absurdly above (it would reject runs that fit)
    struct run { globalLabel coarse; int r; int np; double peakMiB; };
    const run runs[] =
    {
        {917, 2, 1, 93}, {917, 3, 1, 386}, {917, 3, 2, 268},
        {932, 2, 1, 99}, {932, 3, 2, 216}, {840, 2, 1, 92}, {840, 3, 4, 182}
    };
    for (const run& x : runs)
    {
        const double estimate = estimateMemory(x.coarse, x.r, x.np).bytesPerRank;
        const double peak = x.peakMiB*1048576;
        EXPECT_GT(estimate, peak) << x.coarse << " r=" << x.r << " np=" << x.np;
        EXPECT_LT(estimate, 2.5*peak) << x.coarse << " r=" << x.r << " np=" << x.np;
    }
}


TEST(memoryEstimate, hugeLevelsDoNotOverflow)
{
    const memoryEstimate e = estimateMemory(2000000000, 10, 1);
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


TEST(memoryEstimate, aRunThatFitsPasses)
{
    // 917 coarse cells at r = 3: about 0.7 GB on a 16 GiB machine
    EXPECT_NO_THROW(checkMemoryEstimate(sphereSettings(3), 917, 1, 1, 16*GiB));
    EXPECT_NO_THROW(checkMemoryEstimate(sphereSettings(4), 917, 4, 4, 16*GiB));
}


TEST(memoryEstimate, tooManyLevelsNameTheEntryTheEstimateAndTheMemory)
{
    const std::string m = errorOf
    (
        [] { checkMemoryEstimate(sphereSettings(10), 917, 1, 1, 16*GiB); }
    );
    ASSERT_FALSE(m.empty()) << "refinementLevels 10 on 917 coarse cells passed";
    EXPECT_NE(m.find("/cases/sphere/system/pmshDict"), std::string::npos) << m;
    EXPECT_NE(m.find("'refinementLevels'"), std::string::npos) << m;
    EXPECT_NE(m.find("(line 19) is 10"), std::string::npos) << m;
    EXPECT_NE(m.find("917 coarse cells x 8^10"), std::string::npos) << m;
    EXPECT_NE(m.find("PiB per rank"), std::string::npos) << m;
    EXPECT_NE(m.find("16.0 GiB of memory"), std::string::npos) << m;

    // What to do: fewer levels (4 fits: ~5.6 GB), more ranks, larger
    // maxCellSize
    EXPECT_NE(m.find("at most 4"), std::string::npos) << m;
    EXPECT_NE(m.find("more ranks"), std::string::npos) << m;
    EXPECT_NE(m.find("larger maxCellSize"), std::string::npos) << m;
}


TEST(memoryEstimate, suggestedLevelsFitAndOneMoreDoesNot)
{
    // Each suggestion must be right: at the level it proposes the check
    // passes, one level more it fails
    const std::string m = errorOf
    (
        [] { checkMemoryEstimate(sphereSettings(8), 917, 2, 2, 16*GiB); }
    );
    const auto at = m.find("at most ");
    ASSERT_NE(at, std::string::npos) << m;
    const int levels = std::stoi(m.substr(at + 8));
    EXPECT_NO_THROW(checkMemoryEstimate(sphereSettings(levels), 917, 2, 2, 16*GiB));
    EXPECT_THROW
    (
        checkMemoryEstimate(sphereSettings(levels + 1), 917, 2, 2, 16*GiB),
        FatalError
    );
}


TEST(memoryEstimate, suggestedMachineCountFits)
{
    // 4 ranks per machine: the suggested number of ranks, 4 per machine,
    // must pass the check
    const std::string m = errorOf
    (
        [] { checkMemoryEstimate(sphereSettings(6), 917, 4, 4, 16*GiB); }
    );
    const auto at = m.find("at least ");
    ASSERT_NE(at, std::string::npos) << m;
    const double ranks = std::stod(m.substr(at + 9));
    EXPECT_EQ(std::fmod(ranks, 4), 0) << m;
    EXPECT_NO_THROW(checkMemoryEstimate(sphereSettings(6), 917, int(ranks), 4, 16*GiB));
    EXPECT_THROW
    (
        checkMemoryEstimate(sphereSettings(6), 917, int(ranks) - 4, 4, 16*GiB),
        FatalError
    );
}


TEST(memoryEstimate, suggestedMaxCellSizeFits)
{
    const std::string m = errorOf
    (
        [] { checkMemoryEstimate(sphereSettings(6), 917, 1, 1, 16*GiB); }
    );
    const auto at = m.find("maxCellSize: about ");
    ASSERT_NE(at, std::string::npos) << m;
    const double h = std::stod(m.substr(at + 19));
    EXPECT_GT(h, 0.25);

    // Coarse cells scale with 1/h^3
    const double coarse = 917*std::pow(0.25/h, 3);
    EXPECT_NO_THROW
    (
        checkMemoryEstimate(sphereSettings(6), globalLabel(coarse*0.99), 1, 1, 16*GiB)
    );
}


TEST(memoryEstimate, ranksSharingAMachineShareItsMemory)
{
    // 4 levels on 4 ranks (about 1.5 GB each): on four 4 GiB machines they
    // fit, all four on one 4 GiB machine do not
    EXPECT_NO_THROW(checkMemoryEstimate(sphereSettings(4), 917, 4, 1, 4*GiB));
    const std::string m = errorOf
    (
        [] { checkMemoryEstimate(sphereSettings(4), 917, 4, 4, 4*GiB); }
    );
    EXPECT_NE(m.find("for the 4 ranks on this machine"), std::string::npos) << m;
}


TEST(memoryEstimate, aDefaultedEntrySaysSo)
{
    const std::string m = errorOf
    (
        [] { checkMemoryEstimate(sphereSettings(9, 0), 917, 1, 1, 16*GiB); }
    );
    EXPECT_NE(m.find("'refinementLevels'"), std::string::npos) << m;
    EXPECT_NE(m.find("is not given: the default 9"), std::string::npos) << m;
}


TEST(memoryEstimate, unknownMachineMemoryIsNotChecked)
{
    EXPECT_NO_THROW(checkMemoryEstimate(sphereSettings(10), 917, 1, 1, 0));
}


TEST(memoryEstimate, theSerialRunIsOneRankOnItsMachine)
{
    const Communicator serial;
    EXPECT_EQ(ranksOnThisMachine(serial), 1);
    EXPECT_GT(machineMemoryBytes(), 0);

    // The sphere tutorial at 10 levels cannot fit on any machine today
    const std::string m = errorOf
    (
        [&] { checkMemoryEstimate(serial, sphereSettings(10), 917); }
    );
    EXPECT_NE(m.find("'refinementLevels'"), std::string::npos) << m;
    EXPECT_NO_THROW(checkMemoryEstimate(serial, sphereSettings(1), 917));
}


// ************************************************************************* //
