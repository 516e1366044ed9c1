// Stage 6: what the OpenFOAM build's label can hold. A mesh whose global
// numbers pass the label limit stops before anything is written; the
// limit is lowered here so that a small mesh reaches it.

#include "foamMeshOutput.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <numeric>

using namespace pmsh;

namespace
{

// The addressing of one rank holding global points/cells/faces 0..n-1
procAddressing addressingOf(globalLabel nPoints, globalLabel nCells, globalLabel nFaces)
{
    procAddressing a;
    a.point.resize(nPoints);
    std::iota(a.point.begin(), a.point.end(), 0);
    a.cell.resize(nCells);
    std::iota(a.cell.begin(), a.cell.end(), 0);
    for (globalLabel f = 0; f < nFaces; ++f)
    {
        a.face.push_back(f % 2 ? -(f + 1) : f + 1);     // reversed faces too
    }
    return a;
}

} // End anonymous namespace


TEST(labelLimit, globalNumbersUpToTheLimitPass)
{
    const Communicator serial;
    EXPECT_NO_THROW(checkGlobalNumbersFitLabel(serial, addressingOf(100, 50, 100), 100));
}


TEST(labelLimit, aFaceNumberPastTheLimitStopsNamingTheCountsAndTheCure)
{
    const Communicator serial;
    // Face 100 is stored as -(100 + 1): past a limit of 100
    const std::string error = test::errorOf([&]
    {
        checkGlobalNumbersFitLabel(serial, addressingOf(100, 50, 101), 100);
    });
    EXPECT_HAS
    (
        error,
        "too large for this OpenFOAM's " + std::to_string(8*sizeof(Foam::label)) + "-bit labels"
    );
    EXPECT_HAS(error, "101 (faces");
    EXPECT_HAS(error, "WM_LABEL_SIZE=64");
}


TEST(labelLimit, aPointOrCellNumberPastTheLimitStops)
{
    const Communicator serial;
    EXPECT_HAS(test::errorOf([&]
    {
        checkGlobalNumbersFitLabel(serial, addressingOf(102, 50, 10), 100);
    }), "101 (points)");
    EXPECT_HAS(test::errorOf([&]
    {
        checkGlobalNumbersFitLabel(serial, addressingOf(10, 102, 10), 100);
    }), "101 (cells)");
}
