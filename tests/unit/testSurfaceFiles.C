// The geometry's surface files: OpenFOAM's formats through triSurface (OBJ,
// VTK, gzip-compressed), patch names from groups or the file, and one
// surface made of several files.

#include "surfaceFiles.H"
#include "stlGeometry.H"
#include "domainBox.H"
#include "surfaceTopology.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <zlib.h>

#include <array>
#include <cmath>
#include <map>
#include <sstream>

using namespace pmsh;
using namespace pmsh::test;

namespace
{

//- The unit cube's corners and its 12 outward triangles, two a side,
//  sides named by where they are.
const std::vector<point3> cubePoints
{
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}
};
const std::vector<std::pair<std::string, std::array<triVerts, 2>>> cubeSides
{
    {"zMin", {{{0, 2, 1}, {0, 3, 2}}}},
    {"zMax", {{{4, 5, 6}, {4, 6, 7}}}},
    {"yMin", {{{0, 1, 5}, {0, 5, 4}}}},
    {"yMax", {{{3, 7, 6}, {3, 6, 2}}}},
    {"xMin", {{{0, 4, 7}, {0, 7, 3}}}},
    {"xMax", {{{1, 2, 6}, {1, 6, 5}}}}
};

//- The sides [first, last) as OBJ: each a group, or all without one.
std::string cubeObj(std::size_t first, std::size_t last, bool groups = true)
{
    std::ostringstream os;
    os.precision(17);
    os  << "# unit cube\no cube\n";
    for (const point3& p : cubePoints)
    {
        os  << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    }
    for (std::size_t s = first; s < last; ++s)
    {
        if (groups)
        {
            os  << "g " << cubeSides[s].first << '\n';
        }
        for (const triVerts& t : cubeSides[s].second)
        {
            os  << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
        }
    }
    return os.str();
}

//- The sides [first, last) as ascii STL, a solid each.
std::string cubeStl(std::size_t first, std::size_t last)
{
    std::ostringstream os;
    os.precision(17);
    for (std::size_t s = first; s < last; ++s)
    {
        os  << "solid " << cubeSides[s].first << '\n';
        for (const triVerts& t : cubeSides[s].second)
        {
            os  << "facet normal 0 0 0\nouter loop\n";
            for (label v : t)
            {
                const point3& p = cubePoints[v];
                os  << "vertex " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
            }
            os  << "endloop\nendfacet\n";
        }
        os  << "endsolid " << cubeSides[s].first << '\n';
    }
    return os.str();
}

std::string gzipped(const tempDir& dir, const std::string& name, const std::string& text)
{
    const std::string path = dir/name;
    gzFile out = gzopen(path.c_str(), "wb");
    EXPECT_TRUE(out != nullptr);
    EXPECT_EQ(gzwrite(out, text.data(), unsigned(text.size())), int(text.size()));
    gzclose(out);
    return path;
}

//- Triangles as sorted point triples with their patch name: the same for
//  two surfaces that differ only in the order of points and triangles.
std::multimap<std::string, std::array<point3, 3>> trianglesByPatch(const stlSurface& s)
{
    std::multimap<std::string, std::array<point3, 3>> out;
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        std::array<point3, 3> p;
        for (int k = 0; k < 3; ++k)
        {
            p[k] = s.points[s.triangles[t][k]];
        }
        // Rotate the lowest point first, keeping the turn
        int lo = 0;
        for (int k = 1; k < 3; ++k)
        {
            if (p[k] < p[lo]) lo = k;
        }
        std::rotate(p.begin(), p.begin() + lo, p.end());
        out.emplace(s.solidNames[s.solid[t]], p);
    }
    return out;
}

} // End anonymous namespace


TEST(surfaceFiles, anObjFileIsReadAsItsStlTwinWithGroupsAsPatches)
{
    const tempDir dir("surfaceFiles");
    const stlSurface obj = readSurfaceFile(dir.file("cube.obj", cubeObj(0, 6)));
    const stlSurface stl = readSurfaceFile(dir.file("cube.stl", cubeStl(0, 6)));
    EXPECT_EQ(obj.points.size(), 8u);
    EXPECT_EQ(obj.nTriangles(), 12);
    EXPECT_EQ(trianglesByPatch(obj), trianglesByPatch(stl));
    EXPECT_NO_THROW(checkStl(obj, "cube.obj"));
}


TEST(surfaceFiles, trianglesOutsideAnyGroupTakeTheFileStem)
{
    const tempDir dir("surfaceFiles");
    const stlSurface s = readSurfaceFile(dir.file("myBody.OBJ", cubeObj(0, 6, false)));
    EXPECT_EQ(s.solidNames, std::vector<std::string>{"myBody"});
}


TEST(surfaceFiles, aGzippedFileIsReadItselfNotTheUncompressedFileBesideIt)
{
    const tempDir dir("surfaceFiles");
    // body.obj (groups) beside body.obj.gz (none): OpenFOAM's IFstream
    // would read body.obj for either
    dir.file("body.obj", cubeObj(0, 6));
    const std::string gz = gzipped(dir, "body.obj.gz", cubeObj(0, 6, false));
    EXPECT_EQ(readSurfaceFile(gz).solidNames, std::vector<std::string>{"body"});
    EXPECT_EQ(surfaceFileType(gz), "obj");

    const std::string stlGz = gzipped(dir, "box.stl.gz", cubeStl(0, 6));
    EXPECT_EQ(trianglesByPatch(readSurfaceFile(stlGz)),
              trianglesByPatch(readSurfaceFile(dir.file("box.stl", cubeStl(0, 6)))));
}


TEST(surfaceFiles, aVtkFileIsReadByOpenFoam)
{
    const tempDir dir("surfaceFiles");
    std::ostringstream os;
    os  << "# vtk DataFile Version 2.0\ncube\nASCII\nDATASET POLYDATA\nPOINTS 8 double\n";
    for (const point3& p : cubePoints)
    {
        os  << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    }
    os  << "POLYGONS 12 48\n";
    for (const auto& side : cubeSides)
    {
        for (const triVerts& t : side.second)
        {
            os  << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
        }
    }
    const stlSurface s = readSurfaceFile(dir.file("part.vtk", os.str()));
    EXPECT_EQ(s.nTriangles(), 12);
    EXPECT_EQ(s.solidNames, std::vector<std::string>{"part"});
    EXPECT_NO_THROW(checkStl(s, "part.vtk"));
}


TEST(surfaceFiles, aClosedSurfaceInSeveralFilesOfSeveralFormatsIsOneSurface)
{
    const tempDir dir("surfaceFiles");
    const std::vector<std::string> files
    {
        dir.file("bottom.stl", cubeStl(0, 2)),
        dir.file("sides.obj", cubeObj(2, 4)),
        gzipped(dir, "rest.obj.gz", cubeObj(4, 6))
    };
    const stlSurface s = readSurfaceFiles(files);
    EXPECT_EQ(s.points.size(), 8u) << "the files' points are merged";
    EXPECT_EQ(trianglesByPatch(s), trianglesByPatch(readStl(dir.file("cube.stl", cubeStl(0, 6)))));
    EXPECT_NO_THROW(checkStl(s, describeSurfaceFiles(files)));
    EXPECT_EQ(describeSurfaceFiles(files),
              "surface files \"" + files[0] + "\", \"" + files[1] + "\" and \"" + files[2] + "\"");

    // Each file alone is open
    EXPECT_FATAL(stlGeometry({files[1]}), "OBJ file \"" + files[1] + "\" is not closed");
}


TEST(surfaceFiles, twoFilesWithThePatchNameStopNamingBoth)
{
    const tempDir dir("surfaceFiles");
    const std::string a = dir.file("a.stl", cubeStl(0, 3));
    const std::string b = dir.file("b.obj", cubeObj(2, 6));
    EXPECT_FATAL(readSurfaceFiles({a, b}),
                 "Surface files \"" + a + "\" and \"" + b + "\" both have a patch named 'yMin'");
}


TEST(surfaceFiles, unreadableFilesNameTheFileAndTheValidTypes)
{
    const tempDir dir("surfaceFiles");
    const std::string bad = dir.file("bad.obj", "v 0 0 0\nf 1 2 3\n");
    EXPECT_FATAL(readSurfaceFile(bad), "bad.obj");
    EXPECT_FATAL(Geometry::New(dir.file("body.step", "ISO-10303-21;")),
                 "Unknown geometry file type \"" + (dir/"body.step") + "\"");
    EXPECT_FATAL(Geometry::New(dir.file("body.step", "ISO-10303-21;")), ".obj");
    EXPECT_FALSE(canReadSurfaceFile("body.step"));
    EXPECT_TRUE(canReadSurfaceFile("body.VTK.gz"));
    const std::string geo = dir.file("shape.geo", "algebraic3d\nsolid s = sphere (0, 0, 0; 1);\ntlo s;\n");
    EXPECT_FATAL(Geometry::New(std::vector<std::string>{geo, dir.file("b.stl", cubeStl(0, 6))}),
                 "a CSG geometry is one file");
}


// * * * * * * * * * * * * * * * Domain box  * * * * * * * * * * * * * * * //

namespace
{

domainBox boxAround(double lo, double hi)
{
    domainBox box;
    box.given = true;
    box.min = {lo, lo, lo};
    box.max = {hi, hi, hi};
    box.sideNames = {"inlet", "outlet", "sides", "sides", "sides", "sides"};
    return box;
}

double volumeOfSolid(const stlSurface& s, const std::string& name)
{
    double v6 = 0;
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        if (s.solidNames[s.solid[t]] == name)
        {
            const triVerts& f = s.triangles[t];
            v6 += tetVolume6({0, 0, 0}, s.points[f[0]], s.points[f[1]], s.points[f[2]]);
        }
    }
    return v6/6;
}


double areaOfSolid(const stlSurface& s, const std::string& name)
{
    double area = 0;
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        if (s.solidNames[s.solid[t]] == name)
        {
            area += 0.5*std::sqrt(magSqr(s.areaNormal(t)));
        }
    }
    return area;
}

//- An octahedron (solid "tip") of radius 1 standing on its tip at the
//  origin.
stlSurface octahedronOnItsTip()
{
    stlSurface tip;
    tip.points = {{0, 0, 0}, {1, 0, 1}, {0, 1, 1}, {-1, 0, 1}, {0, -1, 1}, {0, 0, 2}};
    tip.triangles = {{0, 2, 1}, {0, 3, 2}, {0, 4, 3}, {0, 1, 4},
                     {5, 1, 2}, {5, 2, 3}, {5, 3, 4}, {5, 4, 1}};
    tip.solid.assign(8, 0);
    tip.solidNames = {"tip"};
    return tip;
}

} // End anonymous namespace


TEST(domainBox, aBodyOfEitherOrientationEndsPointingOutOfTheFluid)
{
    const tempDir dir("domainBox");
    stlSurface outward = readSurfaceFile(dir.file("body.obj", cubeObj(0, 6, false)));
    stlSurface inward = outward;
    for (triVerts& t : inward.triangles)
    {
        std::swap(t[1], t[2]);
    }
    for (stlSurface* s : {&outward, &inward})
    {
        putBodiesInDomain(*s, boxAround(-1, 2), "OBJ file \"body.obj\"");
        EXPECT_EQ(s->solidNames, (std::vector<std::string>{"body", "inlet", "outlet", "sides"}));
        EXPECT_NEAR(volumeOfSolid(*s, "body"), -1, 1e-12) << "into the body";
        EXPECT_NEAR(volumeOfSolid(*s, "inlet") + volumeOfSolid(*s, "outlet")
                  + volumeOfSolid(*s, "sides"), 27, 1e-12) << "the box outward";
        EXPECT_EQ(s->points.size(), 16u);
        EXPECT_NO_THROW(checkStl(*s, "body.obj"));
    }
    EXPECT_EQ(outward.triangles, inward.triangles);
}


TEST(domainBox, aBodyThroughTheBoxIsCutOutOfItAndKeepsItsPatchesInside)
{
    // The unit cube through the corner of a box from 0.5 to 2: the fluid is
    // the box less the cube's eighth inside it
    const tempDir dir("domainBox");
    stlSurface s = readSurfaceFile(dir.file("cube.obj", cubeObj(0, 6)));
    putBodiesInDomain(s, boxAround(0.5, 2), "OBJ file \"cube.obj\"");
    EXPECT_NO_THROW(checkStl(s, "cube.obj"));
    EXPECT_NEAR(enclosedVolume(s), 1.5*1.5*1.5 - 0.5*0.5*0.5, 1e-12);
    // The cube's sides at 0 lie outside the box: no patch; those at 1 are
    // cut to their quarter inside it, facing into the cube
    EXPECT_EQ(s.solidNames, (std::vector<std::string>{"zMax", "yMax", "xMax", "inlet",
                                                      "outlet", "sides"}));
    EXPECT_NEAR(areaOfSolid(s, "zMax"), 0.25, 1e-12);
    EXPECT_NEAR(volumeOfSolid(s, "zMax"), -0.25/3, 1e-12) << "into the cube";
    EXPECT_NEAR(areaOfSolid(s, "inlet"), 1.5*1.5 - 0.25, 1e-12) << "the cube's footprint cut out";
    EXPECT_NEAR(areaOfSolid(s, "outlet"), 1.5*1.5, 1e-12);
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        for (label v : s.triangles[t])
        {
            for (int k = 0; k < 3; ++k)
            {
                ASSERT_GE(s.points[v][k], 0.5) << "a point outside the box";
            }
        }
    }
}


TEST(domainBox, aBodyOnAPlinthMeetsTheSideAtRightAnglesInsteadOfTouchingIt)
{
    // The octahedron standing on its tip on the floor, on a plinth 0.1
    // high: its part below z = 0.1 (a pyramid) replaced
    // by the section there (a square of area 2*0.1^2) drawn down through
    // the floor
    stlSurface tip = octahedronOnItsTip();
    domainBox floor = boxAround(-3, 3);
    floor.min[2] = 0;
    floor.plinthHeight = 0.1;
    putBodiesInDomain(tip, floor, "the octahedron");
    EXPECT_NO_THROW(checkStl(tip, "the octahedron"));

    const double h = floor.plinthHeight;
    const double body = 4.0/3 - 2.0/3*h*h*h + 2*h*h*h;
    EXPECT_NEAR(enclosedVolume(tip), 6*6*3 - body, 1e-10);
    // The plinth's walls (the tip's patch) stand upright on the floor
    label nOnFloor = 0;
    for (label t = 0; t < tip.nTriangles(); ++t)
    {
        const triVerts& f = tip.triangles[t];
        const bool touches = tip.points[f[0]][2] == 0 || tip.points[f[1]][2] == 0
                          || tip.points[f[2]][2] == 0;
        if (tip.solidNames[tip.solid[t]] == "tip" && touches)
        {
            const vector3 n = tip.areaNormal(t);
            EXPECT_NEAR(n[2], 0, 1e-12*std::sqrt(magSqr(n)));
            ++nOnFloor;
        }
    }
    EXPECT_GE(nOnFloor, 4);
    EXPECT_NEAR(areaOfSolid(tip, "sides"), 2*6*3 + 2*6*6 - 2*h*h, 1e-12)
        << "the plinth's footprint cut out of the floor";
}


TEST(domainBox, aCavityThatTheFloorClosesOffIsLeftOutOfTheFluid)
{
    // A cup upside down through the floor, as the inside of a wheel's
    // wrap open only below the road: the box (2 wide, z -1..1) less a
    // cavity (1 wide, z -1..0.5) open at its bottom. The floor at z = 0
    // closes the cavity's upper part off from the rest of the fluid.
    stlSurface cup;
    for (int k = 0; k < 2; ++k)
    {
        for (int j = 0; j < 2; ++j)
        {
            for (int i = 0; i < 2; ++i)
            {
                cup.points.push_back({2.0*i - 1, 2.0*j - 1, 2.0*k - 1});
            }
        }
    }
    for (int k = 0; k < 2; ++k)
    {
        for (int j = 0; j < 2; ++j)
        {
            for (int i = 0; i < 2; ++i)
            {
                cup.points.push_back({i - 0.5, j - 0.5, k ? 0.5 : -1.0});
            }
        }
    }
    const auto o = [](int i, int j, int k) { return label(i + 2*j + 4*k); };
    const auto c = [](int i, int j, int k) { return label(8 + i + 2*j + 4*k); };
    // Each quad round its normal, out of the cup's material
    const std::vector<std::array<label, 4>> quads
    {
        {o(0, 0, 1), o(1, 0, 1), o(1, 1, 1), o(0, 1, 1)},
        {o(0, 0, 0), o(0, 0, 1), o(0, 1, 1), o(0, 1, 0)},
        {o(1, 0, 0), o(1, 1, 0), o(1, 1, 1), o(1, 0, 1)},
        {o(0, 0, 0), o(1, 0, 0), o(1, 0, 1), o(0, 0, 1)},
        {o(0, 1, 0), o(0, 1, 1), o(1, 1, 1), o(1, 1, 0)},
        {o(0, 0, 0), c(0, 0, 0), c(1, 0, 0), o(1, 0, 0)},      // the rim
        {o(1, 0, 0), c(1, 0, 0), c(1, 1, 0), o(1, 1, 0)},
        {o(1, 1, 0), c(1, 1, 0), c(0, 1, 0), o(0, 1, 0)},
        {o(0, 1, 0), c(0, 1, 0), c(0, 0, 0), o(0, 0, 0)},
        {c(0, 0, 0), c(0, 1, 0), c(0, 1, 1), c(0, 0, 1)},      // the cavity
        {c(1, 0, 0), c(1, 0, 1), c(1, 1, 1), c(1, 1, 0)},
        {c(0, 0, 0), c(0, 0, 1), c(1, 0, 1), c(1, 0, 0)},
        {c(0, 1, 0), c(1, 1, 0), c(1, 1, 1), c(0, 1, 1)},
        {c(0, 0, 1), c(0, 1, 1), c(1, 1, 1), c(1, 0, 1)}
    };
    for (const auto& q : quads)
    {
        cup.triangles.push_back({q[0], q[1], q[2]});
        cup.triangles.push_back({q[0], q[2], q[3]});
    }
    cup.solid.assign(cup.triangles.size(), 0);
    cup.solidNames = {"cup"};
    domainBox floor = boxAround(-3, 3);
    floor.min[2] = 0;
    putBodiesInDomain(cup, floor, "the cup");
    EXPECT_NO_THROW(checkStl(cup, "the cup"));
    // The box less the cup above the floor (4 less its cavity's 0.5) and
    // less the pocket (0.5): one shell
    EXPECT_NEAR(enclosedVolume(cup), 6*6*3 - 3.5 - 0.5, 1e-10);
    label nShells = 0;
    surfaceShells(label(cup.points.size()), cup.triangles, nShells);
    EXPECT_EQ(nShells, 1);
}


TEST(domainBox, aBodyTouchingTheBoxAtAPointOrWhollyOutsideOrAPatchOfASideStopsNamingThem)
{
    const tempDir dir("domainBox");
    // An octahedron standing on its tip on the box's floor: the fluid
    // would end in a wedge of zero angle there
    stlSurface tip = octahedronOnItsTip();
    domainBox floor = boxAround(-3, 3);
    floor.min[2] = 0;
    EXPECT_FATAL(putBodiesInDomain(tip, floor, "the octahedron"),
                 "The bodies of the octahedron touch the domain box from (-3 -3 0) to"
                 " (3 3 3) along a line or at a point (0 0 0)");

    const stlSurface body = readSurfaceFile(dir.file("cube.obj", cubeObj(0, 6)));
    stlSurface s = body;
    EXPECT_FATAL(putBodiesInDomain(s, boxAround(2, 3), "OBJ file \"cube.obj\""),
                 "Solid zMin of OBJ file \"cube.obj\" lies outside the domain box from"
                 " (2 2 2) to (3 3 3), at (0 0 0)");
    domainBox named = boxAround(-1, 2);
    named.sideNames[0] = "xMax";
    s = body;
    EXPECT_FATAL(putBodiesInDomain(s, named, "OBJ file \"cube.obj\""),
                 "The domain box's side xMin is patch 'xMax', which is also a body's patch");
}
