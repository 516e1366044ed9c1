// Barycentric global ids (PMSH paper, section 3): the Fig. 4 table, the
// owner rule and the 12-byte packing.

#include "barycentricId.H"
#include "pmshError.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <sstream>

using namespace pmsh;

namespace
{

std::string str(const barycentricId& id)
{
    std::ostringstream os;
    os << id;
    return os.str();
}

} // End anonymous namespace


TEST(barycentricId, reproducesFigureFourOfThePaper)
{
    // Face (3, 5, 8), r = 2: coefficients sum to 4
    EXPECT_EQ(str(barycentricId(3, 4, 5, 0, 8, 0)), "[(0,0),(0,0),(3,4)]");
    EXPECT_EQ(str(barycentricId(3, 0, 5, 4, 8, 0)), "[(0,0),(0,0),(5,4)]");
    EXPECT_EQ(str(barycentricId(3, 0, 5, 0, 8, 4)), "[(0,0),(0,0),(8,4)]");
    EXPECT_EQ(str(barycentricId(3, 1, 5, 2, 8, 1)), "[(3,1),(5,2),(8,1)]");  // a
    EXPECT_EQ(str(barycentricId(3, 3, 5, 1, 8, 0)), "[(0,0),(3,3),(5,1)]");  // b
    EXPECT_EQ(str(barycentricId(3, 2, 5, 1, 8, 1)), "[(3,2),(5,1),(8,1)]");  // c
    EXPECT_EQ(str(barycentricId(3, 0, 5, 1, 8, 3)), "[(0,0),(5,1),(8,3)]");  // d
}


TEST(barycentricId, doesNotDependOnTheOrderOfThePairs)
{
    const barycentricId a(3, 1, 5, 2, 8, 1);
    EXPECT_EQ(a, barycentricId(8, 1, 3, 1, 5, 2));
    EXPECT_EQ(a, barycentricId(5, 2, 8, 1, 3, 1));
}


TEST(barycentricId, edgeVertexIsTheSameFromBothFacesOfTheEdge)
{
    // Edge 3-5 shared by faces (3, 5, 8) and (3, 5, 11): weight 0 on 8 / 11
    EXPECT_EQ(barycentricId(3, 3, 5, 1, 8, 0), barycentricId(11, 0, 5, 1, 3, 3));
    EXPECT_EQ(barycentricId(3, 3, 5, 1, 8, 0).nNonZero(), 2);
    EXPECT_EQ(barycentricId(3, 4, 5, 0, 8, 0), barycentricId(3, 4, 9, 0, 12, 0));
}


TEST(barycentricId, ownerRuleIndexesTheSortedHolderList)
{
    // a = [(3,1),(5,2),(8,1)]: sum 20
    const barycentricId a(3, 1, 5, 2, 8, 1);
    EXPECT_EQ(a.ownerSum(), 20u);
    EXPECT_EQ(ownerRank(a, {4, 7}), 4);         // 20 mod 2 = 0
    EXPECT_EQ(ownerRank(a, {1, 2, 6}), 6);      // 20 mod 3 = 2
    EXPECT_EQ(ownerRank(a, {0, 3, 5, 9}), 0);   // 20 mod 4 = 0
    EXPECT_EQ(ownerRank(a, {5}), 5);
    // b = [(0,0),(3,3),(5,1)]: sum 12
    EXPECT_EQ(ownerRank(barycentricId(3, 3, 5, 1, 8, 0), {2, 3, 4, 5, 7}), 4);
    EXPECT_THROW(ownerRank(a, {}), FatalError);
}


TEST(barycentricId, packsIntoTwelveBytesLosslesslyAndInOrder)
{
    const int r = 3;
    ASSERT_TRUE(barycentricId::packable(1000000, r));
    std::mt19937 gen(7);
    std::uniform_int_distribution<std::uint32_t> vertex(1, 1000000);
    std::uniform_int_distribution<std::uint32_t> weight(0, 8);

    std::vector<barycentricId> ids;
    for (int n = 0; n < 2000; ++n)
    {
        const std::uint32_t a = weight(gen);
        const std::uint32_t b = std::min(8 - a, weight(gen));
        ids.emplace_back(vertex(gen), a, vertex(gen), b, vertex(gen), 8 - a - b);
    }
    for (const barycentricId& id : ids)
    {
        EXPECT_EQ(barycentricId::unpack(id.pack(r), r), id);
    }
    for (std::size_t n = 1; n < ids.size(); ++n)
    {
        EXPECT_EQ(ids[n - 1] < ids[n], ids[n - 1].pack(r) < ids[n].pack(r));
    }
}


TEST(barycentricId, packableOnlyWhenVertexAndWeightFitThirtyTwoBits)
{
    // r = 5: 6 weight bits leave 26 bits for vertex ids
    EXPECT_TRUE(barycentricId::packable((1u << 26) - 1, 5));
    EXPECT_FALSE(barycentricId::packable(1u << 26, 5));
    EXPECT_FALSE(barycentricId::packable(10, 31));
}
