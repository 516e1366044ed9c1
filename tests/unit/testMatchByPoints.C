// The matching kernel (matchByPoints.H) and the tet-face check built on it
// (tetFaceMatching.H): groups found whatever the order of items and points,
// in ascending order of their points, and every kind of misfit reported.

#include "tetFaceMatching.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <map>
#include <random>

using namespace pmsh;

namespace
{

//- The groups of forEachSamePointsGroup: sorted points -> ids, in visit order.
std::vector<std::pair<triVerts, std::vector<matchId>>> groupsOf
(
    std::size_t nPoints,
    const std::vector<triVerts>& faces
)
{
    std::vector<std::pair<triVerts, std::vector<matchId>>> groups;
    forEachSamePointsGroup
    (
        nPoints, matchId(faces.size()), [&](matchId id) { return faces[id]; },
        [&](const matchId* ids, std::size_t n)
        {
            groups.push_back({sortedPoints(faces[ids[0]]), {ids, ids + n}});
        }
    );
    return groups;
}

} // End anonymous namespace


TEST(matchByPoints, groupsAreThoseOfAMapInTheMapsOrder)
{
    // Random triangles on few points: many groups of one, two and more
    std::mt19937 random(7);
    std::uniform_int_distribution<label> pointIndex(0, 9);
    std::vector<triVerts> faces;
    while (faces.size() < 2000)
    {
        const triVerts f{pointIndex(random), pointIndex(random), pointIndex(random)};
        if (f[0] != f[1] && f[1] != f[2] && f[0] != f[2]) faces.push_back(f);
    }

    std::map<triVerts, std::vector<matchId>> expected;
    for (matchId id = 0; id < faces.size(); ++id)
    {
        expected[sortedPoints(faces[id])].push_back(id);
    }
    const auto groups = groupsOf(10, faces);
    ASSERT_EQ(groups.size(), expected.size());
    auto it = expected.begin();
    for (const auto& [points, ids] : groups)
    {
        EXPECT_EQ(points, it->first);
        EXPECT_EQ(ids, it->second);
        ++it;
    }
}


TEST(matchByPoints, edgesMatchEitherWay)
{
    const std::vector<std::array<label, 2>> edges{{3, 1}, {1, 2}, {1, 3}, {2, 1}, {0, 3}};
    std::vector<std::vector<matchId>> groups;
    forEachSamePointsGroup
    (
        4, matchId(edges.size()), [&](matchId id) { return edges[id]; },
        [&](const matchId* ids, std::size_t n) { groups.emplace_back(ids, ids + n); }
    );
    EXPECT_EQ(groups, (std::vector<std::vector<matchId>>{{4}, {1, 3}, {0, 2}}));
}


TEST(tetFaceMatching, twoTetsAndTheirSurfaceFit)
{
    // Tets (0 1 2 3) and (4 1 3 2) share face 3 of each, (1 2 3), from
    // either side
    const std::vector<tetVerts> tets{{0, 1, 2, 3}, {4, 1, 3, 2}};
    std::vector<triVerts> surface;
    for (const tetVerts& t : tets)
    {
        for (int f = 0; f < 3; ++f) surface.push_back(tetFace(t, f));
    }
    const tetFaceMatch m = matchTetFaces(5, tets, surface);
    EXPECT_TRUE(m.fits()) << m.problems;
    EXPECT_EQ(m.across[3], faceId(4 + 3));
    EXPECT_EQ(m.across[4 + 3], faceId(3));
    EXPECT_EQ(m.across[4 + 1], faceId(8 + 4));  // face 1 of tet 1: triangle 4

    // Each misfit, named with its count
    auto problemsWith = [&](std::vector<triVerts> s)
    {
        return matchTetFaces(5, tets, s).problems;
    };
    std::vector<triVerts> s = surface;
    s.pop_back();
    EXPECT_NE(problemsWith(s).find("1 tet faces are on no other tet"), std::string::npos);
    s = surface;
    std::swap(s[0][1], s[0][2]);
    EXPECT_NE(problemsWith(s).find("1 boundary surface triangles are not oriented outward"), std::string::npos);
    s = surface;
    s.push_back({1, 2, 3});
    EXPECT_NE(problemsWith(s).find("1 boundary surface triangles lie on a face between two tets"), std::string::npos);
    s = surface;
    s.push_back({0, 1, 4});
    EXPECT_NE(problemsWith(s).find("1 boundary surface triangles are not a tet face"), std::string::npos);
    s = surface;
    s.push_back(surface[0]);
    EXPECT_NE(problemsWith(s).find("1 faces are shared by more than two tets"), std::string::npos);
}


TEST(tetFaceMatching, fittingFacesSayWhatIsAcrossElseThrowTheMismatchAndItsProblems)
{
    const std::vector<tetVerts> tets{{0, 1, 2, 3}, {4, 1, 3, 2}};
    std::vector<triVerts> surface;
    for (const tetVerts& t : tets)
    {
        for (int f = 0; f < 3; ++f) surface.push_back(tetFace(t, f));
    }
    const tetFaceMatch m = fittingTetFaces(5, tets, surface, "unused", "here");
    EXPECT_EQ(m.nTetFaces, faceId(8));
    EXPECT_EQ(m.acrossOf(3), 1);                    // face 3 of tet 0: tet 1
    EXPECT_EQ(m.acrossOf(4 + 3), 0);
    EXPECT_EQ(m.acrossOf(4 + 1), acrossBoundary(4));  // face 1 of tet 1: triangle 4
    EXPECT_TRUE(isAcrossBoundary(m.acrossOf(0)));
    EXPECT_EQ(boundaryAcross(m.acrossOf(0)), 0);

    surface.pop_back();
    EXPECT_FATAL
    (
        fittingTetFaces(5, tets, surface, "The test mesh does not fit", "here"),
        "The test mesh does not fit:\n    1 tet faces are on no other tet"
    );
}

