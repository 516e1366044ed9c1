// Geometry: CSG (.geo) and STL loading, coarse meshes through Netgen, patch
// names, projection onto surfaces and edges, and every STL input error.

#include "testPaths.H"
#include "surfaceTopology.H"
#include "coarseMeshGeneration.H"
#include "csgGeometry.H"
#include "stlGeometry.H"
#include "stlReader.H"
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

const std::string dataDir = std::string(PMSH_TEST_DATA) + "/geometry/";


std::vector<std::string> patchNames(const CoarseMesh& m)
{
    std::vector<std::string> names;
    for (const meshPatch& p : m.patches) names.push_back(p.name);
    return names;
}


//- Checks every coarse mesh must pass; returns the enclosed volume.
double checkCoarseMesh(const CoarseMesh& m)
{
    EXPECT_GT(m.nCells(), 0);
    EXPECT_FALSE(m.boundary.empty());

    double tetVolume = 0;
    for (const tetVerts& t : m.tets)
    {
        const double v6 = tetVolume6(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]);
        EXPECT_GT(v6, 0);
        tetVolume += v6/6;
    }

    // Closed and consistently oriented: every directed edge once, with its
    // reverse once
    std::map<std::pair<label, label>, int> directed;
    for (const auto& f : m.boundary)
    {
        EXPECT_GE(f.patch, 0);
        EXPECT_LT(f.patch, label(m.patches.size()));
        for (int k = 0; k < 3; ++k)
        {
            ++directed[{f.v[k], f.v[(k + 1) % 3]}];
        }
    }
    for (const auto& d : directed)
    {
        EXPECT_EQ(d.second, 1);
        EXPECT_EQ(directed.count({d.first.second, d.first.first}), 1u);
    }

    // Outward: the enclosed volume is positive and equals the tets'
    double v6 = 0;
    for (const auto& f : m.boundary)
    {
        v6 += dot(m.points[f.v[0]], cross(m.points[f.v[1]], m.points[f.v[2]]));
    }
    EXPECT_GT(v6, 0);
    EXPECT_NEAR(v6/6, tetVolume, 1e-9*tetVolume);

    // Every point used
    std::vector<bool> used(m.points.size(), false);
    for (const tetVerts& t : m.tets)
    {
        for (label p : t) used[p] = true;
    }
    EXPECT_EQ(std::count(used.begin(), used.end(), false), 0);

    return v6/6;
}


double radius(const point3& p)
{
    return std::sqrt(magSqr(p));
}


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


bool sameBits(const point3& a, const point3& b)
{
    return std::memcmp(a.data(), b.data(), sizeof(point3)) == 0;
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


// * * * * * * * * * * * * * * * * * CSG  * * * * * * * * * * * * * * * * * //

TEST(csgGeometry, sphereCoarseMesh)
{
    auto g = Geometry::New(dataDir + "sphere.geo");
    const CoarseMesh m = g->coarseMesh({0.5, 0.3});

    const double v = checkCoarseMesh(m);
    EXPECT_NEAR(v, 4.0/3.0*M_PI, 0.15*4.0/3.0*M_PI);

    ASSERT_EQ(patchNames(m), std::vector<std::string>{"wall"});
    for (const auto& f : m.boundary)
    {
        EXPECT_EQ(f.patch, 0);
        EXPECT_EQ(f.surface, 0);
        for (label p : f.v)
        {
            EXPECT_NEAR(radius(m.points[p]), 1.0, 1e-6);
        }
    }
}


TEST(coarseMesher, hxtFillsNetgensSurfaceKeepingItBitForBit)
{
    const Communicator serial;
    for (const std::string file : {"sphere.geo", "sphere.stl"})
    {
        auto g = Geometry::New(dataDir + file);
        coarseMeshParameters p(0.4, 0.3);
        const CoarseMesh surface = g->coarseSurface(p);
        EXPECT_TRUE(surface.tets.empty()) << file;
        ASSERT_FALSE(surface.boundary.empty()) << file;

        p.mesher = "hxt";
        const CoarseMesh m = generateCoarseMesh(serial, *g, p);
        EXPECT_EQ(m.volumeMesher, "hxt") << file;
        EXPECT_NEAR(checkCoarseMesh(m), 4.0/3.0*M_PI, 0.15*4.0/3.0*M_PI) << file;

        // Netgen's surface, points and faces, is the boundary of the fill
        ASSERT_GE(m.points.size(), surface.points.size()) << file;
        EXPECT_EQ(0, std::memcmp(m.points.data(), surface.points.data(),
                                 surface.points.size()*sizeof(point3))) << file;
        ASSERT_EQ(m.boundary.size(), surface.boundary.size()) << file;
        for (std::size_t b = 0; b < m.boundary.size(); ++b)
        {
            EXPECT_EQ(m.boundary[b].v, surface.boundary[b].v) << file;
            EXPECT_EQ(m.boundary[b].patch, surface.boundary[b].patch) << file;
            EXPECT_EQ(m.boundary[b].surface, surface.boundary[b].surface) << file;
        }
        EXPECT_EQ(patchNames(m), patchNames(surface)) << file;
    }
}


TEST(csgGeometry, sphereProjectionIsExactAndPure)
{
    auto g = Geometry::New(dataDir + "sphere.geo");
    std::mt19937 gen(1);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < 100; ++i)
    {
        point3 d{u(gen), u(gen), u(gen)};
        d = (1.1/radius(d))*d;
        const point3 q = g->projectToSurface(d, 0);
        EXPECT_NEAR(radius(q), 1.0, 1e-12);
        EXPECT_TRUE(sameBits(q, g->projectToSurface(d, 0)));
        // Direction kept
        EXPECT_NEAR(dot(q, d)/radius(d), 1.0, 1e-12);
    }
    EXPECT_FATAL(g->projectToSurface({1, 0, 0}, 7), "valid surfaces are 0..0");
}


//- How far x is from the true surface of shaft.geo that the patch lies on.
double offShaftPatch(const std::string& patch, const point3& x)
{
    const double r = std::hypot(x[0], x[1]);
    if (patch == "inlet") return std::abs(x[2]);
    if (patch == "outlet") return std::abs(x[2] - 3);
    if (patch == "shoulder") return std::abs(x[2] - 1.5);
    if (patch == "shaftWall") return std::abs(r - 0.5);
    if (patch == "shoulderWall") return std::abs(r - 1.0);
    ADD_FAILURE() << "no patch " << patch << " in shaft.geo";
    return 1;
}


TEST(csgGeometry, shaftPatchesAndEdgeProjection)
{
    auto g = Geometry::New(dataDir + "shaft.geo");
    const CoarseMesh m = g->coarseMesh({0.4, 0.3});
    checkCoarseMesh(m);

    std::set<std::string> names;
    for (const meshPatch& p : m.patches) names.insert(p.name);
    EXPECT_EQ
    (
        names,
        (std::set<std::string>{"inlet", "outlet", "shoulder", "shaftWall", "shoulderWall"})
    );

    // Each patch has faces, on the right place
    std::map<std::string, int> nFaces;
    for (const auto& f : m.boundary)
    {
        const std::string& name = m.patches[f.patch].name;
        ++nFaces[name];
        for (label p : f.v)
        {
            EXPECT_LT(offShaftPatch(name, m.points[p]), 1e-6) << name;
        }

        // A face's centroid projects onto its true surface
        const point3 c = (1.0/3)*(m.points[f.v[0]] + m.points[f.v[1]] + m.points[f.v[2]]);
        EXPECT_LT(offShaftPatch(name, g->projectToSurface(c, f.surface)), 1e-12) << name;
    }
    EXPECT_EQ(nFaces.size(), 5u);

    // The shoulder plane faces the +z direction from the thin section's
    // side: its outward normal is -z (Netgen gives it DomainIn 0: flipped)
    for (const auto& f : m.boundary)
    {
        if (m.patches[f.patch].name == "shoulder")
        {
            const vector3 n = cross
            (
                m.points[f.v[1]] - m.points[f.v[0]],
                m.points[f.v[2]] - m.points[f.v[0]]
            );
            EXPECT_LT(n[2], 0);
        }
    }

    // Coarse edges between faces of two surfaces: the midpoint projected
    // onto the edge lies on both true surfaces
    std::map<std::pair<label, label>, std::vector<label>> edgeFaces;
    for (std::size_t i = 0; i < m.boundary.size(); ++i)
    {
        const auto& f = m.boundary[i].v;
        for (int k = 0; k < 3; ++k)
        {
            edgeFaces[{std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])}]
                .push_back(label(i));
        }
    }
    int nChecked = 0;
    for (const auto& ef : edgeFaces)
    {
        ASSERT_EQ(ef.second.size(), 2u);
        const coarseBoundaryFace& f1 = m.boundary[ef.second[0]];
        const coarseBoundaryFace& f2 = m.boundary[ef.second[1]];
        const label s1 = f1.surface;
        const label s2 = f2.surface;
        if (s1 == s2)
        {
            continue;
        }
        const point3 mid = midPoint(m.points[ef.first.first], m.points[ef.first.second]);
        const point3 q = g->projectToEdge(mid, s1, s2);
        EXPECT_TRUE(sameBits(q, g->projectToEdge(mid, s1, s2)));
        EXPECT_TRUE(sameBits(q, g->projectToEdge(mid, s2, s1)));
        EXPECT_LT(offShaftPatch(m.patches[f1.patch].name, q), 1e-10);
        EXPECT_LT(offShaftPatch(m.patches[f2.patch].name, q), 1e-10);
        EXPECT_LT(std::sqrt(magSqr(q - mid)), 0.1);
        ++nChecked;
    }
    EXPECT_GT(nChecked, 20);
}


TEST(csgGeometry, surfacesWithoutBcNamesTakeTheirSolidsName)
{
    const tempDir dir("geometry");
    const std::string f = dir.file
    (
        "cube.geo",
        "algebraic3d\n"
        "solid cube = orthobrick(0, 0, 0; 1, 1, 1) -bc=3;\n"
        "tlo cube;\n"
    );
    auto g = Geometry::New(f);
    const CoarseMesh m = g->coarseMesh({0.5, 0.3});
    checkCoarseMesh(m);
    EXPECT_EQ(patchNames(m), std::vector<std::string>{"cube"});
    std::set<label> surfaces;
    for (const auto& b : m.boundary) surfaces.insert(b.surface);
    EXPECT_EQ(surfaces.size(), 6u);
}


TEST(csgGeometry, errors)
{
    const tempDir dir("geometry");
    EXPECT_FATAL(Geometry::New("/nonexistent/body.geo"), "Cannot open CSG geometry file \"/nonexistent/body.geo\"");

    const std::string noKeyword = dir.file("a.geo", "solid ball = sphere(0, 0, 0; 1);\ntlo ball;\n");
    EXPECT_FATAL(Geometry::New(noKeyword), "does not start with the keyword algebraic3d");

    const std::string syntax = dir.file
    (
        "b.geo",
        "algebraic3d\n# comment\nsolid ball = sphere(0, 0, 0; 1;\ntlo ball;\n"
    );
    const std::string m = errorOf([&]{ Geometry::New(syntax); });
    EXPECT_NE(m.find("Cannot parse CSG geometry file \"" + syntax + "\""), std::string::npos) << m;
    EXPECT_NE(m.find("line 3"), std::string::npos) << m;

    const std::string flagOnPrimitive = dir.file
    (
        "b2.geo",
        "algebraic3d\nsolid c = cylinder(0, 0, -1; 0, 0, 2; 1) and plane(0, 0, 0; 0, 0, -1) -bcname=inlet"
        " and plane(0, 0, 1; 0, 0, 1);\ntlo c;\n"
    );
    EXPECT_FATAL(Geometry::New(flagOnPrimitive), "go at the end of a solid definition");

    const std::string unknownPrimitive = dir.file
    (
        "c.geo", "algebraic3d\nsolid ball = sphear(0, 0, 0; 1);\ntlo ball;\n"
    );
    EXPECT_FATAL(Geometry::New(unknownPrimitive), "sphear");

    const std::string noTlo = dir.file("d.geo", "algebraic3d\nsolid ball = sphere(0, 0, 0; 1);\n");
    EXPECT_FATAL(Geometry::New(noTlo), "no top-level object");

    const std::string unbounded = dir.file
    (
        "e.geo",
        "algebraic3d\nsolid c = cylinder(0, 0, 0; 0, 0, 1; 0.5) and plane(0, 0, 0; 0, 0, -1);\ntlo c;\n"
    );
    EXPECT_FATAL(Geometry::New(unbounded), "is not bounded");

    // A solid that touches a user-given bounding box is bounded
    const std::string touching = dir.file
    (
        "f.geo",
        "algebraic3d\nboundingbox(0, 0, 0; 1, 1, 1);\n"
        "solid cube = orthobrick(0, 0, 0; 1, 1, 1);\ntlo cube;\n"
    );
    EXPECT_NO_THROW(Geometry::New(touching)->coarseMesh({0.5, 0.3}));

    EXPECT_FATAL(Geometry::New(dir.file("body.step", "x")), ".geo");
    EXPECT_FATAL(Geometry::New(dir.file("body.step", "x")), ".stl");
    EXPECT_FATAL(Geometry::New(dir.file("body", "x")), "no extension");

    // Extensions are case-insensitive
    const std::string upper = dir.file("SPHERE.GEO", readFile(dataDir + "sphere.geo"));
    EXPECT_NO_THROW(Geometry::New(upper));
}


// * * * * * * * * * * * * * * * * * STL  * * * * * * * * * * * * * * * * * //

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
        checkStl(readStl(f), f);
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


TEST(csgGeometry, aBodyInABoxKeepsItsBcNameAndTheRestTakesTheSolidsName)
{
    // The surfaces without a bcname (the six box faces, each its own bc
    // number) share one patch named after the top-level solid
    const tempDir dir("geometry");
    const std::string f = dir.file
    (
        "bodyInBox.geo",
        "algebraic3d\n"
        "solid box = orthobrick(-2, -2, -2; 2, 2, 2);\n"
        "solid body = sphere(0, 0, 0; 0.5) -bcname=ball;\n"
        "solid fluid = box and not body;\n"
        "tlo fluid;\n"
    );
    const CoarseMesh m = Geometry::New(f)->coarseMesh({1.0, 0.3});
    checkCoarseMesh(m);
    std::vector<std::string> names = patchNames(m);
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"ball", "fluid"}));
}


namespace
{

// Netgen's periodic cube, the sides z = 0 and z = 1 paired, with the
// bcnames given (none if empty)
std::string periodicCube
(
    const tempDir& dir,
    const std::string& firstName,
    const std::string& secondName
)
{
    auto bc = [](const std::string& name)
    {
        return name.empty() ? std::string() : " -bcname=" + name;
    };
    return dir.file
    (
        "periodic.geo",
        "algebraic3d\n"
        "solid p1 = plane(0, 0, 0; 0, 0, -1)" + bc(firstName) + ";\n"
        "solid p2 = plane(1, 1, 1; 0, 0, 1)" + bc(secondName) + ";\n"
        "solid cube = plane(0, 0, 0; 0, -1, 0) and plane(0, 0, 0; -1, 0, 0)\n"
        "    and plane(1, 1, 1; 0, 1, 0) and plane(1, 1, 1; 1, 0, 0)\n"
        "    and p1 and p2;\n"
        "tlo cube;\n"
        "identify periodic p1 p2;\n"
    );
}


// The first and second patch names of every periodic pair
std::vector<std::pair<std::string, std::string>> periodicPatchNames
(
    const CoarseMesh& m
)
{
    std::vector<std::pair<std::string, std::string>> names;
    for (const periodicPatchPair& pp : m.periodicPatches)
    {
        names.push_back({m.patches[pp.first].name, m.patches[pp.second].name});
    }
    return names;
}


// Every pair's sides are images of each other through that pair's points
// alone: each face of the first patch, mapped point by point, is a face
// of the second, each point moved by the pair's separation, and the two
// patches have as many faces. Returns the pairs each point is a first
// point of.
std::map<label, std::set<label>> expectPeriodicImages(const CoarseMesh& m)
{
    std::vector<std::map<label, label>> image(m.periodicPatches.size());
    std::map<label, std::set<label>> pairsOfPoint;
    for (const periodicPoint& p : m.periodicPoints)
    {
        EXPECT_TRUE(image.at(p.pair).emplace(p.point, p.image).second)
            << "point " << p.point << " has two images in pair " << p.pair;
        pairsOfPoint[p.point].insert(p.pair);
    }
    for (std::size_t pair = 0; pair < m.periodicPatches.size(); ++pair)
    {
        const periodicPatchPair& pp = m.periodicPatches[pair];
        std::set<triVerts> second;
        label nFirst = 0;
        for (const coarseBoundaryFace& b : m.boundary)
        {
            triVerts f = b.v;
            std::sort(f.begin(), f.end());
            if (b.patch == pp.second) second.insert(f);
            nFirst += b.patch == pp.first;
        }
        EXPECT_GT(nFirst, 1);
        EXPECT_EQ(label(second.size()), nFirst) << m.patches[pp.first].name;
        for (const coarseBoundaryFace& b : m.boundary)
        {
            if (b.patch != pp.first) continue;
            triVerts f;
            for (int k = 0; k < 3; ++k)
            {
                const auto it = image[pair].find(b.v[k]);
                f[k] = it == image[pair].end() ? -1 : it->second;
                EXPECT_GE(f[k], 0)
                    << "point " << b.v[k] << " of patch " << m.patches[pp.first].name
                    << " has no image";
                if (f[k] < 0) continue;
                for (int d = 0; d < 3; ++d)
                {
                    EXPECT_NEAR
                    (
                        m.points[f[k]][d] - m.points[b.v[k]][d], pp.separation[d], 1e-9
                    );
                }
            }
            std::sort(f.begin(), f.end());
            EXPECT_EQ(second.count(f), 1u) << m.patches[pp.first].name;
        }
    }
    return pairsOfPoint;
}

} // End anonymous namespace


TEST(csgGeometry, periodicSidesAreImagesOfEachOtherByOneTranslation)
{
    const tempDir dir("geometry");
    const CoarseMesh m =
        Geometry::New(periodicCube(dir, "bottom", "top"))->coarseMesh({0.3, 0.3});
    checkCoarseMesh(m);
    ASSERT_EQ(m.periodicPatches.size(), 1u);
    const periodicPatchPair& pp = m.periodicPatches[0];
    EXPECT_EQ(m.patches[pp.first].name, "bottom");
    EXPECT_EQ(m.patches[pp.second].name, "top");
    EXPECT_NEAR(pp.separation[0], 0, 1e-12);
    EXPECT_NEAR(pp.separation[1], 0, 1e-12);
    EXPECT_NEAR(pp.separation[2], 1, 1e-12);
    expectPeriodicImages(m);
}


TEST(csgGeometry, periodicCubeSidesMeetAtEdgesAndCornersEachMappedThroughItsOwnPair)
{
    // Three pairs touching along the cube's edges: a point on an edge is
    // in two pairs, a corner in three, with a different image in each
    const CoarseMesh m =
        Geometry::New(testDataDir() + "/geometry/fullyPeriodicCube.geo")
            ->coarseMesh({0.3, 0.3});
    checkCoarseMesh(m);
    EXPECT_EQ
    (
        periodicPatchNames(m),
        (std::vector<std::pair<std::string, std::string>>
        {{"left", "right"}, {"front", "back"}, {"bottom", "top"}})
    );
    for (std::size_t pair = 0; pair < 3; ++pair)
    {
        for (std::size_t d = 0; d < 3; ++d)
        {
            EXPECT_NEAR(m.periodicPatches[pair].separation[d], d == pair ? 1 : 0, 1e-12);
        }
    }
    const std::map<label, std::set<label>> pairsOfPoint = expectPeriodicImages(m);
    label origin = -1;
    for (label p = 0; p < m.nPoints(); ++p)
    {
        if (magSqr(m.points[p]) < 1e-20) origin = p;
    }
    ASSERT_GE(origin, 0);
    EXPECT_EQ(pairsOfPoint.at(origin), (std::set<label>{0, 1, 2}));
    label nOnEdges = 0;
    for (const auto& [point, pairs] : pairsOfPoint)
    {
        nOnEdges += pairs.size() == 2;
    }
    EXPECT_GT(nOnEdges, 3);
}


TEST(csgGeometry, netgensPeriodExampleHasTwoRegionsAndThreePairs)
{
    // Netgen's tutorials/period.geo: no bcnames, so each side is named
    // after its solid; both regions reach the sides the cylinders cross
    const CoarseMesh m =
        Geometry::New(testDataDir() + "/geometry/period.geo")->coarseMesh({0.3, 0.3});
    checkCoarseMesh(m);
    EXPECT_EQ(m.zones, (std::vector<std::string>{"matrix", "inner"}));
    EXPECT_EQ
    (
        periodicPatchNames(m),
        (std::vector<std::pair<std::string, std::string>>
        {{"p1", "p2"}, {"p3", "p4"}, {"p5", "p6"}})
    );
    expectPeriodicImages(m);
    std::map<std::string, std::set<label>> zonesOfPatch;
    for (const coarseBoundaryFace& b : m.boundary)
    {
        zonesOfPatch[m.patches[b.patch].name].insert(b.zone);
    }
    for (const std::string side : {"p1", "p2", "p5", "p6"})
    {
        EXPECT_EQ(zonesOfPatch[side], (std::set<label>{0, 1})) << side;
    }
}


TEST(csgGeometry, periodicSidesWithoutBcnamesAreNamedAfterTheirSolids)
{
    const tempDir dir("geometry");
    const CoarseMesh m = Geometry::New(periodicCube(dir, "", ""))->coarseMesh({0.3, 0.3});
    EXPECT_EQ
    (
        periodicPatchNames(m),
        (std::vector<std::pair<std::string, std::string>>{{"p1", "p2"}})
    );
}


TEST(csgGeometry, periodicSidesSharingAPatchAreAnErrorAskingForBcnames)
{
    // Both sides would be one patch: no cyclic pair can be made of it
    const tempDir dir("geometry");
    const auto geometry = Geometry::New(periodicCube(dir, "sides", "sides"));
    EXPECT_FATAL
    (
        geometry->coarseMesh({0.3, 0.3}),
        "cannot make cyclic patches of 'identify periodic p1 p2': both surfaces"
        " are in patch sides. Give each its own -bcname"
    );
}


TEST(csgGeometry, unsupportedPeriodicPairsAreErrorsNamingTheirCase)
{
    const tempDir dir("geometry");
    const std::string cube =
        " and plane(0, 0, 0; 0, -1, 0) and plane(1, 1, 1; 0, 1, 0)"
        " and plane(0, 0, 0; 0, 0, -1) and plane(1, 1, 1; 0, 0, 1)";
    auto errorFor = [&](const std::string& name, const std::string& text)
    {
        const std::string file = dir.file(name, "algebraic3d\n" + text);
        const auto geometry = Geometry::New(file);
        const std::string m = errorOf([&]{ geometry->coarseMesh({0.3, 0.3}); });
        EXPECT_NE(m.find("CSG geometry \"" + file + "\": cannot make cyclic patches of 'identify periodic "), std::string::npos) << m;
        return m;
    };

    // Rotational: Netgen pairs only the points on the wedge's axis, each
    // with itself
    {
        const std::string m = errorFor
        (
            "wedge.geo",
            "solid a = plane(0, 0, 0; 0, -1, 0) -bcname=a;\n"
            "solid b = plane(0, 0, 0; -0.5, 0.8660254037844386, 0) -bcname=b;\n"
            "solid w = a and b and plane(0, 0, 0; 0, 0, -1) and plane(0, 0, 1; 0, 0, 1)\n"
            "    and sphere(0, 0, 0; 1);\n"
            "identify periodic a b;\n"
            "tlo w;\n"
        );
        EXPECT_NE(m.find("'identify periodic a b': a and b are not a translation of each other"), std::string::npos) << m;
        EXPECT_NE(m.find("Only translational periodic pairs are supported, not rotational ones"), std::string::npos) << m;
    }
    // One side in two pairs
    {
        const std::string m = errorFor
        (
            "twice.geo",
            "solid left = plane(0, 0, 0; -1, 0, 0) -bcname=left;\n"
            "solid right = plane(1, 1, 1; 1, 0, 0) -bcname=right;\n"
            "solid front = plane(0, 0, 0; 0, -1, 0) -bcname=front;\n"
            "solid cube = left and right and front" + cube + ";\n"
            "identify periodic left right;\n"
            "identify periodic left front;\n"
            "tlo cube;\n"
        );
        EXPECT_NE(m.find("'identify periodic left front': the surface of left is in 'identify periodic left right' too"), std::string::npos) << m;
    }
    // A side between two regions, not on the boundary
    {
        const std::string m = errorFor
        (
            "between.geo",
            "solid l0 = plane(0, 0, 0; -1, 0, 0) -bcname=l0;\n"
            "solid mid = plane(1, 0, 0; 1, 0, 0);\n"
            "solid box1 = l0 and mid" + cube + ";\n"
            "solid box2 = not mid and plane(2, 0, 0; 1, 0, 0)" + cube + ";\n"
            "identify periodic l0 mid;\n"
            "tlo box1;\n"
            "tlo box2;\n"
        );
        EXPECT_NE(m.find("'identify periodic l0 mid': the surface of mid lies between two regions"), std::string::npos) << m;
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
        const std::string m = errorOf([&]{ checkStl(flipSolids({"body"}), f); });
        EXPECT_NE(m.find("sphereInBox.stl\": the closed surface of solid body (1280 triangles between ("), std::string::npos) << m;
        EXPECT_NE(m.find(") lies inside that of solids inlet, outlet, sides"), std::string::npos) << m;
        EXPECT_NE(m.find("Flip the normals of solid body"), std::string::npos) << m;
    }
    {
        const std::string m = errorOf([&]{ checkStl(flipSolids({"inlet", "outlet", "sides"}), f); });
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


// Touching shells are named, with a point, before Netgen sees them: a
// desk whose legs stand on the floor of its room and touch its top, and
// two cubes sharing a face.
TEST(stlReader, touchingShellsAreNamedWithAPoint)
{
    const std::string room = dataDir + "roomWithDesk.stl";
    const std::string m = errorOf([&] { checkStl(readStl(room), room); });
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
    const std::string c = errorOf([&] { checkStl(readStl(cubes), cubes); });
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
    const std::string m = errorOf([&] { checkStl(onFloor, "onFloor.stl"); });
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
    const std::string p = errorOf([&] { checkStl(sharing, "sharing.stl"); });
    EXPECT_NE(p.find("share the point at (0.5 0.5 0.501)"), std::string::npos) << p;
}
