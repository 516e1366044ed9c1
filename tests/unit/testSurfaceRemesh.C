// The coarse surface remeshed from the triangles (coarseSurface remesh):
// closed, every point on its face's surface, each patch at its own size,
// the box's corners kept; and a thin plate, whose two sides cross when
// remeshed coarser than its thickness, comes out without crossings.

#include "Geometry.H"
#include "stlGeometry.H"
#include "domainBox.H"
#include "testMeshers.H"
#include "testUtilities.H"
#include "surfaceRemesh.H"
#include "triangleCrossings.H"
#include "geometryTests.H"
#include "surfaceChecks.H"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>

using namespace pmsh;
using namespace pmsh::test;

namespace
{

//- Mean edge length of the boundary faces of patch `name`.
double meanEdge(const CoarseMesh& m, const std::string& name)
{
    double sum = 0;
    label n = 0;
    for (const coarseBoundaryFace& f : m.boundary)
    {
        if (m.patches[f.patch].name != name) continue;
        for (int k = 0; k < 3; ++k)
        {
            sum += std::sqrt(magSqr(m.points[f.v[k]] - m.points[f.v[(k + 1) % 3]]));
            ++n;
        }
    }
    return n ? sum/n : 0;
}


std::vector<triVerts> triangles(const CoarseMesh& m)
{
    std::vector<triVerts> t;
    for (const coarseBoundaryFace& f : m.boundary) t.push_back(f.v);
    return t;
}

//- Largest angle of each boundary triangle of patch `name`, in degrees.
std::vector<double> largestAngles(const CoarseMesh& m, const std::string& name)
{
    std::vector<double> angles;
    for (const coarseBoundaryFace& f : m.boundary)
    {
        if (m.patches[f.patch].name != name) continue;
        double largest = 0;
        for (int k = 0; k < 3; ++k)
        {
            const vector3 u = m.points[f.v[(k + 1) % 3]] - m.points[f.v[k]];
            const vector3 v = m.points[f.v[(k + 2) % 3]] - m.points[f.v[k]];
            largest = std::max
            (
                largest,
                std::atan2(std::sqrt(magSqr(cross(u, v))), dot(u, v))*180/M_PI
            );
        }
        angles.push_back(largest);
    }
    return angles;
}

} // End anonymous namespace


TEST(surfaceRemesh, aSphereInABoxIsRemeshedClosedOnItsSurfacesAtEachPatchsSize)
{
    auto g = Geometry::New(dataDir + "sphereInBox.stl");
    coarseMeshParameters p(2.0);
    p.coarseSurface = "remesh";
    p.patchMaxCellSize = [](const std::string& patch) { return patch == "body" ? 0.25 : 0.0; };
    ASSERT_TRUE(g->remeshesCoarseSurface(p.coarseSurface));
    const CoarseMesh m = g->coarseSurface(p);

    EXPECT_TRUE(m.tets.empty());
    EXPECT_TRUE(closedAndConsistent(triangles(m)));
    EXPECT_EQ(patchNames(m), (std::vector<std::string>{"inlet", "outlet", "sides", "body"}));

    // Every point on its face's surface: the box's sides stay flat and
    // its corners sharp, the ball's points on its facets
    for (const coarseBoundaryFace& f : m.boundary)
    {
        for (const label v : f.v)
        {
            const point3 q = g->projectToSurface(m.points[v], f.surface);
            EXPECT_LT(std::sqrt(magSqr(q - m.points[v])), 1e-9);
        }
    }
    for (const point3& corner : {point3{-5, -5, -5}, point3{5, 5, 5}, point3{-5, 5, -5}})
    {
        const bool kept = std::any_of
        (
            m.points.begin(), m.points.end(),
            [&](const point3& x) { return magSqr(x - corner) < 1e-20; }
        );
        EXPECT_TRUE(kept);
    }

    // Each patch at its size (isotropic remeshing keeps edges within
    // 4/5 and 4/3 of the target)
    EXPECT_NEAR(meanEdge(m, "body"), 0.25, 0.25*0.3);
    EXPECT_NEAR(meanEdge(m, "sides"), 2.0, 2.0*0.3);

    const std::vector<label> crossed = crossingTriangles
    (
        m.points, triangles(m), std::vector<bool>(m.boundary.size(), true)
    );
    EXPECT_EQ(std::count(crossed.begin(), crossed.end(), 0), label(crossed.size()));
}


namespace
{

//- The sphereInBox's coarse surface remeshed with a refinement box through
//  its sides that halves their size where it reaches them: a border of
//  sizes within each side, no edge of the geometry
CoarseMesh sidesWithASizeBorder()
{
    auto g = Geometry::New(dataDir + "sphereInBox.stl");
    coarseMeshParameters p(2.0);
    p.coarseSurface = "remesh";
    sizeRegion wake;
    wake.name = "wake";
    wake.min = {-1.3, -1.1, -5.5};
    wake.max = {5.5, 2.3, 1.9};
    wake.size = 0.35;
    p.regions.push_back(wake);
    return g->coarseSurface(p);
}


//- visit(angle, angleAcross) for each edge between two coplanar triangles
//  of one patch, once from each side: the angle opposite the edge in the
//  triangle on this side and in the one across, in degrees
template<class Visit>
void forEachFlatEdgeWithinAPatch(const CoarseMesh& m, const Visit& visit)
{
    std::map<std::pair<label, label>, label> faceOfEdge;
    for (std::size_t f = 0; f < m.boundary.size(); ++f)
    {
        const triVerts& v = m.boundary[f].v;
        for (int k = 0; k < 3; ++k)
        {
            faceOfEdge[{v[k], v[(k + 1) % 3]}] = label(f);
        }
    }
    const auto angleAt = [&](const label c, const label a, const label b)
    {
        const vector3 u = m.points[a] - m.points[c];
        const vector3 w = m.points[b] - m.points[c];
        return std::acos(dot(u, w)/std::sqrt(magSqr(u)*magSqr(w)))*180/M_PI;
    };
    for (std::size_t f = 0; f < m.boundary.size(); ++f)
    {
        const triVerts& v = m.boundary[f].v;
        for (int k = 0; k < 3; ++k)
        {
            const label c = v[k], a = v[(k + 1) % 3], b = v[(k + 2) % 3];
            const label across = faceOfEdge.at({b, a});
            const triVerts& w = m.boundary[across].v;
            const label d = w[0] != a && w[0] != b ? w[0] : w[1] != a && w[1] != b ? w[1] : w[2];
            const vector3 n = cross(m.points[a] - m.points[c], m.points[b] - m.points[c]);
            const vector3 o = cross(m.points[w[1]] - m.points[w[0]], m.points[w[2]] - m.points[w[0]]);
            const bool flat = dot(n, o) > 0.999*std::sqrt(magSqr(n)*magSqr(o));
            if (m.boundary[across].patch == m.boundary[f].patch && flat)
            {
                visit(angleAt(c, a, b), angleAt(d, b, a));
            }
        }
    }
}

} // End anonymous namespace


TEST(surfaceRemesh, theBorderOfARefinementRegionLeavesNoCapAbove170DegreesOnAFlatSide)
{
    // The remeshing leaves caps along a border of sizes (OpenFOAM's
    // motorBike: 177 degrees on its floor at the refinement box's border,
    // whose tets made potentialFoam's velocity 1e7). Flips across it
    // leave none above 170 degrees (179 without them): a cap whose flip
    // would not make its pair better stays.
    const CoarseMesh m = sidesWithASizeBorder();
    EXPECT_TRUE(closedAndConsistent(triangles(m)));
    double largest = 0;
    forEachFlatEdgeWithinAPatch(m, [&](const double angle, double)
    {
        largest = std::max(largest, angle);
    });
    EXPECT_LT(largest, 170);
}


TEST(surfaceRemesh, theFlatSidesAreDelaunayAcrossABorderOfSizes)
{
    // Along the border the remesher also leaves obtuse pairs, whose prism
    // layers' side faces are as far from orthogonal (OpenFOAM's motorBike
    // with a layer on its floor: 155 faces above 70 degrees). On the box's
    // flat sides every edge within a patch is Delaunay: the angles
    // opposite it add up to at most 180 degrees (and the flips' tolerance)
    const CoarseMesh m = sidesWithASizeBorder();
    EXPECT_TRUE(closedAndConsistent(triangles(m)));
    double largestSum = 0;
    forEachFlatEdgeWithinAPatch(m, [&](const double angle, const double angleAcross)
    {
        largestSum = std::max(largestSum, angle + angleAcross);
    });
    EXPECT_LE(largestSum, 180.06);
}


TEST(surfaceRemesh, aCsgGeometryHasNoTrianglesToRemesh)
{
    auto g = Geometry::New(dataDir + "sphere.geo");
    coarseMeshParameters p(0.5);
    p.coarseSurface = "remesh";
    EXPECT_NE(errorOf([&] { g->coarseSurface(p); }).find("for surface files"), std::string::npos);
}


TEST(surfaceRemesh, aThinShellIsRefinedWhereItsSidesWouldCross)
{
    // A hollow ball 0.02 thick: at size 0.5 the chords of its outer side
    // sag by 0.03 (h^2/8R), through its inner side
    const closedSurface fine = icosphere(5);
    stlSurface s;
    s.solidNames = {"shell"};
    const label n = label(fine.points.size());
    for (const double r : {1.0, 0.98})
    {
        for (const point3& x : fine.points) s.points.push_back(r*x);
    }
    std::vector<label> region;
    for (const triVerts& t : fine.triangles)
    {
        s.triangles.push_back(t);
        region.push_back(0);
    }
    for (const triVerts& t : fine.triangles)
    {
        // The inner side faces the hollow
        s.triangles.push_back({t[0] + n, t[2] + n, t[1] + n});
        region.push_back(1);
    }
    s.solid.assign(s.triangles.size(), 0);

    std::vector<boxTree::entry> entries;
    for (label t = 0; t < s.nTriangles(); ++t) entries.push_back(triangleEntry(s, t));
    const remeshedTriangulation r = remeshSurface
    (
        s, boxTree(std::move(entries)), region, {},
        std::vector<double>(s.nTriangles(), 0.5), 0, 0, "the hollow ball"
    );
    EXPECT_GT(r.nRefined, 0);
    EXPECT_GT(r.nRounds, 1);
    EXPECT_TRUE(closedAndConsistent(r.triangles));
    const std::vector<label> crossed = crossingTriangles
    (
        r.points, r.triangles, std::vector<bool>(r.triangles.size(), true)
    );
    EXPECT_EQ(std::count(crossed.begin(), crossed.end(), 0), label(crossed.size()));

    // Away from the crossings the size stays: far fewer triangles than
    // the input's
    EXPECT_LT(r.triangles.size(), s.triangles.size()/4);
}


// OpenFOAM's motorBike (Debian's openfoam-examples, which the project's
// set-up installs) wrapped in its tutorial's box, on plinths, with its
// tutorial's refinementBox (0.0625 fine): on the floor, CGAL 5.5's
// remesher flipped an edge on the border of the size it remeshed, by a
// face of exactly collinear points, and threw "map::at" (surfaceRemesh.C,
// remeshAtSize). That size is remeshed again with its border held: the
// coarse surface is closed and keeps every side and the bike. And the
// floor is graded from the box's border (0.125 inside, 1 outside), with
// no triangle of more than 140 degrees along it.
TEST(surfaceRemesh, theMotorBikesFloorIsRemeshedAtItsTutorialsRefinementBox)
{
    const std::string obj =
        "/usr/share/doc/openfoam-examples/examples/resources/geometry/motorBike.obj.gz";
    ASSERT_TRUE(std::ifstream(obj).good()) << obj << " (Debian's openfoam-examples)";
    domainBox box;
    box.given = true;
    box.min = {-5, -4, 0};
    box.max = {15, 4, 8};
    box.sideNames = {"inlet", "outlet", "frontAndBack", "frontAndBack", "lowerWall", "upperWall"};
    box.wrapSize = 0.03125;
    box.wrapOffset = 0.03125/2;
    box.plinthHeight = 0.03;
    auto g = Geometry::New({obj}, box);

    coarseMeshParameters p(1.0);
    p.coarseSurface = "remesh";
    p.curvatureRefinement = 3;
    p.minCellSize = 1.0/8;
    p.patchMaxCellSize = [](const std::string& patch)
    {
        return patch.find('%') != std::string::npos ? 0.0625 : 0.0;
    };
    sizeRegion refinementBox;
    refinementBox.name = "refinementBox";
    refinementBox.min = {-1, -0.7, 0};
    refinementBox.max = {8, 0.7, 2.5};
    refinementBox.size = 0.125;
    p.regions.push_back(refinementBox);
    const CoarseMesh m = g->coarseSurface(p);

    EXPECT_TRUE(closedAndConsistent(triangles(m)));
    const std::vector<std::string> names = patchNames(m);
    for (const std::string side : {"inlet", "outlet", "frontAndBack", "lowerWall", "upperWall"})
    {
        EXPECT_NE(std::find(names.begin(), names.end(), side), names.end()) << side;
    }
    EXPECT_GT(std::count_if(names.begin(), names.end(), [](const std::string& n)
    {
        return n.find('%') != std::string::npos;
    }), 20);

    // The floor graded from the box's border (gradeSizeBorders): before,
    // 48 of its triangles had an angle above 140 degrees along it, and the
    // side faces of the floor's prisms on them reached 86 degrees from
    // orthogonal
    const std::vector<double> floor = largestAngles(m, "lowerWall");
    EXPECT_GT(floor.size(), 1000u);
    EXPECT_EQ(std::count_if(floor.begin(), floor.end(), [](double a) { return a > 140; }), 0);
}
