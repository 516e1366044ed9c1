// Dirty CAD wrapped (CGAL's alpha wrap): an open box, two overlapping
// cubes and two cubes sharing an edge each fail the surface checks as
// they are and pass them wrapped, keeping their patches; a clean body is
// left as it is unless the wrap is asked for.

#include "domainBox.H"
#include "surfaceBuilder.H"
#include "surfaceWrap.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <set>

using namespace pmsh;
using namespace pmsh::test;

namespace
{

//- Outward triangles of the box [lo, hi], all in solid `name`, but for
//  the sides listed in `open` (0..5: xMin, xMax, yMin, yMax, zMin, zMax).
void addBox
(
    stlSurface& s,
    const point3& lo,
    const point3& hi,
    const std::string& name,
    const std::set<int>& open = {}
)
{
    surfaceBuilder builder(s, name);
    const label solid = builder.addSolid(name);
    const auto corner = [&](int i, int j, int k)
    {
        return point3{(i ? hi : lo)[0], (j ? hi : lo)[1], (k ? hi : lo)[2]};
    };
    const int quads[6][4][3]
    {
        {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}},
        {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
        {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},
        {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
        {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}},
        {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}
    };
    for (int side = 0; side < 6; ++side)
    {
        if (open.count(side)) continue;
        point3 c[4];
        for (int i = 0; i < 4; ++i)
        {
            c[i] = corner(quads[side][i][0], quads[side][i][1], quads[side][i][2]);
        }
        builder.addTriangle(c[0], c[1], c[2], solid);
        builder.addTriangle(c[0], c[2], c[3], solid);
    }
}

//- The solid of the wrap triangle nearest p.
std::string solidNear(const stlSurface& s, const point3& p)
{
    label best = -1;
    double d2 = 1e300;
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        const double d = magSqr(s.centroid(t) - p);
        if (d < d2)
        {
            d2 = d;
            best = t;
        }
    }
    return s.solidNames[s.solid[best]];
}

//- The wrap must be what pmshFoam can mesh: closed, manifold, oriented
//  consistently and outward, no shells crossing or touching; and close
//  to the input: within the offset, or `bridged` where it closes
//  concave corners.
void expectMeshable
(
    const stlSurface& wrapped,
    const surfaceWrapReport& report,
    double offset,
    double bridged = 0
)
{
    EXPECT_NO_THROW(checkStl(wrapped, "the wrap"));
    EXPECT_GT(enclosedVolume(wrapped), 0);
    EXPECT_TRUE(report.wrapped);
    EXPECT_EQ(report.nTriangles, wrapped.nTriangles());
    EXPECT_GE(report.maxDistance, 0.99*offset);
    EXPECT_LE(report.maxDistance, std::max(1.01*offset, bridged));
}

//- The unit cube (solid a) and box b, which the surface check refuses
//  (`defect`), wrapped at 0.1 into one meshable body.
stlSurface twoBoxesWrapped(const point3& bLo, const point3& bHi, const char* defect)
{
    stlSurface s;
    addBox(s, {0, 0, 0}, {1, 1, 1}, "a");
    addBox(s, bLo, bHi, "b");
    EXPECT_FATAL(checkStlTopology(s, "two.stl"), defect);

    surfaceWrapReport report;
    const stlSurface wrapped = wrapSurface(s, 0.1, 0.005, report);
    expectMeshable(wrapped, report, 0.005, 0.1);   // bridging where they meet
    EXPECT_EQ(nestShells(wrapped).triangles.size(), 1u) << "one body";
    return wrapped;
}

//- A domain box round the unit cube, wrapping at 0.1 (offset 0.005).
domainBox boxRoundTheUnitCube()
{
    domainBox box;
    box.given = true;
    box.min = {-1, -1, -1};
    box.max = {2, 2, 2};
    box.wrapSize = 0.1;
    box.wrapOffset = 0.005;
    return box;
}

} // End anonymous namespace


TEST(surfaceWrap, anOpenBoxBecomesAClosedManifoldBodyWithItsPatch)
{
    stlSurface s;
    addBox(s, {0, 0, 0}, {1, 1, 1}, "body", {5});
    EXPECT_FATAL(checkStlTopology(s, "open.stl"), "is not closed: 4 edge(s)");

    surfaceWrapReport report;
    const stlSurface wrapped = wrapSurface(s, 0.1, 0.005, report);
    expectMeshable(wrapped, report, 0.005, 0.1);     // its inner corners
    EXPECT_EQ(wrapped.solidNames, std::vector<std::string>{"body"});
    EXPECT_EQ(report.nInputTriangles, 10);
}


TEST(surfaceWrap, twoOverlappingCubesBecomeOneShellKeepingEachOnesPatch)
{
    const stlSurface wrapped =
        twoBoxesWrapped({0.5, 0.5, 0.5}, {1.5, 1.5, 1.5}, "touch or overlap");
    // The union's volume, grown by the offset over its area (10.5)
    EXPECT_NEAR(enclosedVolume(wrapped), 1.875 + 10.5*0.005, 0.02);
    EXPECT_EQ(solidNear(wrapped, {0, 0.25, 0.25}), "a");
    EXPECT_EQ(solidNear(wrapped, {1.5, 1.25, 1.25}), "b");
}


TEST(surfaceWrap, cubesSharingAnEdgeAreNotManifoldUntilWrapped)
{
    twoBoxesWrapped({1, 1, 0}, {2, 2, 1}, "is not manifold");
}


TEST(domainBox, aCleanBodyIsWrappedOnlyWhenAsked)
{
    stlSurface clean;
    addBox(clean, {0, 0, 0}, {1, 1, 1}, "body");
    domainBox box = boxRoundTheUnitCube();

    stlSurface s = clean;
    EXPECT_FALSE(wrapBodies(s, box, "body.stl").wrapped) << "wrap auto";
    EXPECT_EQ(s.triangles, clean.triangles);

    box.wrap = "on";
    const surfaceWrapReport report = wrapBodies(s, box, "body.stl");
    EXPECT_TRUE(report.wrapped);
    EXPECT_EQ(report.reason, "wrap on in 'domain'");
    EXPECT_GT(s.nTriangles(), clean.nTriangles());
}


TEST(domainBox, anOpenBodyIsWrappedSayingWhyUnlessWrapIsOff)
{
    stlSurface open;
    addBox(open, {0, 0, 0}, {1, 1, 1}, "body", {0});
    domainBox box = boxRoundTheUnitCube();

    box.wrap = "off";
    stlSurface s = open;
    EXPECT_FALSE(wrapBodies(s, box, "body.stl").wrapped);
    EXPECT_EQ(s.triangles, open.triangles);
    EXPECT_FATAL(checkStlTopology(s, "body.stl"), "body.stl is not closed");

    box.wrap = "auto";
    s = open;
    const surfaceWrapReport report = wrapBodies(s, box, "body.stl");
    EXPECT_TRUE(report.wrapped);
    EXPECT_NE(report.reason.find("body.stl is not closed"), std::string::npos) << report.reason;
    EXPECT_NO_THROW(putBodiesInDomain(s, box, "body.stl"));
    EXPECT_NO_THROW(checkStl(s, "body.stl"));
}


TEST(surfaceWrap, patchIslandsOfAFewTrianglesJoinTheirNeighbourLargeOnesStay)
{
    stlSurface s;
    addBox(s, {0, 0, 0}, {1, 1, 1}, "a");
    surfaceWrapReport report;
    stlSurface wrapped = wrapSurface(s, 0.1, 0.005, report);
    EXPECT_EQ(report.nTidied, 0) << "one patch: nothing to tidy";

    // Half the wrap (x > 0.5) is patch b, and one triangle in each half
    // takes the other's patch: a spike of one triangle
    wrapped.solidNames.push_back("b");
    label inA = -1, inB = -1;
    for (label t = 0; t < wrapped.nTriangles(); ++t)
    {
        const bool b = wrapped.centroid(t)[0] > 0.5;
        wrapped.solid[t] = b ? 1 : 0;
        if (!b && wrapped.centroid(t)[0] < 0.1 && inA < 0) inA = t;
        if (b && wrapped.centroid(t)[0] > 0.9 && inB < 0) inB = t;
    }
    ASSERT_GE(inA, 0);
    ASSERT_GE(inB, 0);
    const std::vector<label> halves = wrapped.solid;
    wrapped.solid[inA] = 1;
    wrapped.solid[inB] = 0;

    const label moved = tidyWrapPatches(wrapped, smallestPatchIsland);
    EXPECT_GE(moved, 2);
    EXPECT_EQ(wrapped.solid[inA], 0);
    EXPECT_EQ(wrapped.solid[inB], 1);
    // The halves stay, but for their ragged border
    label differ = 0;
    for (label t = 0; t < wrapped.nTriangles(); ++t)
    {
        differ += wrapped.solid[t] != halves[t];
    }
    EXPECT_LT(differ, wrapped.nTriangles()/20);
}
