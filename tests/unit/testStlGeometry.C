// Geometry from STL: the reader (ascii and binary, solids, shells and every
// input error), coarse meshes through Netgen, patches and regions,
// projection onto the facets, and the curvature and gap sizes.

#include "geometryTests.H"
#include "boxTree.H"
#include "surfaceTopology.H"
#include "coarseMeshGeneration.H"
#include "csgGeometry.H"
#include "domainBox.H"
#include "stlGeometry.H"
#include "stlReader.H"
#include "surfaceFiles.H"
#include "partitionVolume.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <sstream>

using namespace pmsh;
using namespace pmsh::test;

namespace
{


double distanceToTriangle(const stlSurface& s, label t, const point3& p)
{
    // Brute force: sample-free exact distance by projecting onto the plane
    // and clamping through the three edges
    const point3& a = s.points[s.triangles[t][0]];
    const point3& b = s.points[s.triangles[t][1]];
    const point3& c = s.points[s.triangles[t][2]];
    const vector3 n = cross(b - a, c - a);
    const double nn = magSqr(n);
    const point3 q = p - (dot(p - a, n)/nn)*n;
    auto inside = [&](const point3& x)
    {
        return dot(cross(b - a, x - a), n) >= 0
            && dot(cross(c - b, x - b), n) >= 0
            && dot(cross(a - c, x - c), n) >= 0;
    };
    if (inside(q))
    {
        return std::sqrt(magSqr(p - q));
    }
    auto seg = [&](const point3& u, const point3& v)
    {
        const double l2 = magSqr(v - u);
        double tt = dot(p - u, v - u)/l2;
        tt = std::min(1.0, std::max(0.0, tt));
        return std::sqrt(magSqr(p - (u + tt*(v - u))));
    };
    return std::min({seg(a, b), seg(b, c), seg(c, a)});
}


double distanceToStl(const stlSurface& s, const point3& p)
{
    double d = 1e300;
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        d = std::min(d, distanceToTriangle(s, t, p));
    }
    return d;
}



// A small closed box as ascii STL text, for the broken variants:
// unit cube, 12 triangles, outward
struct boxStl
{
    std::vector<point3> p
    {
        {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}
    };
    std::vector<triVerts> t
    {
        {0, 2, 1}, {0, 3, 2},   // z = 0
        {4, 5, 6}, {4, 6, 7},   // z = 1
        {0, 1, 5}, {0, 5, 4},   // y = 0
        {3, 7, 6}, {3, 6, 2},   // y = 1
        {0, 4, 7}, {0, 7, 3},   // x = 0
        {1, 2, 6}, {1, 6, 5}    // x = 1
    };

    std::string ascii(const std::string& name = "box") const
    {
        std::ostringstream os;
        os.precision(17);
        os  << "solid " << name << "\n";
        for (const triVerts& f : t)
        {
            os  << " facet normal 0 0 0\n  outer loop\n";
            for (label v : f)
            {
                os  << "   vertex " << p[v][0] << ' ' << p[v][1] << ' ' << p[v][2] << "\n";
            }
            os  << "  endloop\n endfacet\n";
        }
        os  << "endsolid " << name << "\n";
        return os.str();
    }

    std::string binary(const std::string& header = "binary box") const
    {
        std::string s(80, ' ');
        std::copy(header.begin(), header.end(), s.begin());
        const std::uint32_t n = std::uint32_t(t.size());
        s.append(reinterpret_cast<const char*>(&n), 4);
        for (const triVerts& f : t)
        {
            float rec[12] = {0, 0, 0};
            for (int k = 0; k < 3; ++k)
            {
                for (int j = 0; j < 3; ++j)
                {
                    rec[3 + 3*k + j] = float(p[f[k]][j]);
                }
            }
            s.append(reinterpret_cast<const char*>(rec), sizeof(rec));
            s.append(2, '\0');
        }
        return s;
    }
};

//- The unit cube, every side split n x n into 2 n^2 outward triangles, as
//  ascii STL with two solids: "inlet" (the cells of side x = 0 whose
//  centre lies in the square [lo, hi]^2) and "walls" (the rest).
std::string cubeWithInlet(int n, double lo, double hi)
{
    std::vector<std::pair<bool, std::array<point3, 3>>> tris;
    auto side = [&](const point3& o, const vector3& du, const vector3& dv, bool x0)
    {
        for (int i = 0; i < n; ++i)
        {
            for (int j = 0; j < n; ++j)
            {
                auto P = [&](int a, int b)
                {
                    return o + (double(a)/n)*du + (double(b)/n)*dv;
                };
                const point3 centre = o + (0.5/n)*((2*i + 1)*du + (2*j + 1)*dv);
                const bool inlet = x0
                    && centre[1] > lo && centre[1] < hi
                    && centre[2] > lo && centre[2] < hi;
                tris.push_back({inlet, {P(i, j), P(i + 1, j), P(i + 1, j + 1)}});
                tris.push_back({inlet, {P(i, j), P(i + 1, j + 1), P(i, j + 1)}});
            }
        }
    };
    // du x dv outward
    side({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, true);
    side({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, false);
    side({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, false);
    side({0, 1, 0}, {0, 0, 1}, {1, 0, 0}, false);
    side({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, false);
    side({0, 0, 1}, {1, 0, 0}, {0, 1, 0}, false);

    std::ostringstream os;
    os.precision(17);
    for (int solid = 0; solid < 2; ++solid)
    {
        const std::string name = solid ? "walls" : "inlet";
        os  << "solid " << name << "\n";
        for (const auto& t : tris)
        {
            if (t.first != (solid == 0)) continue;
            os  << "facet normal 0 0 0\nouter loop\n";
            for (const point3& p : t.second)
            {
                os  << "vertex " << p[0] << ' ' << p[1] << ' ' << p[2] << "\n";
            }
            os  << "endloop\nendfacet\n";
        }
        os  << "endsolid " << name << "\n";
    }
    return os.str();
}

} // End anonymous namespace


TEST(stlReader, asciiAndBinarySphereAreIdentical)
{
    const stlSurface a = readStl(dataDir + "sphere.stl");
    const stlSurface b = readStl(dataDir + "sphereBinary.stl");
    EXPECT_FALSE(a.binary);
    EXPECT_TRUE(b.binary);
    EXPECT_EQ(a.nTriangles(), 1280);
    EXPECT_EQ(a.points.size(), 642u);
    ASSERT_EQ(a.points.size(), b.points.size());
    ASSERT_EQ(a.triangles, b.triangles);
    for (std::size_t i = 0; i < a.points.size(); ++i)
    {
        EXPECT_TRUE(sameBits(a.points[i], b.points[i]));
    }
    EXPECT_EQ(a.solidNames, std::vector<std::string>{"sphere"});
    EXPECT_EQ(b.solidNames, std::vector<std::string>{"sphereBinary"});
    EXPECT_NO_THROW(checkStl(a, "sphere.stl"));
    EXPECT_GT(enclosedVolume(a), 4.0);
}


TEST(stlReader, binaryHeaderStartingWithSolid)
{
    const tempDir dir("geometry");
    boxStl box;
    const std::string f = dir.file("cube.stl", box.binary("solid cube exported as binary"));
    const stlSurface s = readStl(f);
    EXPECT_TRUE(s.binary);
    EXPECT_EQ(s.nTriangles(), 12);
    EXPECT_EQ(s.points.size(), 8u);
    EXPECT_EQ(s.solidNames, std::vector<std::string>{"cube"});
}


TEST(stlReader, multiSolidNames)
{
    const stlSurface s = readStl(dataDir + "box.stl");
    EXPECT_EQ(s.solidNames, (std::vector<std::string>{"inlet", "walls"}));
    EXPECT_NO_THROW(checkStl(s, "box.stl"));

    // An unnamed solid takes the file's stem; a repeated name is one patch
    const tempDir dir("geometry");
    boxStl box;
    std::string text = box.ascii("");
    const std::string f = dir.file("myPart.stl", text);
    EXPECT_EQ(readStl(f).solidNames, std::vector<std::string>{"myPart"});

    // Two solids with the same name, and a name with spaces
    std::string two = box.ascii("wall");
    const std::string f2 = dir.file("two.stl", two + two);
    const stlSurface s2 = readStl(f2);
    EXPECT_EQ(s2.solidNames, std::vector<std::string>{"wall"});
    const std::string f3 = dir.file("three.stl", box.ascii("my wall 1"));
    EXPECT_EQ(readStl(f3).solidNames, std::vector<std::string>{"mywall1"});
}


TEST(stlReader, inputErrors)
{
    const tempDir dir("geometry");
    boxStl box;

    EXPECT_FATAL(readStl(dir.file("empty.stl", "")), "is empty");
    EXPECT_FATAL(readStl(dir.file("noTriangles.stl", "solid x\nendsolid x\n")), "contains no triangles");
    EXPECT_FATAL(readStl("/nonexistent/body.stl"), "Cannot open STL file \"/nonexistent/body.stl\"");

    // Truncated binary: the header announces more triangles than there are
    std::string bin = box.binary();
    EXPECT_FATAL(readStl(dir.file("truncated.stl", bin.substr(0, bin.size() - 30))), "is truncated");
    EXPECT_FATAL(readStl(dir.file("short.stl", bin.substr(0, 40))), "84-byte");

    // Ascii syntax errors name the line
    std::string text = box.ascii();
    const std::size_t pos = text.find("vertex", text.find("vertex") + 1);
    std::string bad = text;
    bad.replace(pos, 6, "vertx");
    EXPECT_FATAL(readStl(dir.file("syntax.stl", bad)), "line 5: expected 'vertex', found 'vertx'");
    std::string badNumber = text;
    badNumber.replace(text.find("vertex 0 0 0"), 12, "vertex 0 a 0");
    EXPECT_FATAL(readStl(dir.file("number.stl", badNumber)), "expected a number, found 'a'");
}


TEST(stlReader, validationErrors)
{
    const tempDir dir("geometry");

    auto check = [&](const boxStl& b)
    {
        const std::string f = dir.file("broken.stl", b.ascii());
        checkStl(readStl(f), describeSurfaceFiles({f}));
    };

    {
        boxStl b;
        EXPECT_NO_THROW(check(b));
    }
    {
        // A hole
        boxStl b;
        b.t.pop_back();
        EXPECT_FATAL(check(b), "is not closed: 3 edge(s) are used by only one triangle, e.g. the edge (");
    }
    {
        // A third triangle on an edge: an extra fin (closed, but not manifold)
        boxStl b;
        b.p.push_back({0.5, -0.5, -0.5});
        b.t.push_back({0, 1, 8});
        b.t.push_back({1, 0, 8});
        EXPECT_FATAL(check(b), "is not manifold");
    }
    {
        // One triangle flipped
        boxStl b;
        std::swap(b.t[3][1], b.t[3][2]);
        EXPECT_FATAL(check(b), "is inconsistently oriented");
    }
    {
        // All flipped: inward
        boxStl b;
        for (auto& f : b.t) std::swap(f[1], f[2]);
        const std::string m = errorOf([&]{ check(b); });
        EXPECT_NE(m.find("is oriented inward"), std::string::npos) << m;
        EXPECT_NE(m.find("flip the normals"), std::string::npos) << m;
    }
    {
        // A zero-area triangle (three collinear points on an edge)
        boxStl b;
        b.p.push_back({0.5, 0, 0});
        b.t.push_back({0, 8, 1});
        EXPECT_FATAL(check(b), "degenerate (zero-area)");
    }
    {
        // A triangle whose vertices merge (repeated point)
        boxStl b;
        b.t.push_back({0, 0, 1});
        EXPECT_FATAL(check(b), "degenerate (zero-area)");
    }

    // Through Geometry::New the message names the file
    boxStl b;
    b.t.pop_back();
    const std::string f = dir.file("open.stl", b.ascii());
    EXPECT_FATAL(Geometry::New(f), "STL file \"" + f + "\" is not closed");
}


TEST(stlGeometry, sphereAsciiAndBinaryGiveTheSameMesh)
{
    auto a = Geometry::New(dataDir + "sphere.stl");
    auto b = Geometry::New(dataDir + "sphereBinary.stl");
    const CoarseMesh ma = a->coarseMesh({0.5, 0.3});
    const CoarseMesh mb = b->coarseMesh({0.5, 0.3});

    EXPECT_EQ(ma.nPoints(), mb.nPoints());
    EXPECT_EQ(ma.nCells(), mb.nCells());
    EXPECT_EQ(ma.boundary.size(), mb.boundary.size());
    EXPECT_EQ(patchNames(ma), std::vector<std::string>{"sphere"});
    EXPECT_EQ(patchNames(mb), std::vector<std::string>{"sphereBinary"});

    const double v = checkCoarseMesh(ma);
    EXPECT_NEAR(v, 4.0/3.0*M_PI, 0.15*4.0/3.0*M_PI);

    // One smooth region; boundary points on the STL
    const stlGeometry& sg = dynamic_cast<const stlGeometry&>(*a);
    EXPECT_EQ(sg.nRegions(), 1);
    for (const auto& f : ma.boundary)
    {
        EXPECT_EQ(f.surface, 0);
        EXPECT_EQ(f.patch, 0);
        for (label p : f.v)
        {
            point3 q;
            sg.nearestTriangle(ma.points[p], q);
            EXPECT_LT(std::sqrt(magSqr(q - ma.points[p])), 1e-9);
        }
    }
}


TEST(stlGeometry, boxPatchesAndRegions)
{
    auto g = Geometry::New(dataDir + "box.stl");
    const stlGeometry& sg = dynamic_cast<const stlGeometry&>(*g);
    EXPECT_EQ(sg.surface().solidNames, (std::vector<std::string>{"inlet", "walls"}));
    EXPECT_EQ(sg.nRegions(), 6);        // the six sides
    EXPECT_EQ(sg.featureEdges().size(), 12u*2u);  // 12 box edges, 2 segments each

    const CoarseMesh m = g->coarseMesh({0.3, 0.3});
    const double v = checkCoarseMesh(m);
    EXPECT_NEAR(v, 2.0, 1e-9);
    EXPECT_EQ(patchNames(m), (std::vector<std::string>{"inlet", "walls"}));

    std::map<label, std::set<label>> patchSurfaces;
    for (const auto& f : m.boundary)
    {
        patchSurfaces[f.patch].insert(f.surface);
        for (label p : f.v)
        {
            if (f.patch == 0)
            {
                EXPECT_EQ(m.points[p][0], 0.0);
            }
        }
        // All three points on the face's surface
        for (label p : f.v)
        {
            const point3 q = g->projectToSurface(m.points[p], f.surface);
            EXPECT_LT(std::sqrt(magSqr(q - m.points[p])), 1e-12);
        }
    }
    EXPECT_EQ(patchSurfaces[0].size(), 1u);
    EXPECT_EQ(patchSurfaces[1].size(), 5u);
}


TEST(stlGeometry, coplanarSolidsKeepTheirBoundary)
{
    // The inlet is flush with the wall around it: no angle marks the
    // boundary between the two solids, only the change of solid.
    // Mesh another STL with feature edges first: nglib keeps the edges of
    // the last geometry in a global buffer that would spoil this one's
    Geometry::New(dataDir + "box.stl")->coarseMesh({0.5, 0.3});
    const tempDir dir("geometry");
    const std::string f = dir.file("duct.stl", cubeWithInlet(4, 0.25, 0.75));
    auto g = Geometry::New(f);
    const stlGeometry& sg = dynamic_cast<const stlGeometry&>(*g);
    EXPECT_EQ(sg.surface().solidNames, (std::vector<std::string>{"inlet", "walls"}));
    EXPECT_EQ(sg.nRegions(), 7);

    const CoarseMesh m = g->coarseMesh({0.2, 0.3});
    checkCoarseMesh(m);
    double inletArea = 0;
    for (const auto& f : m.boundary)
    {
        if (m.patches[f.patch].name != "inlet") continue;
        for (label p : f.v)
        {
            const point3& x = m.points[p];
            EXPECT_EQ(x[0], 0.0);
            EXPECT_GE(x[1], 0.25 - 1e-12);
            EXPECT_LE(x[1], 0.75 + 1e-12);
            EXPECT_GE(x[2], 0.25 - 1e-12);
            EXPECT_LE(x[2], 0.75 + 1e-12);
        }
        inletArea += 0.5*std::sqrt(magSqr(cross
        (
            m.points[f.v[1]] - m.points[f.v[0]], m.points[f.v[2]] - m.points[f.v[0]]
        )));
    }
    EXPECT_NEAR(inletArea, 0.25, 1e-9);
}


TEST(stlGeometry, projection)
{
    auto g = Geometry::New(dataDir + "sphere.stl");
    const stlGeometry& sg = dynamic_cast<const stlGeometry&>(*g);
    std::mt19937 gen(2);
    std::uniform_real_distribution<double> u(-1.3, 1.3);
    for (int i = 0; i < 200; ++i)
    {
        const point3 p{u(gen), u(gen), u(gen)};
        const point3 q = g->projectToSurface(p, 0);
        EXPECT_TRUE(sameBits(q, g->projectToSurface(p, 0)));
        // On the triangles, and nearest
        EXPECT_LT(distanceToStl(sg.surface(), q), 1e-12);
        EXPECT_NEAR(std::sqrt(magSqr(p - q)), distanceToStl(sg.surface(), p), 1e-12);
    }

    // Box: the edge between two sides is a box edge
    auto b = Geometry::New(dataDir + "box.stl");
    const stlGeometry& bg = dynamic_cast<const stlGeometry&>(*b);
    const auto& region = bg.triangleRegion();
    const stlSurface& s = bg.surface();
    // Region of the side x = 0 (inlet) and of the side y = 0
    label rx0 = -1, ry0 = -1;
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        const auto& f = s.triangles[t];
        if (s.points[f[0]][0] == 0 && s.points[f[1]][0] == 0 && s.points[f[2]][0] == 0) rx0 = region[t];
        if (s.points[f[0]][1] == 0 && s.points[f[1]][1] == 0 && s.points[f[2]][1] == 0) ry0 = region[t];
    }
    ASSERT_GE(rx0, 0);
    ASSERT_GE(ry0, 0);
    ASSERT_NE(rx0, ry0);
    for (int i = 0; i < 50; ++i)
    {
        const point3 p{0.1*u(gen), 0.1*u(gen), 0.5 + 0.3*u(gen)};
        const point3 q = b->projectToEdge(p, rx0, ry0);
        EXPECT_EQ(q[0], 0.0);
        EXPECT_EQ(q[1], 0.0);
        EXPECT_NEAR(q[2], std::min(1.0, std::max(0.0, p[2])), 1e-15);
        EXPECT_TRUE(sameBits(q, b->projectToEdge(p, ry0, rx0)));
    }
    // Opposite sides share no edge: the surface of the first
    label rx1 = -1;
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        const auto& f = s.triangles[t];
        if (s.points[f[0]][0] == 2 && s.points[f[1]][0] == 2 && s.points[f[2]][0] == 2) rx1 = region[t];
    }
    ASSERT_GE(rx1, 0);
    const point3 q = b->projectToEdge({1, 0.5, 0.5}, rx0, rx1);
    EXPECT_EQ(q[0], 0.0);
    EXPECT_FATAL(b->projectToSurface({0, 0, 0}, 6), "valid surfaces are 0..5");
}


TEST(stlGeometry, projectionIsAsCloseToTheTrueSphereAsTheFacets)
{
    // sphere.stl approximates the unit sphere, its points on it (as
    // floats): a projected point is off the true sphere by no more than the
    // facets are (the largest distance of a facet's plane inside the
    // sphere), and near the true projection p/|p|
    auto g = Geometry::New(dataDir + "sphere.stl");
    const stlSurface& s = dynamic_cast<const stlGeometry&>(*g).surface();
    double facetDepth = 0, longestEdge = 0;
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        const vector3 n = s.areaNormal(t);
        const point3& a = s.points[s.triangles[t][0]];
        facetDepth = std::max(facetDepth, 1 - dot(n, a)/std::sqrt(magSqr(n)));
        for (int k = 0; k < 3; ++k)
        {
            const vector3 e = s.points[s.triangles[t][(k + 1) % 3]] - s.points[s.triangles[t][k]];
            longestEdge = std::max(longestEdge, std::sqrt(magSqr(e)));
        }
    }
    ASSERT_GT(facetDepth, 0);
    ASSERT_LT(facetDepth, 0.01);

    std::mt19937 gen(3);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < 2000; ++i)
    {
        point3 p{u(gen), u(gen), u(gen)};
        p = ((1 + 0.2*u(gen))/radius(p))*p;
        const point3 q = g->projectToSurface(p, 0);
        EXPECT_LE(radius(q), 1 + 1e-6) << str(p);
        EXPECT_GE(radius(q), 1 - facetDepth - 1e-6) << str(p);
        EXPECT_LT(std::sqrt(magSqr(q - (1/radius(p))*p)), longestEdge) << str(p);
    }
}


TEST(stlReader, bodyInABoxIsTwoShellsEachPointingOutOfTheFluid)
{
    const std::string f = testDataDir() + "/geometry/sphereInBox.stl";
    const stlSurface s = readStl(f);
    label nShells = 0;
    const std::vector<label> shell = surfaceShells(label(s.points.size()), s.triangles, nShells);
    ASSERT_EQ(nShells, 2);
    std::vector<label> bodyTriangles;
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        // The box's solids are one shell, the body the other
        EXPECT_EQ(shell[t], s.solidNames[s.solid[t]] == "body" ? 1 : 0);
        if (shell[t] == 1) bodyTriangles.push_back(t);
    }
    // The body points into itself: winding number -1 inside it
    EXPECT_NEAR(windingNumber(s.points, s.triangles, bodyTriangles, {0, 0, 0}), -1, 1e-9);
    EXPECT_NEAR(windingNumber(s.points, s.triangles, bodyTriangles, {2, 0, 0}), 0, 1e-9);
    EXPECT_NO_THROW(checkStl(s, f));

    auto flipSolids = [&](const std::vector<std::string>& names)
    {
        stlSurface flipped = s;
        for (label t = 0; t < flipped.nTriangles(); ++t)
        {
            const std::string& name = flipped.solidNames[flipped.solid[t]];
            if (std::find(names.begin(), names.end(), name) != names.end())
            {
                std::swap(flipped.triangles[t][1], flipped.triangles[t][2]);
            }
        }
        return flipped;
    };
    // The body's normals into the fluid: its total volume is still
    // positive, only the shell check sees it
    {
        const std::string m = errorOf([&]{ checkStl(flipSolids({"body"}), describeSurfaceFiles({f})); });
        EXPECT_NE(m.find("sphereInBox.stl\": the closed surface of solid body (1280 triangles between ("), std::string::npos) << m;
        EXPECT_NE(m.find(") lies inside that of solids inlet, outlet, sides"), std::string::npos) << m;
        EXPECT_NE(m.find("Flip the normals of solid body"), std::string::npos) << m;
    }
    {
        const std::string m = errorOf([&]{ checkStl(flipSolids({"inlet", "outlet", "sides"}), describeSurfaceFiles({f})); });
        EXPECT_NE(m.find("is oriented inward: the closed surface of solids inlet, outlet, sides (48 triangles"), std::string::npos) << m;
    }
}


// Curvature sizing asks for the radius of curvature over
// curvatureRefinement, never less than minCellSize, and its sizes grow
// along the surface by at most grading times the distance. The needle
// (radius 0.03) wants 0.01 at curvatureRefinement 3.
TEST(stlGeometry, curvatureSizesKeepTheirFloorAndGrading)
{
    const auto g = Geometry::New(dataDir + "needleInBox.stl");
    const stlGeometry& sg = dynamic_cast<const stlGeometry&>(*g);
    const stlSurface& s = sg.surface();
    const double maxh = 2.5, grading = 0.3;

    const auto unbounded = sg.curvatureSizes(3, 1e-6, maxh, grading);
    double smallest = maxh;
    for (const sizePoint& p : unbounded.points) smallest = std::min(smallest, p.size);
    // Centroids near the capsule's poles lie closer to the axis: up to
    // 1.6x smaller there
    EXPECT_GT(smallest, 0.01/1.7);
    EXPECT_LT(smallest, 0.01*1.1);

    const double floor = 0.05;
    const auto sizing = sg.curvatureSizes(3, floor, maxh, grading);
    ASSERT_FALSE(sizing.points.empty());
    std::map<std::array<double, 3>, double> size;
    for (const sizePoint& p : sizing.points)
    {
        EXPECT_GE(p.size, floor*(1 - 1e-12));
        EXPECT_LT(p.size, maxh);
        size[{p.p[0], p.p[1], p.p[2]}] = p.size;
    }
    auto sizeOf = [&](label v)
    {
        const auto it = size.find({s.points[v][0], s.points[v][1], s.points[v][2]});
        return it == size.end() ? maxh : it->second;
    };
    label nEdges = 0;
    for (const triVerts& f : s.triangles)
    {
        for (int k = 0; k < 3; ++k)
        {
            const label a = f[k], b = f[(k + 1) % 3];
            const double length = std::sqrt(magSqr(s.points[a] - s.points[b]));
            EXPECT_LE(std::abs(sizeOf(a) - sizeOf(b)), grading*length*(1 + 1e-9) + 1e-12)
                << "edge " << a << '-' << b;
            ++nEdges;
        }
    }
    EXPECT_GT(nEdges, 0);

    // Only the body's solid asks for anything; nothing with sizing off
    const auto& names = s.solidNames;
    const auto body = std::find(names.begin(), names.end(), "body") - names.begin();
    for (std::size_t i = 0; i < sizing.solids.size(); ++i)
    {
        EXPECT_EQ(sizing.solids[i].nPoints > 0, label(i) == body) << names[i];
    }
    EXPECT_GT(sizing.solids[body].nAtFloor, 0);
    EXPECT_TRUE(sg.curvatureSizes(0, floor, maxh, grading).points.empty());
}


// Away from a small feature the sizes grow by at most grading times the
// distance: a box whose inlet face has a shallow bump at its centre asks
// for about 2.7 there, and its far corners get no more than that plus
// grading times their distance, not maxCellSize.
TEST(stlGeometry, curvatureSizesGrowAwayFromAFeatureAsGradingAllows)
{
    stlSurface box = readStl(dataDir + "box.stl");
    const auto centre = std::find
    (
        box.points.begin(), box.points.end(), point3{0, 0.5, 0.5}
    );
    ASSERT_NE(centre, box.points.end());
    (*centre)[0] = -0.01;
    const tempDir dir("curvatureGrading");
    writeSurfaceStl(dir/"bump.stl", "box", box.points, box.triangles);
    const auto g = Geometry::New(dir/"bump.stl");
    const stlGeometry& sg = dynamic_cast<const stlGeometry&>(*g);

    const double maxh = 100;
    for (const double grading : {0.1, 0.3, 1.0})
    {
        const auto sizing = sg.curvatureSizes(3, 0.01, maxh, grading);
        double smallest = maxh, largest = 0;
        point3 at{0, 0, 0};
        for (const sizePoint& p : sizing.points)
        {
            if (p.size < smallest)
            {
                smallest = p.size;
                at = p.p;
            }
        }
        EXPECT_LT(smallest, 10) << grading;
        // Every point of the box is sized (one connected surface), within
        // grading times its distance along the surface of the smallest
        EXPECT_EQ(sizing.points.size(), sg.surface().points.size()) << grading;
        for (const sizePoint& p : sizing.points)
        {
            largest = std::max(largest, p.size);
            EXPECT_LE(p.size, smallest + grading*4*std::sqrt(magSqr(p.p - at)) + 1e-12);
        }
        EXPECT_GT(largest, smallest) << grading;
    }
}


// The ray query finds what trying every triangle finds: random segments
// from inside the unit sphere's facets, their first hit and its distance.
TEST(boxTree, aRayMeetsTheTriangleThatTryingEveryOneFinds)
{
    const stlSurface s = readStl(dataDir + "sphere.stl");
    std::vector<boxTree::entry> entries;
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        entries.push_back(triangleEntry(s, t));
    }
    const boxTree tree(entries);
    const auto hit = [&](label t, const point3& x, const vector3& dir)
    {
        const triVerts& f = s.triangles[t];
        return rayHitsTriangle(x, dir, s.points[f[0]], s.points[f[1]], s.points[f[2]]);
    };
    std::mt19937 random(7);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    label nHits = 0;
    for (int i = 0; i < 500; ++i)
    {
        const point3 x{u(random), u(random), u(random)};
        vector3 dir{u(random), u(random), u(random)};
        dir = (1/std::sqrt(magSqr(dir)))*dir;
        for (const double length : {0.3, 2.0})
        {
            label everyFirst = -1;
            double everyDistance = length;
            for (label t = 0; t < s.nTriangles(); ++t)
            {
                const double d = hit(t, x, dir);
                if (d > 0 && d <= everyDistance)
                {
                    everyDistance = d;
                    everyFirst = t;
                }
            }
            label first = -1;
            double reach = length;
            tree.alongRay
            (
                x, dir, reach,
                [&](label t)
                {
                    const double d = hit(t, x, dir);
                    if (d > 0 && d <= reach)
                    {
                        reach = d;
                        first = t;
                    }
                }
            );
            EXPECT_EQ(first, everyFirst) << str(x) << ' ' << length;
            EXPECT_EQ(reach, everyDistance) << str(x) << ' ' << length;
            nHits += first >= 0;
        }
    }
    // Every long segment leaves the sphere; short ones mostly do not
    EXPECT_GT(nHits, 500);
    EXPECT_LT(nHits, 1000);
}


// Gap sizing: the two faces of a slot 0.06 wide between two blocks in a
// domain box face each other; at a local size of 0.15 they ask for the
// gap over cellsAcrossGap, never below a quarter of the local size, and
// nothing else does (the box is a block's length away). A gap wider than
// cellsAcrossGap local sizes asks nothing, and one narrower than a
// quarter of the local size is a contact, left as it is.
TEST(stlGeometry, gapSizesNarrowASlotToTheGapOverCellsAcrossIt)
{
    domainBox box;
    box.given = true;
    box.min = {-1, -1, -1};
    box.max = {3.06, 2, 2};
    const stlGeometry g({dataDir + "twoBlocksWithASlot.stl"}, box);
    const stlSurface& s = g.surface();
    const double gap = 1.06f - 1.0;
    const auto sizes = [&](double h) { return std::vector<double>(s.nTriangles(), h); };
    const auto onASlotFace = [&](const point3& p)
    {
        return
            (std::abs(p[0] - 1) < 1e-6 || std::abs(p[0] - 1.06f) < 1e-6)
         && p[1] > 0 && p[1] < 1 && p[2] > 0 && p[2] < 1;
    };

    const auto one = g.gapSizes(1, sizes(0.15));
    ASSERT_FALSE(one.points.empty());
    for (const sizePoint& p : one.points)
    {
        EXPECT_TRUE(onASlotFace(p.p)) << str(p.p, 10);
        EXPECT_NEAR(p.size, gap, 1e-6) << str(p.p, 10);
    }
    // The slot's four triangles, two a face, and no other
    EXPECT_EQ(one.nTriangles, 4);
    EXPECT_NEAR(one.narrowest, gap, 1e-6);
    EXPECT_EQ(one.nAtFloor, 0);

    // Two cells across would be 0.03: held at 0.15/4
    const auto two = g.gapSizes(2, sizes(0.15));
    ASSERT_FALSE(two.points.empty());
    for (const sizePoint& p : two.points)
    {
        EXPECT_NEAR(p.size, 0.15/4, 1e-12);
    }
    EXPECT_EQ(two.nAtFloor, label(two.points.size()));

    EXPECT_TRUE(g.gapSizes(1, sizes(0.04)).points.empty()) << "a gap wider than the cells";
    // (0.9: the box's sides, a block's length away, stay out of reach)
    const auto contact = g.gapSizes(1, sizes(0.9));
    EXPECT_TRUE(contact.points.empty()) << "a gap under a quarter of the cells";
    EXPECT_GT(contact.nContacts, 0);
    EXPECT_TRUE(g.gapSizes(0, sizes(0.15)).points.empty());
}


// Touching shells are named, with a point, before Netgen sees them: a
// desk whose legs stand on the floor of its room and touch its top, and
// two cubes sharing a face.
TEST(stlReader, touchingShellsAreNamedWithAPoint)
{
    const std::string room = dataDir + "roomWithDesk.stl";
    const std::string m = errorOf([&] { checkStl(readStl(room), describeSurfaceFiles({room})); });
    // Each of the four legs touches the top (at its corners) and the floor
    EXPECT_NE(m.find("roomWithDesk.stl\": 8 pair(s) of closed surfaces touch or overlap"), std::string::npos) << m;
    EXPECT_NE(m.find("the closed surface of solid deskTop (12 triangles between (1 1 0.6999999881) and (3 2 0.75))\n"
                     "    and the closed surface of solid deskLegs (12 triangles between (1 1 0) and"
                     " (1.049999952 1.049999952 0.6999999881))\n"
                     "        share the point at (1 1 0.6999999881)"), std::string::npos) << m;
    EXPECT_NE(m.find("the closed surface of solid room (the outer boundary) (12 triangles"), std::string::npos) << m;
    EXPECT_NE(m.find("touch or overlap at ("), std::string::npos) << m;
    EXPECT_NE(m.find("... and 3 more"), std::string::npos) << m;
    EXPECT_NE(m.find("join the touching solids into one closed surface"), std::string::npos) << m;
    EXPECT_NE(m.find("move them apart"), std::string::npos) << m;

    const std::string cubes = dataDir + "twoCubesSharingAFace.stl";
    const std::string c = errorOf([&] { checkStl(readStl(cubes), describeSurfaceFiles({cubes})); });
    EXPECT_NE(c.find("is not manifold"), std::string::npos) << c;
    EXPECT_NE(c.find("triangles of solids left, right"), std::string::npos) << c;
    EXPECT_NE(c.find("share faces or edges (touching shells)"), std::string::npos) << c;
    EXPECT_NE(c.find("join the touching solids"), std::string::npos) << c;
}


// Shells apart, also when one is close (a gap of 1e-4 of the size), pass;
// two shells touching at one point do not.
TEST(stlReader, shellsApartPassAndShellsSharingAPointDoNot)
{
    for (const char* name : {"sphereInBox.stl", "cylinderInBox.stl", "needleInBox.stl"})
    {
        const std::string f = dataDir + name;
        EXPECT_NO_THROW(checkStl(readStl(f), f)) << name;
    }

    // A tetrahedron in a box, lifted 1e-3 off its floor, then onto a
    // corner of a second tetrahedron
    stlSurface s;
    s.points = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}};
    s.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    s.solid.assign(4, 0);
    s.solidNames = {"outer", "body"};
    auto addTet = [&s](const point3 o, double a)
    {
        const label n = label(s.points.size());
        s.points.push_back(o);
        s.points.push_back(o + point3{a, 0, 0});
        s.points.push_back(o + point3{0, a, 0});
        s.points.push_back(o + point3{0, 0, a});
        // Inward: a body in the fluid
        for (const triVerts& t : {triVerts{0, 1, 2}, triVerts{0, 3, 1}, triVerts{0, 2, 3}, triVerts{1, 3, 2}})
        {
            s.triangles.push_back({n + t[0], n + t[1], n + t[2]});
            s.solid.push_back(1);
        }
    };
    addTet({0.5, 0.5, 1e-3}, 0.5);
    EXPECT_NO_THROW(checkStl(s, "lifted.stl"));

    stlSurface onFloor = s;
    onFloor.points[4][2] = 0;
    onFloor.points[5][2] = 0;
    onFloor.points[6][2] = 0;
    onFloor.points[7][2] = 0.5;
    const std::string m = errorOf([&] { checkStl(onFloor, describeSurfaceFiles({"onFloor.stl"})); });
    EXPECT_NE(m.find("1 pair(s) of closed surfaces touch or overlap"), std::string::npos) << m;
    EXPECT_NE(m.find("solid outer (the outer boundary)"), std::string::npos) << m;
    EXPECT_NE(m.find("solid body (4 triangles"), std::string::npos) << m;

    // A second body whose corner is the first body's apex: one shared
    // point, no shared edge
    stlSurface sharing = s;
    addTet(s.points[7], 0.5);
    const label apex = 7;
    const label n = label(s.points.size()) - 4;
    sharing.points = s.points;
    for (label t = label(sharing.triangles.size()); t < s.nTriangles(); ++t)
    {
        triVerts u = s.triangles[t];
        for (label& v : u) v = v == n ? apex : v;
        sharing.triangles.push_back(u);
        sharing.solid.push_back(1);
    }
    const std::string p = errorOf([&] { checkStl(sharing, describeSurfaceFiles({"sharing.stl"})); });
    EXPECT_NE(p.find("share the point at (0.5 0.5 0.501)"), std::string::npos) << p;
}
