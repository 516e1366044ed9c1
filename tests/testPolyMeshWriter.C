/*---------------------------------------------------------------------------*\
  pmshFoam tests: the FoamFile writers and writePolyMesh.

  Round trips through the strict test reader (ascii and binary, labels 32
  and 64 bits), the exact list encodings, the boundary file, label
  overflow, and the real OpenFOAM checkMesh on written cases.
\*---------------------------------------------------------------------------*/

#include "foamFile.H"
#include "polyMeshWriter.H"
#include "tetsToPolyMesh.H"
#include "foamFileReader.H"
#include "testMeshes.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

using namespace pmsh;
using namespace pmsh::test;
namespace fs = std::filesystem;

namespace
{

// * * * * * * * * * * * * * * * Test meshes * * * * * * * * * * * * * * * //

//- Kuhn grid (kuhnGridAt). The points are perturbed off round decimals so
//  the digits written matter.
tetMesh kuhnGrid(int nx, int ny, int nz, double jiggle = 0)
{
    return kuhnGridAt
    (
        nx, ny, nz,
        [jiggle](int i, int j, int k)
        {
            const double s = jiggle*std::sin(1.0 + i + 3*j + 7*k);
            return point{i/3.0 + s, j/7.0 + s, k*0.1 + s};
        }
    );
}


std::vector<polyPatchInfo> boxPatches()
{
    std::vector<polyPatchInfo> patches(4);
    patches[0].name = "inlet";
    patches[0].type = "patch";
    patches[1].name = "outlet";
    patches[1].type = "patch";
    patches[2].name = "unused";
    patches[2].type = "wall";
    patches[3].name = "walls";
    patches[3].type = "wall";
    return patches;
}


//- The PolyMesh of rank `rank` of m split into x-slabs of boxes (nRanks 1:
//  serial), or with tets scattered over the ranks. Boundary faces:
//  x = min -> inlet, x = max -> outlet, else walls.
PolyMesh rankMesh
(
    const tetMesh& m,
    int nx,
    int rank,
    int nRanks,
    bool scatter = false
)
{
    const bool serial = nRanks == 1;
    std::vector<int> tetRank(m.tets.size());
    for (std::size_t t = 0; t < tetRank.size(); ++t)
    {
        tetRank[t] = scatter ? int((t*7 + t/5) % nRanks) : int((t/6) % nx)*nRanks/nx;
    }
    auto region = [](const point& c, const point& lo, const point& hi)
    {
        // Faces on the x = const ends (jiggle is 0 for the checkMesh cases)
        const double eps = 1e-12;
        return label(std::abs(c[0] - lo[0]) < eps ? 0 : std::abs(c[0] - hi[0]) < eps ? 1 : 3);
    };
    rankInput in = makeRankInput(m, tetRank, rank, region);
    if (serial)
    {
        // Local points scrambled all the same, but no global point ids
        in.globalIds.clear();
    }
    return build(in, boxPatches(), serial ? -1 : rank);
}


// * * * * * * * * * * * * * * * * Utilities * * * * * * * * * * * * * * * //

foamFileFormat format(bool binary, int labelBits, int precision = 6)
{
    foamFileFormat fmt;
    fmt.binary = binary;
    fmt.labelBits = labelBits;
    fmt.precision = precision;
    return fmt;
}


template<class T>
std::string rawBytes(const std::vector<T>& v)
{
    return std::string(reinterpret_cast<const char*>(v.data()), v.size()*sizeof(T));
}


// Relative difference allowed after a 15-significant-digit round trip
constexpr double digits15 = 5.01e-15;

} // End anonymous namespace


// * * * * * * * * * * * * * * * Round trips * * * * * * * * * * * * * * * //

class polyMeshRoundTrip
:
    public ::testing::TestWithParam<std::tuple<bool, int>>
{};


TEST_P(polyMeshRoundTrip, readsBackWhatWasWritten)
{
    const bool binary = std::get<0>(GetParam());
    const int labelBits = std::get<1>(GetParam());
    const foamFileFormat fmt = format(binary, labelBits, 6);

    const tetMesh m = kuhnGrid(4, 2, 2, 1e-3);
    const PolyMesh mesh = rankMesh(m, 4, 1, 2);
    ASSERT_GT(mesh.patches.size(), boxPatches().size()) << "no processor patch";

    tempDir tmp("case");
    const std::string dir = tmp / "processor1/constant/polyMesh";
    writePolyMesh(dir, mesh, fmt, "processor1/constant/polyMesh");

    const std::string arch = labelBits == 32
        ? "LSB;label=32;scalar=64" : "LSB;label=64;scalar=64";

    // Headers
    for (const char* name : {"points", "faces", "owner", "neighbour", "boundary"})
    {
        const pmshTest::foamFile f = pmshTest::readFoamFile(dir + "/" + name);
        EXPECT_EQ(f.header.at("version"), "2.0") << name;
        const bool binaryFile = binary && std::string(name) != "boundary";
        EXPECT_EQ(f.header.at("format"), binaryFile ? "binary" : "ascii") << name;
        EXPECT_EQ(f.header.at("arch"), arch) << name;
        EXPECT_EQ(f.header.at("object"), name);
        EXPECT_EQ(f.header.at("location"), "processor1/constant/polyMesh") << name;
    }

    // points: bit-exact in binary, 15 digits in ascii (despite precision 6)
    const pmshTest::foamFile pf = pmshTest::readFoamFile(dir + "/points");
    EXPECT_EQ(pf.header.at("class"), "vectorField");
    const auto points = pmshTest::readVectorField(pf);
    ASSERT_EQ(points.size(), mesh.points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
    {
        for (int d = 0; d < 3; ++d)
        {
            if (binary)
            {
                EXPECT_EQ(std::memcmp(&points[i][d], &mesh.points[i][d], 8), 0) << i;
            }
            else
            {
                EXPECT_LE
                (
                    std::abs(points[i][d] - mesh.points[i][d]),
                    digits15*std::abs(mesh.points[i][d])
                ) << "point " << i;
            }
        }
    }

    // faces
    const pmshTest::foamFile ff = pmshTest::readFoamFile(dir + "/faces");
    EXPECT_EQ(ff.header.at("class"), binary ? "faceCompactList" : "faceList");
    const auto faces = pmshTest::readFaces(ff);
    ASSERT_EQ(faces.size(), mesh.faces.size());
    for (std::size_t i = 0; i < faces.size(); ++i)
    {
        ASSERT_EQ(faces[i].size(), 3u);
        for (int k = 0; k < 3; ++k)
        {
            EXPECT_EQ(faces[i][k], mesh.faces[i][k]);
        }
    }

    // owner, neighbour and their note
    const std::string note = "nPoints:" + std::to_string(mesh.points.size())
        + "  nCells:" + std::to_string(mesh.nCells)
        + "  nFaces:" + std::to_string(mesh.faces.size())
        + "  nInternalFaces:" + std::to_string(mesh.neighbour.size());
    for (const char* name : {"owner", "neighbour"})
    {
        const pmshTest::foamFile f = pmshTest::readFoamFile(dir + "/" + name);
        EXPECT_EQ(f.header.at("class"), "labelList");
        EXPECT_EQ(f.header.at("note"), note);
        const auto labels = pmshTest::readLabelList(f);
        const auto& expected = std::string(name) == "owner" ? mesh.owner : mesh.neighbour;
        ASSERT_EQ(labels.size(), expected.size());
        EXPECT_TRUE(std::equal(labels.begin(), labels.end(), expected.begin())) << name;
    }

    // boundary
    const auto patches = pmshTest::readBoundary(pmshTest::readFoamFile(dir + "/boundary"));
    ASSERT_EQ(patches.size(), mesh.patches.size());
    for (std::size_t i = 0; i < patches.size(); ++i)
    {
        EXPECT_EQ(patches[i].name, mesh.patches[i].name);
        EXPECT_EQ(patches[i].entries.at("nFaces"), std::to_string(mesh.patches[i].size));
        EXPECT_EQ(patches[i].entries.at("startFace"), std::to_string(mesh.patches[i].start));
    }
}


INSTANTIATE_TEST_SUITE_P
(
    formats,
    polyMeshRoundTrip,
    ::testing::Combine(::testing::Bool(), ::testing::Values(32, 64)),
    [](const ::testing::TestParamInfo<std::tuple<bool, int>>& info)
    {
        return std::string(std::get<0>(info.param) ? "binary" : "ascii")
            + "Label" + std::to_string(std::get<1>(info.param));
    }
);


TEST(foamFile, asciiPointsHaveAtLeast15DigitsWhateverThePrecision)
{
    tempDir tmp("pts");
    const std::vector<point> pts = {{1.0/3, 2.0/3, -1e-20/3}};
    writePointFieldFile(tmp / "points", pts, format(false, 32, 3), "constant/polyMesh");

    const pmshTest::foamFile f = pmshTest::readFoamFile(tmp / "points");
    EXPECT_NE(f.body.find("0.333333333333333"), std::string::npos) << f.body;
    const auto back = pmshTest::readVectorField(f);
    ASSERT_EQ(back.size(), 1u);
    for (int d = 0; d < 3; ++d)
    {
        EXPECT_LE(std::abs(back[0][d] - pts[0][d]), digits15*std::abs(pts[0][d]));
    }

    // A higher precision is honoured
    writePointFieldFile(tmp / "points17", pts, format(false, 32, 17), "constant/polyMesh");
    const auto back17 = pmshTest::readVectorFieldFile(tmp / "points17");
    ASSERT_EQ(back17.size(), 1u);
    EXPECT_EQ(back17[0], pts[0]);
}


TEST(foamFile, asciiFacesAreOneFacePerLine)
{
    tempDir tmp("faces");
    writeFaceListFile(tmp / "faces", {{0, 1, 2}, {2, 1, 30}}, format(false, 32), "constant/polyMesh");
    const pmshTest::foamFile f = pmshTest::readFoamFile(tmp / "faces");
    EXPECT_EQ(f.header.at("class"), "faceList");
    EXPECT_EQ(f.body, "2\n(\n3(0 1 2)\n3(2 1 30)\n)");
}


// * * * * * * * * * * * * * * * Encodings * * * * * * * * * * * * * * * * //

TEST(foamFile, emptyListsAreBareZeroInBinaryAndZeroParensInAscii)
{
    tempDir tmp("empty");
    for (int bits : {32, 64})
    {
        writeLabelListFile(tmp / "b", std::vector<label>(), format(true, bits), "constant/polyMesh");
        const pmshTest::foamFile b = pmshTest::readFoamFile(tmp / "b");
        EXPECT_EQ(b.body, "0");
        EXPECT_NE(b.data.find("\n0\n"), std::string::npos);
        EXPECT_TRUE(pmshTest::readLabelList(b).empty());

        writeLabelListFile(tmp / "a", std::vector<label>(), format(false, bits), "constant/polyMesh");
        const pmshTest::foamFile a = pmshTest::readFoamFile(tmp / "a");
        EXPECT_EQ(a.body, "0()");
        EXPECT_TRUE(pmshTest::readLabelList(a).empty());
    }

    writePointFieldFile(tmp / "p", {}, format(true, 32), "constant/polyMesh");
    EXPECT_EQ(pmshTest::readFoamFile(tmp / "p").body, "0");
    writePointFieldFile(tmp / "q", {}, format(false, 32), "constant/polyMesh");
    EXPECT_EQ(pmshTest::readFoamFile(tmp / "q").body, "0()");

    // No faces: offsets list (0) then an empty vertex list
    writeFaceListFile(tmp / "f", {}, format(true, 32), "constant/polyMesh");
    const pmshTest::foamFile f = pmshTest::readFoamFile(tmp / "f");
    EXPECT_EQ(f.body, "1\n(" + rawBytes(std::vector<std::int32_t>{0}) + ")\n0");
    EXPECT_TRUE(pmshTest::readFaces(f).empty());
}


TEST(foamFile, binaryListIsNewlineSizeNewlineParenRawBytesParen)
{
    tempDir tmp("layout");
    const std::vector<label> labels = {1, -2, 2147483647};

    writeLabelListFile(tmp / "l32", labels, format(true, 32), "constant/polyMesh");
    const pmshTest::foamFile f32 = pmshTest::readFoamFile(tmp / "l32");
    EXPECT_EQ(f32.body, "3\n(" + rawBytes(labels) + ")");
    EXPECT_NE(f32.data.find("\n3\n("), std::string::npos);

    writeLabelListFile(tmp / "l64", labels, format(true, 64), "constant/polyMesh");
    const pmshTest::foamFile f64 = pmshTest::readFoamFile(tmp / "l64");
    const std::vector<std::int64_t> wide(labels.begin(), labels.end());
    EXPECT_EQ(f64.body, "3\n(" + rawBytes(wide) + ")");
    EXPECT_EQ(f64.header.at("arch"), "LSB;label=64;scalar=64");

    const std::vector<point> pts = {{0.1, 0.2, 0.3}, {-1, 1e300, 5e-324}};
    writePointFieldFile(tmp / "p", pts, format(true, 32), "constant/polyMesh");
    EXPECT_EQ(pmshTest::readFoamFile(tmp / "p").body, "2\n(" + rawBytes(pts) + ")");

    // faceCompactList: offsets 0 3 6, then the 6 vertex labels
    const std::vector<triFace> faces = {{0, 1, 2}, {3, 4, 5}};
    writeFaceListFile(tmp / "f", faces, format(true, 64), "constant/polyMesh");
    const pmshTest::foamFile ff = pmshTest::readFoamFile(tmp / "f");
    EXPECT_EQ(ff.header.at("class"), "faceCompactList");
    EXPECT_EQ
    (
        ff.body,
        "3\n(" + rawBytes(std::vector<std::int64_t>{0, 3, 6}) + ")"
        "\n6\n(" + rawBytes(std::vector<std::int64_t>{0, 1, 2, 3, 4, 5}) + ")"
    );
}


TEST(foamFile, asciiLabelListIsMultiLine)
{
    tempDir tmp("ascii");
    writeLabelListFile(tmp / "l", std::vector<globalLabel>{5, -1, 7}, format(false, 32), "");
    const pmshTest::foamFile f = pmshTest::readFoamFile(tmp / "l");
    EXPECT_EQ(f.body, "3\n(\n5\n-1\n7\n)");
    EXPECT_EQ(f.header.count("location"), 0u);
    EXPECT_EQ(f.header.at("object"), "l");
}


TEST(foamFile, largeListsRoundTripThroughTheBuffer)
{
    // More than one buffer's worth in every path (binary, width change, ascii)
    tempDir tmp("large");
    std::vector<label> labels(700000);
    for (std::size_t i = 0; i < labels.size(); ++i)
    {
        labels[i] = label(i*2654435761u % 1000003) - 500000;
    }
    for (bool binary : {false, true})
    {
        for (int bits : {32, 64})
        {
            writeLabelListFile(tmp / "l", labels, format(binary, bits), "constant/polyMesh");
            const auto back = pmshTest::readLabelListFile(tmp / "l");
            ASSERT_EQ(back.size(), labels.size());
            EXPECT_TRUE(std::equal(back.begin(), back.end(), labels.begin()))
                << (binary ? "binary " : "ascii ") << bits;
        }
    }
}


// * * * * * * * * * * * * * * * Label overflow * * * * * * * * * * * * * * //

TEST(foamFile, labelAbove32BitsIsAnErrorWithLabelSize32)
{
    tempDir tmp("overflow");
    const globalLabel big = globalLabel(std::numeric_limits<std::int32_t>::max()) + 1;
    const globalLabel small = globalLabel(std::numeric_limits<std::int32_t>::min()) - 1;

    for (bool binary : {false, true})
    {
        for (globalLabel bad : {big, small})
        {
            const std::string path = tmp / "cellProcAddressing";
            const std::string e = errorOf
            (
                [&]()
                {
                    writeLabelListFile
                    (
                        path, std::vector<globalLabel>{0, bad, 1},
                        format(binary, 32), "constant/polyMesh"
                    );
                }
            );
            EXPECT_NE(e.find(std::to_string(bad)), std::string::npos) << e;
            EXPECT_NE(e.find("label size 64"), std::string::npos) << e;
            EXPECT_NE(e.find(path), std::string::npos) << e;
            EXPECT_FALSE(fs::exists(path)) << "a truncated file was left behind";
        }
    }

    // The 32-bit limits themselves are fine, and 64 bits take the big ones
    const std::vector<globalLabel> edge =
        {std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::min()};
    for (bool binary : {false, true})
    {
        writeLabelListFile(tmp / "edge", edge, format(binary, 32), "constant/polyMesh");
        const auto backEdge = pmshTest::readLabelListFile(tmp / "edge");
        EXPECT_TRUE(std::equal(edge.begin(), edge.end(), backEdge.begin(), backEdge.end()));

        const std::vector<globalLabel> wide = {big, small, 5000000000LL};
        writeLabelListFile(tmp / "wide", wide, format(binary, 64), "constant/polyMesh");
        const auto backWide = pmshTest::readLabelListFile(tmp / "wide");
        EXPECT_TRUE(std::equal(wide.begin(), wide.end(), backWide.begin(), backWide.end()));
    }
}


TEST(foamFile, unwritablePathIsAnErrorNamingTheFile)
{
    tempDir tmp("unwritable");
    const std::string path = tmp / "no/such/dir/owner";
    const std::string e = errorOf
    (
        [&]() { writeLabelListFile(path, std::vector<label>{1}, format(false, 32), ""); }
    );
    EXPECT_NE(e.find(path), std::string::npos) << e;

    // A file where the polyMesh directory should be
    std::ofstream(tmp / "blocker") << "x";
    const std::string e2 = errorOf
    (
        [&]()
        {
            writePolyMesh
            (
                tmp / "blocker/polyMesh", rankMesh(kuhnGrid(1, 1, 1), 1, 0, 1),
                format(false, 32), "constant/polyMesh"
            );
        }
    );
    EXPECT_NE(e2.find("blocker"), std::string::npos) << e2;
}


TEST(foamFile, unsupportedLabelSizeIsAnError)
{
    tempDir tmp("bits");
    const std::string e = errorOf
    (
        [&]() { writeLabelListFile(tmp / "x", std::vector<label>{1}, format(false, 16), ""); }
    );
    EXPECT_NE(e.find("label size 16"), std::string::npos) << e;
}


// * * * * * * * * * * * * * * * * * boundary * * * * * * * * * * * * * * * //

TEST(polyMeshWriter, boundaryIsAsciiWithProcessorAndWallEntries)
{
    const tetMesh m = kuhnGrid(3, 1, 1);
    const PolyMesh mesh = rankMesh(m, 3, 1, 3);
    tempDir tmp("boundary");
    writePolyMesh(tmp / "polyMesh", mesh, format(true, 64), "processor1/constant/polyMesh");

    const pmshTest::foamFile f = pmshTest::readFoamFile(tmp / "polyMesh/boundary");
    EXPECT_EQ(f.header.at("format"), "ascii");
    EXPECT_EQ(f.header.at("class"), "polyBoundaryMesh");
    EXPECT_EQ(f.header.at("arch"), "LSB;label=64;scalar=64");

    const auto patches = pmshTest::readBoundary(f);
    ASSERT_EQ(patches.size(), 6u);

    const std::vector<std::string> names =
        {"inlet", "outlet", "unused", "walls", "procBoundary1to0", "procBoundary1to2"};
    label start = mesh.nInternalFaces();
    for (std::size_t i = 0; i < patches.size(); ++i)
    {
        const auto& e = patches[i].entries;
        EXPECT_EQ(patches[i].name, names[i]);
        EXPECT_EQ(e.at("startFace"), std::to_string(start)) << names[i];
        start += std::stoi(e.at("nFaces"));
    }
    EXPECT_EQ(start, mesh.nFaces());

    // Rank 1 of 3 touches neither end: inlet and outlet are empty but present
    EXPECT_EQ(patches[0].entries.at("type"), "patch");
    EXPECT_EQ(patches[0].entries.at("nFaces"), "0");
    EXPECT_EQ(patches[0].entries.count("inGroups"), 0u);
    EXPECT_EQ(patches[1].entries.at("nFaces"), "0");
    EXPECT_EQ(patches[2].entries.at("nFaces"), "0");

    EXPECT_EQ(patches[3].entries.at("type"), "wall");
    EXPECT_EQ(patches[3].entries.at("inGroups"), "1(wall)");

    for (std::size_t i : {4u, 5u})
    {
        const auto& e = patches[i].entries;
        EXPECT_EQ(e.at("type"), "processor");
        EXPECT_EQ(e.at("inGroups"), "1(processor)");
        EXPECT_EQ(e.at("matchTolerance"), "0.0001");
        EXPECT_EQ(e.at("transform"), "unknown");
        EXPECT_EQ(e.at("myProcNo"), "1");
        EXPECT_EQ(e.at("neighbProcNo"), i == 4 ? "0" : "2");
        EXPECT_NE(e.at("nFaces"), "0");
        EXPECT_EQ(e.size(), 8u);
    }
}


TEST(polyMeshWriter, inconsistentPatchLayoutIsNotWritten)
{
    PolyMesh mesh = rankMesh(kuhnGrid(1, 1, 1), 1, 0, 1);
    mesh.patches[1].start += 1;
    tempDir tmp("layout");
    const std::string e = errorOf
    (
        [&]() { writePolyMesh(tmp / "polyMesh", mesh, format(false, 32), "constant/polyMesh"); }
    );
    EXPECT_NE(e.find("outlet"), std::string::npos) << e;
    EXPECT_FALSE(fs::exists(tmp / "polyMesh/points"));
}


// * * * * * * * * * * * * * * * Real checkMesh * * * * * * * * * * * * * * //

namespace
{

std::string findOnPath(const std::string& exe)
{
    const char* path = std::getenv("PATH");
    std::istringstream is(path ? path : "");
    for (std::string dir; std::getline(is, dir, ':'); )
    {
        const std::string f = (dir.empty() ? "." : dir) + "/" + exe;
        if (::access(f.c_str(), X_OK) == 0)
        {
            return f;
        }
    }
    return "";
}


void writeDict(const std::string& path, const std::string& text)
{
    foamOFstream os(path, format(false, 32));
    os.writeHeader({"dictionary", "system", fileNameOf(path), ""});
    os.writeText(text);
    os.close();
}


//- The system/ dictionaries checkMesh v1912 reads (it builds an fvMesh, so
//  it needs fvSchemes and fvSolution as well as controlDict; in parallel
//  also decomposeParDict).
void writeSystemDicts(const std::string& caseDir, int nRanks = 1)
{
    fs::create_directories(caseDir + "/system");
    writeDict
    (
        caseDir + "/system/controlDict",
        "application     pmshFoam;\n"
        "startFrom       startTime;\n"
        "startTime       0;\n"
        "stopAt          endTime;\n"
        "endTime         1;\n"
        "deltaT          1;\n"
        "writeControl    timeStep;\n"
        "writeInterval   1;\n"
    );
    writeDict
    (
        caseDir + "/system/fvSchemes",
        "ddtSchemes { default Euler; }\n"
        "gradSchemes { default Gauss linear; }\n"
        "divSchemes { default none; }\n"
        "laplacianSchemes { default Gauss linear corrected; }\n"
        "interpolationSchemes { default linear; }\n"
        "snGradSchemes { default corrected; }\n"
    );
    writeDict(caseDir + "/system/fvSolution", "");
    if (nRanks > 1)
    {
        writeDict
        (
            caseDir + "/system/decomposeParDict",
            "numberOfSubdomains " + std::to_string(nRanks) + ";\n"
            "method          scotch;\n"
        );
    }
}

} // End anonymous namespace


class realCheckMesh
:
    public ::testing::TestWithParam<std::tuple<bool, int>>
{};


TEST_P(realCheckMesh, sixTetCubeAndGridAreMeshOK)
{
    ASSERT_FALSE(findOnPath("checkMesh").empty())
        << "checkMesh is not on PATH: the project needs the OpenFOAM binaries"
           " (Debian package openfoam, /usr/bin/checkMesh) for this test";

    const foamFileFormat fmt =
        format(std::get<0>(GetParam()), std::get<1>(GetParam()));

    struct meshCase { std::string name; int nx, ny, nz; };
    for (const meshCase& mc : {meshCase{"cube", 1, 1, 1}, meshCase{"grid", 4, 3, 2}})
    {
        tempDir tmp(mc.name);
        const std::string caseDir = tmp.path();
        writeSystemDicts(caseDir);
        const PolyMesh mesh = rankMesh(kuhnGrid(mc.nx, mc.ny, mc.nz), mc.nx, 0, 1);
        writePolyMesh(caseDir + "/constant/polyMesh", mesh, fmt, "constant/polyMesh");

        const auto [out, status] = runFoam("checkMesh -case " + caseDir);
        EXPECT_NE(out.find("Mesh OK"), std::string::npos) << mc.name << ":\n" << out;
        EXPECT_EQ(status, 0) << mc.name << ":\n" << out;

        std::ostringstream cells;
        cells << "cells:            " << mesh.nCells;
        EXPECT_NE(out.find(cells.str()), std::string::npos) << mc.name << ":\n" << out;
    }
}


INSTANTIATE_TEST_SUITE_P
(
    formats,
    realCheckMesh,
    ::testing::Values
    (
        std::make_tuple(false, 32),
        std::make_tuple(true, 32),
        std::make_tuple(true, 64)
    ),
    [](const ::testing::TestParamInfo<std::tuple<bool, int>>& info)
    {
        return std::string(std::get<0>(info.param) ? "binary" : "ascii")
            + "Label" + std::to_string(std::get<1>(info.param));
    }
);


TEST(realCheckMeshParallel, decomposedCasesPassCheckMeshParallel)
{
    ASSERT_FALSE(findOnPath("checkMesh").empty())
        << "checkMesh is not on PATH: the project needs the OpenFOAM binaries";
    ASSERT_FALSE(findOnPath("mpirun").empty())
        << "mpirun is not on PATH: the project needs OpenMPI";

    // Slabs (each rank touches one or two others) and scattered tets (every
    // rank touches every other, several processor patches per rank), with
    // scrambled local point numbering, in ascii and binary
    struct parCase { std::string name; int nRanks; bool scatter; bool binary; };
    for
    (
        const parCase& pc :
        {
            parCase{"slabs", 3, false, false},
            parCase{"scattered", 4, true, true}
        }
    )
    {
        tempDir tmp(pc.name);
        const std::string caseDir = tmp.path();
        writeSystemDicts(caseDir, pc.nRanks);
        const tetMesh m = kuhnGrid(6, 3, 2);
        for (int r = 0; r < pc.nRanks; ++r)
        {
            const std::string loc =
                "processor" + std::to_string(r) + "/constant/polyMesh";
            writePolyMesh
            (
                caseDir + "/" + loc, rankMesh(m, 6, r, pc.nRanks, pc.scatter),
                format(pc.binary, 32), loc
            );
        }

        const auto [out, status] = runFoam
        (
            "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1"
            " mpirun --oversubscribe -np " + std::to_string(pc.nRanks)
          + " checkMesh -parallel -case " + caseDir
        );
        EXPECT_NE(out.find("Coupled point location match (average 0) OK."), std::string::npos)
            << pc.name << ":\n" << out;
        EXPECT_NE(out.find("Mesh OK"), std::string::npos) << pc.name << ":\n" << out;
        EXPECT_EQ(status, 0) << pc.name << ":\n" << out;
    }
}
