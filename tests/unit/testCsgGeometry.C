// Geometry from CSG (.geo): coarse meshes through Netgen (and HXT's fill of
// Netgen's surface), patch names from bcnames and solids, projection onto
// surfaces and edges, periodic pairs, and the input errors.

#include "geometryTests.H"
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
