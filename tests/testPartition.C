// Stage 2: METIS partition and its repair into parts with closed, manifold
// surfaces, which the volume mesher needs.

#include "partitionCoarseMesh.H"
#include "partitionSurface.H"
#include "cubeMesh.H"
#include "surfaceChecks.H"
#include "error.H"

#include <gtest/gtest.h>

#include <set>

using namespace pmsh;

TEST(partition, everyPartIsNonEmptyWithAClosedManifoldSurface)
{
    const CoarseMesh m = test::cubeMesh(6);
    for (label nParts : {2, 3, 4, 7, 16})
    {
        const std::vector<label> part = partitionCells(m, nParts);
        ASSERT_EQ(part.size(), m.tets.size());
        std::vector<int> size(nParts, 0);
        for (label p : part)
        {
            ASSERT_GE(p, 0);
            ASSERT_LT(p, nParts);
            ++size[p];
        }
        for (label p = 0; p < nParts; ++p)
        {
            EXPECT_GT(size[p], 0) << nParts << " parts";
            EXPECT_TRUE(test::closedManifold(partitionSurface(m, part, p).faces))
                << "part " << p << " of " << nParts;
        }
        EXPECT_EQ(countNonManifoldParts(m, part), 0) << nParts << " parts";
    }
}


TEST(partition, repairTurnsACheckerboardIntoManifoldParts)
{
    // Alternating cubes touch each other only along edges and at corners
    const int n = 4;
    const CoarseMesh m = test::cubeMesh(n);
    std::vector<label> part(m.tets.size());
    for (std::size_t c = 0; c < part.size(); ++c)
    {
        const int cube = int(c/6);
        const int i = cube % n, j = (cube/n) % n, k = cube/(n*n);
        part[c] = (i + j + k) % 2;
    }
    ASSERT_GT(countNonManifoldParts(m, part), 0);

    const label moved = repairPartition(m, 2, part);
    EXPECT_GT(moved, 0);
    EXPECT_EQ(countNonManifoldParts(m, part), 0);
    for (label p : {0, 1})
    {
        EXPECT_TRUE(test::closedManifold(partitionSurface(m, part, p).faces)) << "part " << p;
    }
}


TEST(partition, repairGivesEveryEmptyPartACell)
{
    const CoarseMesh m = test::cubeMesh(2);
    std::vector<label> part(m.tets.size(), 0);
    repairPartition(m, 3, part);
    std::set<label> used(part.begin(), part.end());
    EXPECT_EQ(used.size(), 3u);
    EXPECT_EQ(countNonManifoldParts(m, part), 0);
}


TEST(partition, isTheSameOnEveryCall)
{
    const CoarseMesh m = test::cubeMesh(5);
    EXPECT_EQ(partitionCells(m, 4), partitionCells(m, 4));
}


TEST(partition, moreRanksThanCoarseCellsIsAFatalErrorSayingWhatToDo)
{
    const CoarseMesh m = test::cubeMesh(1);    // 6 cells
    try
    {
        partitionCells(m, 7);
        FAIL() << "expected FatalError";
    }
    catch (const FatalError& e)
    {
        EXPECT_NE(std::string(e.what()).find("6 cells into 7 parts"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("maxCellSize"), std::string::npos);
    }
}
