/*---------------------------------------------------------------------------*\
  pmshFoam tests: tetsToPolyMesh on small hand-built meshes.

  The expected boundary of each test mesh is computed independently of the
  library (testMeshes.H), and every result is checked against OpenFOAM's
  rules: face blocks, owner < neighbour, upper-triangular order, normals
  from owner to neighbour and out of the domain, patch layout, and
  processor faces that are reverseFace of each other. The same for tets on
  prism layers (layerMeshes.H: faces of 3 and 4 points), and such a mesh
  written through foamRankMesh must pass the real checkMesh.
\*---------------------------------------------------------------------------*/

#include "tetsToPolyMesh.H"
#include "foamMeshOutput.H"
#include "foamShims.H"
#include "IStringStream.H"
#include "layerMeshes.H"
#include "mixedFaceMatching.H"
#include "prismFaces.H"
#include "testMeshes.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <numeric>

using namespace pmsh;
using namespace pmsh::test;

namespace
{

tetMesh singleTet()
{
    tetMesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    m.tets = {{0, 1, 2, 3}};
    return m;
}


tetMesh twoTets()
{
    tetMesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    // Listed so that the shared face (1 2 3) has the higher tet first
    m.tets = {{4, 1, 2, 3}, {0, 1, 2, 3}};
    orientPositive(m);
    return m;
}


//- The unit cube as 5 tets: four corner tets and a central one.
tetMesh fiveTetCube()
{
    tetMesh m;
    for (int c = 0; c < 8; ++c)
    {
        m.points.push_back({double(c & 1), double((c >> 1) & 1), double(c >> 2)});
    }
    m.tets = {{0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}, {1, 2, 4, 7}};
    orientPositive(m);
    return m;
}


//- Kuhn grid (kuhnGridAt) with uneven spacing on purpose.
tetMesh kuhnGrid(int nx, int ny, int nz)
{
    auto coord = [](int i) { return i + 0.1*i*i; };
    return kuhnGridAt
    (
        nx, ny, nz,
        [&](int i, int j, int k) { return point3{coord(i), 0.5*coord(j), 2*coord(k)}; }
    );
}


//- Physical patches used with the box meshes: the six sides, and an empty
//  patch in the middle that no triangle uses.
std::vector<meshPatch> boxPatches()
{
    std::vector<meshPatch> patches(7);
    const char* names[] = {"xMin", "xMax", "yMin", "nothing", "yMax", "zMin", "zMax"};
    for (int i = 0; i < 7; ++i)
    {
        patches[i].name = names[i];
        patches[i].type = i < 2 ? "patch" : "wall";
    }
    return patches;
}


//- Region of a boundary face of a box from its centroid (see boxPatches).
//  Faces on no side of the bounding box (slanted faces) go to zMax.
label boxRegion(const point3& c, const point3& lo, const point3& hi)
{
    const double eps = 1e-9;
    if (std::abs(c[0] - lo[0]) < eps) return 0;
    if (std::abs(c[0] - hi[0]) < eps) return 1;
    if (std::abs(c[1] - lo[1]) < eps) return 2;
    if (std::abs(c[1] - hi[1]) < eps) return 4;
    if (std::abs(c[2] - lo[2]) < eps) return 5;
    // zMax, and any slanted face (of the single tets)
    return 6;
}


//- Every OpenFOAM ordering and orientation rule, checked on a mesh whose
//  cell c has the points cells[c] (a tet's 4 or a prism's 6), with faces
//  of 3 and 4 points: each face on its cells, internal faces first with
//  owner < neighbour in strict (owner, neighbour) order, normals from
//  owner to neighbour and out of the domain, each cell closed by its 4 or
//  5 faces, the patches contiguous after the internal faces. For the
//  tet-only path and the path with prisms alike.
void expectValidCells
(
    const tetPolyMesh& mesh,
    const std::vector<std::vector<label>>& cells
)
{
    const auto& p = mesh.points;
    const label nInt = mesh.nInternalFaces();
    const std::size_t nCells = cells.size();

    ASSERT_EQ(mesh.nCells, label(nCells));
    ASSERT_EQ(mesh.owner.size(), mesh.faces.size());

    std::vector<point3> C(nCells);
    for (std::size_t c = 0; c < nCells; ++c)
    {
        C[c] = centroid(p, cells[c]);
    }
    auto onCell = [&](label c, label v)
    {
        return std::find(cells[c].begin(), cells[c].end(), v) != cells[c].end();
    };

    std::vector<vector3> sumS(nCells, {0, 0, 0});
    std::vector<double> sumMagS(nCells, 0);
    std::vector<int> nCellFaces(nCells, 0);
    label nFacePoints = 0;
    for (label f = 0; f < mesh.nFaces(); ++f)
    {
        const std::vector<label> face = facePointsOf(mesh, f);
        nFacePoints += label(face.size());
        const label own = mesh.owner[f];
        ASSERT_GE(own, 0);
        ASSERT_LT(own, mesh.nCells);
        const vector3 S = areaVector(p, face);
        const point3 fc = centroid(p, face);
        for (label v : face)
        {
            EXPECT_TRUE(onCell(own, v)) << "face " << f << " has a point not on its owner";
        }
        sumS[own] = sumS[own] + S;
        sumMagS[own] += std::sqrt(magSqr(S));
        ++nCellFaces[own];

        if (f < nInt)
        {
            const label nei = mesh.neighbour[f];
            ASSERT_LT(own, nei) << "face " << f;
            ASSERT_LT(nei, mesh.nCells) << "face " << f;
            for (label v : face)
            {
                EXPECT_TRUE(onCell(nei, v)) << "face " << f << " has a point not on its neighbour";
            }
            EXPECT_GT(dot(S, C[nei] - C[own]), 0)
                << "internal face " << f << " does not point owner->neighbour";
            sumS[nei] = sumS[nei] - S;
            sumMagS[nei] += std::sqrt(magSqr(S));
            ++nCellFaces[nei];
            if (f > 0)
            {
                const auto prev = std::make_pair(mesh.owner[f - 1], mesh.neighbour[f - 1]);
                EXPECT_LT(prev, std::make_pair(own, nei))
                    << "internal faces not in strict (owner, neighbour) order at " << f;
            }
        }
        else
        {
            EXPECT_GT(dot(S, fc - C[own]), 0)
                << "boundary face " << f << " does not point out of the domain";
        }
    }

    for (std::size_t c = 0; c < nCells; ++c)
    {
        const bool prism = cells[c].size() == 6;
        EXPECT_EQ(nCellFaces[c], prism ? 5 : 4) << "cell " << c;
        EXPECT_LT(std::sqrt(magSqr(sumS[c])), 1e-12*sumMagS[c])
            << (prism ? "prism" : "tet") << " cell " << c << " not closed";
    }
    // 3 points a triangle, 4 a quad: the quads are exactly the faces of 4
    EXPECT_EQ(nFacePoints, 3*mesh.nFaces() + label(mesh.quads.size()));

    // Patches: contiguous from nInternalFaces, in order, covering all faces
    label start = nInt;
    for (const meshPatch& pp : mesh.patches)
    {
        EXPECT_EQ(pp.start, start) << pp.name;
        EXPECT_GE(pp.size, 0) << pp.name;
        start += pp.size;
    }
    EXPECT_EQ(start, mesh.nFaces());
}


//- expectValidCells on a mesh of tets: no quads, and each tet's 4 faces
//  are 4*nCells = 2*nInternal + nBoundary.
void expectValidPolyMesh(const tetPolyMesh& mesh, const std::vector<tetVerts>& tets)
{
    std::vector<std::vector<label>> cells;
    for (const tetVerts& t : tets)
    {
        cells.push_back({t.begin(), t.end()});
    }
    expectValidCells(mesh, cells);
    EXPECT_TRUE(mesh.quads.empty());
    const label nInt = mesh.nInternalFaces();
    EXPECT_EQ(4*mesh.nCells, 2*nInt + (mesh.nFaces() - nInt));
}


//- Patch of each face's region, checked by the face centroid.
void expectBoxPatchesByGeometry(const tetPolyMesh& mesh, std::size_t nPhysical)
{
    point3 lo = mesh.points[0], hi = mesh.points[0];
    for (const point3& p : mesh.points)
    {
        for (int d = 0; d < 3; ++d)
        {
            lo[d] = std::min(lo[d], p[d]);
            hi[d] = std::max(hi[d], p[d]);
        }
    }
    for (std::size_t pi = 0; pi < nPhysical; ++pi)
    {
        const meshPatch& pp = mesh.patches[pi];
        for (label f = pp.start; f < pp.start + pp.size; ++f)
        {
            const triVerts& face = mesh.faces[f];
            const point3 c = centroid(mesh.points, {face[0], face[1], face[2]});
            EXPECT_EQ(boxRegion(c, lo, hi), label(pi)) << "face " << f << " in " << pp.name;
        }
    }
}


//- Split m along x into nRanks slabs by tet centroid.
std::vector<int> slabRanks(const tetMesh& m, int nRanks)
{
    double lo = 1e300, hi = -1e300;
    for (const point3& p : m.points)
    {
        lo = std::min(lo, p[0]);
        hi = std::max(hi, p[0]);
    }
    std::vector<int> rank;
    for (const tetVerts& t : m.tets)
    {
        const double x = cellCentre(m.points, t)[0];
        rank.push_back(std::min(nRanks - 1, int(nRanks*(x - lo)/(hi - lo))));
    }
    return rank;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * * Tests * * * * * * * * * * * * * * * * //

TEST(freeStorage, handsAVectorsStorageBackWhereAssigningBracesDoesNot)
{
    // The write stage frees each array as soon as it is used: `v = {}`
    // kept them all (34 bytes per cell at the write stage's peak)
    std::vector<label> v(1000, 1);
    v = {};
    ASSERT_EQ(v.capacity(), 1000u) << "the quirk freeStorage exists for";
    freeStorage(v);
    EXPECT_EQ(v.capacity(), 0u);
}


TEST(tetsToPolyMesh, interfaceRegionEncodingRoundTrips)
{
    for (label rank : {0, 1, 7, 123456})
    {
        const label r = interfaceRegion(rank);
        EXPECT_TRUE(isInterfaceRegion(r));
        EXPECT_EQ(interfaceNeighbour(r), rank);
    }
    EXPECT_EQ(interfaceRegion(0), -1);
    EXPECT_FALSE(isInterfaceRegion(0));
    EXPECT_FALSE(isInterfaceRegion(5));
}


TEST(tetsToPolyMesh, tetFaceTableIsOutwardAndOppositeVertex3MinusF)
{
    const tetMesh m = kuhnGrid(1, 1, 1);
    for (const tetVerts& t : m.tets)
    {
        const point3 C = cellCentre(m.points, t);
        for (int f = 0; f < 4; ++f)
        {
            const triVerts face = tetFace(t, f);
            const point3 fc = centroid(m.points, {face[0], face[1], face[2]});
            EXPECT_GT(dot(faceNormal(m.points, face), fc - C), 0) << "face " << f;
            for (label v : face)
            {
                EXPECT_NE(v, t[3 - f]) << "face " << f << " contains vertex " << 3 - f;
            }
        }
    }
}


TEST(tetsToPolyMesh, singleTetHasFourOutwardBoundaryFaces)
{
    const tetMesh m = singleTet();
    const rankInput in = makeRankInput(m, {}, 0, boxRegion);
    const tetPolyMesh mesh = build(in, boxPatches());

    EXPECT_EQ(mesh.nCells, 1);
    EXPECT_EQ(mesh.nFaces(), 4);
    EXPECT_EQ(mesh.nInternalFaces(), 0);
    expectValidPolyMesh(mesh, in.tets);
    expectBoxPatchesByGeometry(mesh, 7);
}


TEST(tetsToPolyMesh, twoTetsShareOneFaceOrientedFromLowerToHigherCell)
{
    const tetMesh m = twoTets();
    rankInput in = makeRankInput(m, {}, 0, boxRegion);
    std::vector<meshPatch> patches(1);
    patches[0].name = "walls";
    for (label& r : in.regions)
    {
        r = 0;
    }
    const tetPolyMesh mesh = build(in, patches);

    ASSERT_EQ(mesh.nInternalFaces(), 1);
    EXPECT_EQ(mesh.nFaces(), 7);
    EXPECT_EQ(mesh.owner[0], 0);
    EXPECT_EQ(mesh.neighbour[0], 1);
    expectValidPolyMesh(mesh, in.tets);
    ASSERT_EQ(mesh.patches.size(), 1u);
    EXPECT_EQ(mesh.patches[0].size, 6);
}


TEST(tetsToPolyMesh, fiveTetCubeIsValid)
{
    const tetMesh m = fiveTetCube();
    const rankInput in = makeRankInput(m, {}, 0, boxRegion);
    const tetPolyMesh mesh = build(in, boxPatches());

    EXPECT_EQ(mesh.nInternalFaces(), 4);
    EXPECT_EQ(mesh.nFaces(), 16);
    expectValidPolyMesh(mesh, in.tets);
    expectBoxPatchesByGeometry(mesh, 7);
}


TEST(tetsToPolyMesh, sixTetCubeHasTwoFacesPerSideAndEmptyPatchKept)
{
    const tetMesh m = kuhnGrid(1, 1, 1);
    const rankInput in = makeRankInput(m, {}, 0, boxRegion);
    const tetPolyMesh mesh = build(in, boxPatches());

    EXPECT_EQ(mesh.nCells, 6);
    EXPECT_EQ(mesh.nInternalFaces(), 6);
    EXPECT_EQ(mesh.nFaces(), 18);
    expectValidPolyMesh(mesh, in.tets);
    expectBoxPatchesByGeometry(mesh, 7);

    ASSERT_EQ(mesh.patches.size(), 7u);
    for (std::size_t i = 0; i < 7; ++i)
    {
        EXPECT_EQ(mesh.patches[i].name, boxPatches()[i].name);
        EXPECT_EQ(mesh.patches[i].type, boxPatches()[i].type);
        EXPECT_EQ(mesh.patches[i].size, i == 3 ? 0 : 2) << mesh.patches[i].name;
    }
    // The empty patch starts where the next one starts
    EXPECT_EQ(mesh.patches[3].start, mesh.patches[4].start);
}


TEST(tetsToPolyMesh, gridIsUpperTriangularAndOriented)
{
    const tetMesh m = kuhnGrid(3, 2, 2);
    const rankInput in = makeRankInput(m, {}, 0, boxRegion);
    const tetPolyMesh mesh = build(in, boxPatches());

    expectValidPolyMesh(mesh, in.tets);
    expectBoxPatchesByGeometry(mesh, 7);
    EXPECT_TRUE(mesh.patches.size() == 7u);
}


TEST(tetsToPolyMesh, physicalPatchFacesAreOrderedByOwner)
{
    const tetMesh m = kuhnGrid(2, 2, 2);
    const rankInput in = makeRankInput(m, {}, 0, boxRegion);
    const tetPolyMesh mesh = build(in, boxPatches());

    for (const meshPatch& pp : mesh.patches)
    {
        for (label f = pp.start + 1; f < pp.start + pp.size; ++f)
        {
            EXPECT_LE(mesh.owner[f - 1], mesh.owner[f]) << pp.name;
        }
    }
}


TEST(tetsToPolyMesh, resultDoesNotDependOnBoundaryTriangleOrder)
{
    const tetMesh m = kuhnGrid(2, 2, 1);
    const std::vector<int> ranks = slabRanks(m, 2);
    rankInput in = makeRankInput(m, ranks, 1, boxRegion);
    const tetPolyMesh a = build(in, boxPatches(), 1);

    // Reverse and rotate the triangles: same mesh expected
    std::reverse(in.tris.begin(), in.tris.end());
    std::reverse(in.regions.begin(), in.regions.end());
    for (triVerts& t : in.tris)
    {
        t = {t[1], t[2], t[0]};
    }
    const tetPolyMesh b = build(in, boxPatches(), 1);

    EXPECT_EQ(a.faces, b.faces);
    EXPECT_EQ(a.owner, b.owner);
    EXPECT_EQ(a.neighbour, b.neighbour);
}


TEST(tetsToPolyMesh, serialMeshHasNoProcessorPatches)
{
    const rankInput in = makeRankInput(kuhnGrid(2, 1, 1), {}, 0, boxRegion);
    const tetPolyMesh mesh = build(in, boxPatches());
    for (const meshPatch& pp : mesh.patches)
    {
        EXPECT_FALSE(pp.isProcessor()) << pp.name;
    }
}


TEST(tetsToPolyMesh, twoRankCubeHasProcessorPatchesAfterPhysicalOnes)
{
    const tetMesh m = kuhnGrid(1, 1, 1);
    // Tets 0-2 on rank 0, 3-5 on rank 1
    const std::vector<int> ranks = {0, 0, 0, 1, 1, 1};

    for (int rank = 0; rank < 2; ++rank)
    {
        const rankInput in = makeRankInput(m, ranks, rank, boxRegion);
        const tetPolyMesh mesh = build(in, boxPatches(), rank);
        expectValidPolyMesh(mesh, in.tets);

        ASSERT_EQ(mesh.patches.size(), 8u) << "rank " << rank;
        for (std::size_t i = 0; i < 7; ++i)
        {
            EXPECT_EQ(mesh.patches[i].name, boxPatches()[i].name);
        }
        const meshPatch& pp = mesh.patches[7];
        EXPECT_EQ(pp.name, rank == 0 ? "procBoundary0to1" : "procBoundary1to0");
        EXPECT_EQ(pp.type, "processor");
        EXPECT_EQ(pp.neighbProcNo, 1 - rank);
        EXPECT_GT(pp.size, 0);
    }
}


TEST(tetsToPolyMesh, processorPatchesAreInAscendingNeighbourRank)
{
    const tetMesh m = kuhnGrid(3, 2, 2);
    const std::vector<int> ranks = slabRanks(m, 3);

    // Rank 1 touches ranks 0 and 2; feed rank 2's triangles first
    rankInput in = makeRankInput(m, ranks, 1, boxRegion);
    std::vector<std::size_t> order(in.tris.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort
    (
        order.begin(), order.end(),
        [&](std::size_t a, std::size_t b) { return in.regions[a] < in.regions[b]; }
    );
    rankInput sorted = in;
    for (std::size_t i = 0; i < order.size(); ++i)
    {
        sorted.tris[i] = in.tris[order[i]];
        sorted.regions[i] = in.regions[order[i]];
    }
    ASSERT_EQ(sorted.regions.front(), interfaceRegion(2));

    const tetPolyMesh mesh = build(sorted, boxPatches(), 1);
    expectValidPolyMesh(mesh, sorted.tets);
    expectBoxPatchesByGeometry(mesh, 7);

    ASSERT_EQ(mesh.patches.size(), 9u);
    EXPECT_EQ(mesh.patches[7].name, "procBoundary1to0");
    EXPECT_EQ(mesh.patches[7].neighbProcNo, 0);
    EXPECT_EQ(mesh.patches[8].name, "procBoundary1to2");
    EXPECT_EQ(mesh.patches[8].neighbProcNo, 2);
}


TEST(tetsToPolyMesh, processorFacesAreReverseFaceOfEachOtherInGlobalIds)
{
    struct testCase
    {
        tetMesh m;
        std::vector<int> ranks;
        int nRanks;
    };
    std::vector<testCase> cases;
    {
        tetMesh cube = kuhnGrid(1, 1, 1);
        cases.push_back({cube, {0, 0, 0, 1, 1, 1}, 2});
        cases.push_back({cube, {1, 0, 1, 0, 1, 0}, 2});
        tetMesh grid = kuhnGrid(3, 2, 2);
        cases.push_back({grid, slabRanks(grid, 3), 3});
        std::vector<int> scattered(grid.tets.size());
        for (std::size_t t = 0; t < scattered.size(); ++t)
        {
            scattered[t] = int((t*7 + t/5) % 4);
        }
        cases.push_back({grid, scattered, 4});
    }

    for (std::size_t ci = 0; ci < cases.size(); ++ci)
    {
        const testCase& tc = cases[ci];
        std::vector<rankInput> in;
        std::vector<tetPolyMesh> mesh;
        for (int r = 0; r < tc.nRanks; ++r)
        {
            in.push_back(makeRankInput(tc.m, tc.ranks, r, boxRegion));
            mesh.push_back(build(in.back(), boxPatches(), r));
            expectValidPolyMesh(mesh.back(), in.back().tets);
        }

        std::size_t nChecked = 0;
        for (int a = 0; a < tc.nRanks; ++a)
        {
            for (const meshPatch& pa : mesh[a].patches)
            {
                if (!pa.isProcessor())
                {
                    continue;
                }
                const int b = pa.neighbProcNo;
                const auto pb = std::find_if
                (
                    mesh[b].patches.begin(), mesh[b].patches.end(),
                    [&](const meshPatch& p) { return p.name == processorPatchName(b, a); }
                );
                ASSERT_NE(pb, mesh[b].patches.end()) << "case " << ci;
                ASSERT_EQ(pa.size, pb->size) << "case " << ci << ' ' << pa.name;

                for (label i = 0; i < pa.size; ++i)
                {
                    const triVerts& fa = mesh[a].faces[pa.start + i];
                    const triVerts& fb = mesh[b].faces[pb->start + i];
                    std::array<label, 3> ga, gb;
                    for (int k = 0; k < 3; ++k)
                    {
                        ga[k] = in[a].globalIds[fa[k]];
                        gb[k] = in[b].globalIds[fb[k]];
                    }
                    // reverseFace: vertex 0 kept, the rest reversed
                    EXPECT_EQ(ga[0], gb[0]) << "case " << ci << ' ' << pa.name << " face " << i;
                    EXPECT_EQ(ga[1], gb[2]) << "case " << ci << ' ' << pa.name << " face " << i;
                    EXPECT_EQ(ga[2], gb[1]) << "case " << ci << ' ' << pa.name << " face " << i;
                    // vertex 0 is the smallest global id
                    EXPECT_LT(ga[0], ga[1]);
                    EXPECT_LT(ga[0], ga[2]);
                    // and the same point in space
                    EXPECT_EQ(mesh[a].points[fa[0]], mesh[b].points[fb[0]]);
                    ++nChecked;
                }
                // Faces sorted by their sorted global ids
                for (label i = 1; i < pa.size; ++i)
                {
                    auto key = [&](label j)
                    {
                        const triVerts& f = mesh[a].faces[pa.start + j];
                        std::array<label, 3> k =
                            {in[a].globalIds[f[0]], in[a].globalIds[f[1]], in[a].globalIds[f[2]]};
                        std::sort(k.begin(), k.end());
                        return k;
                    };
                    EXPECT_LT(key(i - 1), key(i)) << pa.name;
                }
            }
        }
        EXPECT_GT(nChecked, 0u) << "case " << ci;
    }
}


// * * * * * * * * * * * * * * * Error tests * * * * * * * * * * * * * * * //

TEST(tetsToPolyMesh, boundaryTriangleNotOnATetIsAnError)
{
    rankInput in = makeRankInput(kuhnGrid(1, 1, 1), {}, 0, boxRegion);
    // Replace one triangle by one through the cube's interior diagonal
    in.tris[0] = {0, 7, 3};
    const std::string e = errorOf([&]() { build(in, boxPatches()); });
    const std::string open =
        "1 tet faces are on no other tet and not in the boundary surface";
    EXPECT_NE(e.find(open), std::string::npos) << e;
    EXPECT_NE(e.find("1 boundary surface triangles"), std::string::npos) << e;
}


TEST(tetsToPolyMesh, reversedBoundaryTriangleIsAnError)
{
    rankInput in = makeRankInput(kuhnGrid(1, 1, 1), {}, 0, boxRegion);
    std::swap(in.tris[3][1], in.tris[3][2]);
    const std::string e = errorOf([&]() { build(in, boxPatches()); });
    EXPECT_NE(e.find("1 boundary surface triangles are not oriented outward"), std::string::npos) << e;
}


TEST(tetsToPolyMesh, missingBoundaryTriangleIsAnError)
{
    rankInput in = makeRankInput(kuhnGrid(1, 1, 1), {}, 0, boxRegion);
    in.tris.pop_back();
    in.regions.pop_back();
    const std::string e = errorOf([&]() { build(in, boxPatches()); });
    EXPECT_NE(e.find("1 tet faces are on no other tet"), std::string::npos) << e;
}


TEST(tetsToPolyMesh, surfaceTriangleOnAnInternalFaceIsAnError)
{
    rankInput in = makeRankInput(kuhnGrid(1, 1, 1), {}, 0, boxRegion);
    // Tets 0 and 1 of the Kuhn cube share a face
    in.tris.push_back(tetFace(in.tets[0], 0));
    in.regions.push_back(0);
    const std::string e = errorOf([&]() { build(in, boxPatches()); });
    EXPECT_FALSE(e.empty());
}


TEST(tetsToPolyMesh, nonPositiveTetIsAnError)
{
    rankInput in = makeRankInput(singleTet(), {}, 0, boxRegion);
    std::swap(in.tets[0][0], in.tets[0][1]);
    const std::string e = errorOf([&]() { build(in, boxPatches()); });
    EXPECT_NE(e.find("non-positive volume"), std::string::npos) << e;
}


TEST(tetsToPolyMesh, regionWithoutPatchIsAnError)
{
    rankInput in = makeRankInput(singleTet(), {}, 0, boxRegion);
    in.regions[0] = 7;
    const std::string e = errorOf([&]() { build(in, boxPatches()); });
    EXPECT_NE(e.find("invalid region"), std::string::npos) << e;
}


TEST(tetsToPolyMesh, interfaceRegionInSerialIsAnError)
{
    rankInput in = makeRankInput(singleTet(), {}, 0, boxRegion);
    in.regions[0] = interfaceRegion(1);
    const std::string e = errorOf([&]() { build(in, boxPatches()); });
    EXPECT_NE(e.find("invalid region"), std::string::npos) << e;
}


TEST(tetsToPolyMesh, interfaceWithOwnRankIsAnError)
{
    const tetMesh m = kuhnGrid(1, 1, 1);
    rankInput in = makeRankInput(m, {0, 0, 0, 1, 1, 1}, 0, boxRegion);
    for (label& r : in.regions)
    {
        if (isInterfaceRegion(r)) r = interfaceRegion(0);
    }
    const std::string e = errorOf([&]() { build(in, boxPatches(), 0); });
    EXPECT_NE(e.find("invalid region"), std::string::npos) << e;
}


TEST(tetsToPolyMesh, unusedPointIsAnError)
{
    rankInput in = makeRankInput(singleTet(), {}, 0, boxRegion);
    in.points.push_back({5, 5, 5});
    const std::string e = errorOf([&]() { build(in, boxPatches()); });
    EXPECT_NE(e.find("used by no tet"), std::string::npos) << e;
}


TEST(tetsToPolyMesh, duplicateTetIsAnError)
{
    rankInput in = makeRankInput(singleTet(), {}, 0, boxRegion);
    in.tets.push_back(in.tets[0]);
    const std::string e = errorOf([&]() { build(in, boxPatches()); });
    EXPECT_FALSE(e.empty());
}


TEST(tetsToPolyMesh, physicalPatchOfTypeProcessorIsAnError)
{
    rankInput in = makeRankInput(singleTet(), {}, 0, boxRegion);
    std::vector<meshPatch> patches = boxPatches();
    patches[6].type = "processor";
    const std::string e = errorOf([&]() { build(in, patches); });
    EXPECT_NE(e.find("type processor"), std::string::npos) << e;
}


TEST(tetsToPolyMesh, repeatedGlobalPointIdOnProcessorFaceIsAnError)
{
    const tetMesh m = kuhnGrid(1, 1, 1);
    rankInput in = makeRankInput(m, {0, 0, 0, 1, 1, 1}, 0, boxRegion);
    // Give two points of an interface triangle the same global id
    for (std::size_t b = 0; b < in.tris.size(); ++b)
    {
        if (isInterfaceRegion(in.regions[b]))
        {
            in.globalIds[in.tris[b][1]] = in.globalIds[in.tris[b][0]];
            break;
        }
    }
    const std::string e = errorOf([&]() { build(in, boxPatches(), 0); });
    EXPECT_NE(e.find("same global point ids"), std::string::npos) << e;
}


TEST(tetsToPolyMesh, globalPointIdsOfWrongSizeAreAnError)
{
    const tetMesh m = kuhnGrid(1, 1, 1);
    rankInput in = makeRankInput(m, {0, 0, 0, 1, 1, 1}, 0, boxRegion);
    in.globalIds.pop_back();
    const std::string e = errorOf([&]() { build(in, boxPatches(), 0); });
    EXPECT_NE(e.find("global point ids given"), std::string::npos) << e;
}


// * * * * * * * * * * * * Prism layers (tets and prisms) * * * * * * * * * //

namespace
{

//- expectValidCells on a mesh of tets and prisms (cells of in, tets
//  first): its prisms counted, its quads listed by ascending face.
void expectValidLayeredPolyMesh(const tetPolyMesh& mesh, const layeredRankInput& in)
{
    ASSERT_EQ(mesh.nPrisms, label(in.prisms.size()));
    for (std::size_t q = 0; q < mesh.quads.size(); ++q)
    {
        ASSERT_GE(mesh.quads[q].face, 0);
        ASSERT_LT(mesh.quads[q].face, mesh.nFaces());
        if (q > 0)
        {
            ASSERT_LT(mesh.quads[q - 1].face, mesh.quads[q].face) << "quads not ascending";
        }
    }
    std::vector<std::vector<label>> cells;
    for (std::size_t c = 0; c < in.tets.size() + in.prisms.size(); ++c)
    {
        cells.push_back(in.cellPoints(c));
    }
    expectValidCells(mesh, cells);
}


//- The boundary faces (triangles and quads) of each region of in.
std::map<label, label> facesPerRegion(const layeredRankInput& in)
{
    std::map<label, label> n;
    for (label r : in.triRegions) ++n[r];
    for (label r : in.quadRegions) ++n[r];
    return n;
}


//- Split the cells of m at x = xSplit by centroid: ranks 0 and 1.
std::vector<int> twoSlabs(const layeredMesh& m, double xSplit)
{
    std::vector<int> rank;
    for (std::size_t c = 0; c < m.nCells(); ++c)
    {
        rank.push_back(centroid(m.points, m.cellPoints(c))[0] < xSplit ? 0 : 1);
    }
    return rank;
}

} // End anonymous namespace


TEST(tetsToPolyMesh, prismFaceTableIsOpenFOAMsPrismModel)
{
    // cellModels' prism: 3(0 2 1) 3(3 4 5) 4(0 3 5 2) 4(1 2 5 4) 4(0 1 4 3)
    const prismVerts c = {10, 11, 12, 13, 14, 15};
    const std::vector<std::vector<label>> expected =
        {{10, 12, 11}, {13, 14, 15}, {10, 13, 15, 12}, {11, 12, 15, 14}, {10, 11, 14, 13}};
    for (int f = 0; f < 5; ++f)
    {
        quadVerts v;
        const int n = prismFace(c, f, v);
        EXPECT_EQ(std::vector<label>(v.begin(), v.begin() + n), expected[f]) << "face " << f;
    }
}


TEST(tetsToPolyMesh, tetsOnTwoPrismLayersAreValid)
{
    const layeredMesh m = layeredBlock(3, 2, 2, 2);
    const layeredRankInput in = makeLayeredRankInput(m, {}, 0, boxRegion);
    ASSERT_FALSE(in.quads.empty());
    const tetPolyMesh mesh = build(in, boxPatches());
    expectValidLayeredPolyMesh(mesh, in);

    // 2 levels of 2 prisms per square on the 3x2 wall
    EXPECT_EQ(mesh.nPrisms, 2*2*3*2);
    // Every cell face once: 4 a tet, 5 a prism
    const label nInt = mesh.nInternalFaces();
    EXPECT_EQ(4*label(in.tets.size()) + 5*mesh.nPrisms, 2*nInt + (mesh.nFaces() - nInt));

    // Quads: the internal ones between prisms, and the boundary ones
    label nInternalQuads = 0;
    for (const quadFace& q : mesh.quads)
    {
        nInternalQuads += q.face < nInt;
    }
    EXPECT_EQ(label(mesh.quads.size()) - nInternalQuads, label(in.quads.size()));
    // Per level: 3*2 diagonals and 2*3*2 - 3 - 2 inner grid edges
    EXPECT_EQ(nInternalQuads, 2*(6 + (2*3*2 - 3 - 2)));

    // Every patch complete: as many faces as the input has in its region
    const std::map<label, label> expected = facesPerRegion(in);
    for (std::size_t pi = 0; pi < mesh.patches.size(); ++pi)
    {
        const auto it = expected.find(label(pi));
        EXPECT_EQ(mesh.patches[pi].size, it == expected.end() ? 0 : it->second)
            << mesh.patches[pi].name;
    }
    // The wall (zMin) is the prisms' base triangles
    EXPECT_EQ(mesh.patches[5].size, 2*3*2);
    for (label f = mesh.patches[5].start; f < mesh.patches[5].start + mesh.patches[5].size; ++f)
    {
        EXPECT_EQ(facePointsOf(mesh, f).size(), 3u);
        EXPECT_GE(mesh.owner[f], label(in.tets.size())) << "wall face " << f << " not on a prism";
    }
}


TEST(tetsToPolyMesh, layeredMeshDoesNotDependOnBoundaryFaceOrder)
{
    const layeredMesh m = layeredBlock(2, 2, 2, 1);
    layeredRankInput in = makeLayeredRankInput(m, {}, 0, boxRegion);
    const tetPolyMesh a = build(in, boxPatches());
    std::reverse(in.quads.begin(), in.quads.end());
    std::reverse(in.quadRegions.begin(), in.quadRegions.end());
    std::reverse(in.tris.begin(), in.tris.end());
    std::reverse(in.triRegions.begin(), in.triRegions.end());
    const tetPolyMesh b = build(in, boxPatches());
    ASSERT_EQ(a.nFaces(), b.nFaces());
    for (label f = 0; f < a.nFaces(); ++f)
    {
        EXPECT_EQ(facePointsOf(a, f), facePointsOf(b, f)) << "face " << f;
        EXPECT_EQ(a.owner[f], b.owner[f]) << "face " << f;
    }
}


TEST(tetsToPolyMesh, layeredProcessorFacesAreReverseFaceOfEachOther)
{
    // Split through the prisms and the tets: the interface has both
    const layeredMesh m = layeredBlock(4, 2, 2, 2);
    const std::vector<int> ranks = twoSlabs(m, 2.2);
    std::vector<layeredRankInput> in;
    std::vector<tetPolyMesh> mesh;
    for (int r = 0; r < 2; ++r)
    {
        in.push_back(makeLayeredRankInput(m, ranks, r, boxRegion));
        mesh.push_back(build(in.back(), boxPatches(), r));
        expectValidLayeredPolyMesh(mesh.back(), in.back());
    }
    const meshPatch& pa = mesh[0].patches.back();
    const meshPatch& pb = mesh[1].patches.back();
    ASSERT_EQ(pa.name, processorPatchName(0, 1));
    ASSERT_EQ(pb.name, processorPatchName(1, 0));
    ASSERT_EQ(pa.size, pb.size);

    std::size_t nTris = 0, nQuads = 0;
    std::vector<label> previousKey;
    for (label i = 0; i < pa.size; ++i)
    {
        const std::vector<label> fa = facePointsOf(mesh[0], pa.start + i);
        const std::vector<label> fb = facePointsOf(mesh[1], pb.start + i);
        ASSERT_EQ(fa.size(), fb.size()) << "face " << i;
        const std::size_t n = fa.size();
        (n == 3 ? nTris : nQuads)++;
        std::vector<label> ga(n), gb(n);
        for (std::size_t k = 0; k < n; ++k)
        {
            ga[k] = in[0].globalIds[fa[k]];
            gb[k] = in[1].globalIds[fb[k]];
            // The same point in space
            EXPECT_EQ(mesh[0].points[fa[k]], m.points[ga[k]]);
            EXPECT_EQ(mesh[1].points[fb[k]], m.points[gb[k]]);
        }
        // reverseFace: vertex 0 kept, the rest reversed
        for (std::size_t k = 0; k < n; ++k)
        {
            EXPECT_EQ(ga[k], gb[(n - k) % n]) << "face " << i << " point " << k;
        }
        EXPECT_EQ(ga[0], *std::min_element(ga.begin(), ga.end())) << "face " << i;

        // Sorted by the sorted global ids, triangles (led by -1) first
        std::vector<label> key = ga;
        std::sort(key.begin(), key.end());
        if (n == 3) key.insert(key.begin(), -1);
        EXPECT_LT(previousKey, key) << "face " << i;
        previousKey = key;
    }
    EXPECT_GT(nTris, 0u);
    EXPECT_GT(nQuads, 0u);
}


TEST(tetsToPolyMesh, layeredRepeatedGlobalPointIdOnProcessorFaceIsAnError)
{
    // On an interface quad and on an interface triangle: the -1 that pads
    // a triangle's key is no repeated point, two equal ids are
    const layeredMesh m = layeredBlock(4, 2, 2, 2);
    const std::vector<int> ranks = twoSlabs(m, 2.2);
    const layeredRankInput in = makeLayeredRankInput(m, ranks, 0, boxRegion);
    EXPECT_NO_THROW(build(in, boxPatches(), 0));
    auto firstInterface = [](const std::vector<label>& regions)
    {
        return std::size_t(std::find_if(regions.begin(), regions.end(), isInterfaceRegion)
            - regions.begin());
    };
    const std::size_t q = firstInterface(in.quadRegions);
    const std::size_t t = firstInterface(in.triRegions);
    ASSERT_LT(q, in.quads.size());
    ASSERT_LT(t, in.tris.size());

    layeredRankInput repeated = in;
    repeated.globalIds[in.quads[q][2]] = in.globalIds[in.quads[q][0]];
    EXPECT_FATAL(build(repeated, boxPatches(), 0), "same global point ids");
    EXPECT_FATAL(build(repeated, boxPatches(), 0), ", -1: none).");
    repeated = in;
    repeated.globalIds[in.tris[t][1]] = in.globalIds[in.tris[t][0]];
    EXPECT_FATAL(build(repeated, boxPatches(), 0), "same global point ids");
}


TEST(tetsToPolyMesh, missingBoundaryQuadIsAnError)
{
    const layeredMesh m = layeredBlock(2, 1, 2, 1);
    layeredRankInput in = makeLayeredRankInput(m, {}, 0, boxRegion);
    in.quads.pop_back();
    in.quadRegions.pop_back();
    EXPECT_FATAL(build(in, boxPatches()), "cell faces are on no other cell");
}


TEST(tetsToPolyMesh, reversedOrTwistedBoundaryQuadIsAnError)
{
    const layeredMesh m = layeredBlock(2, 1, 2, 1);
    layeredRankInput in = makeLayeredRankInput(m, {}, 0, boxRegion);
    std::reverse(in.quads[0].begin(), in.quads[0].end());
    EXPECT_FATAL(build(in, boxPatches()), "not oriented outward");
    std::reverse(in.quads[0].begin(), in.quads[0].end());
    std::swap(in.quads[0][1], in.quads[0][2]);
    EXPECT_FATAL(build(in, boxPatches()), "not oriented outward");
}


TEST(tetsToPolyMesh, boundaryQuadOnAnInternalFaceIsAnError)
{
    const layeredMesh m = layeredBlock(2, 1, 2, 1);
    layeredRankInput in = makeLayeredRankInput(m, {}, 0, boxRegion);
    // A side quad between two prisms of one level: (a b b' a') of prism 0's
    // face 2 in the library's table is shared with its neighbour
    const tetPolyMesh mesh = build(in, boxPatches());
    const quadFace& q = mesh.quads.front();
    ASSERT_LT(q.face, mesh.nInternalFaces());
    const triVerts& t = mesh.faces[q.face];
    in.quads.push_back({t[0], t[1], t[2], q.fourth});
    in.quadRegions.push_back(0);
    EXPECT_FATAL(build(in, boxPatches()), "lie on a face between two cells");
}


TEST(tetsToPolyMesh, negativePrismIsAnError)
{
    const layeredMesh m = layeredBlock(2, 1, 1, 1);
    layeredRankInput in = makeLayeredRankInput(m, {}, 0, boxRegion);
    prismVerts& p = in.prisms[1];
    p = {p[3], p[4], p[5], p[0], p[1], p[2]};
    EXPECT_FATAL(build(in, boxPatches()), "prisms are not positive");
}


TEST(tetsToPolyMesh, pointOnlyOnPrismsIsUsed)
{
    // The wall points are on prisms only: not "unused"; a point on nothing is
    const layeredMesh m = layeredBlock(1, 1, 1, 1);
    layeredRankInput in = makeLayeredRankInput(m, {}, 0, boxRegion);
    EXPECT_NO_THROW(build(in, boxPatches()));
    in.points.push_back({9, 9, 9});
    EXPECT_FATAL(build(in, boxPatches()), "used by no tet or prism");
}


TEST(tetsToPolyMesh, tetOnlyMeshHasNoQuads)
{
    const tetPolyMesh mesh = build(makeRankInput(kuhnGrid(2, 2, 1), {}, 0, boxRegion), boxPatches());
    EXPECT_TRUE(mesh.quads.empty());
    EXPECT_EQ(mesh.nPrisms, 0);
    EXPECT_EQ(mesh.quads.capacity(), 0u);
}


// The end-to-end check: a layered mesh given to OpenFOAM by foamRankMesh,
// written into a case, judged by the real checkMesh
TEST(foamRankMesh, layeredMeshPassesCheckMesh)
{
    const layeredMesh m = layeredBlock(3, 2, 2, 2);
    const layeredRankInput in = makeLayeredRankInput(m, {}, 0, boxRegion);
    tetPolyMesh mesh = build(in, boxPatches());
    const label nTets = label(in.tets.size()), nPrisms = mesh.nPrisms;
    // Zones: the prisms' after the tets'
    mesh.zoneNames = {"block", "layers"};
    mesh.cellZone.assign(nTets, 0);
    mesh.cellZone.resize(nTets + nPrisms, 1);
    mesh.zonePairs = {{0, 1}};

    const tempDir dir("layeredCheckMesh");
    const std::string controls =
        "application none; startFrom startTime; startTime 0; stopAt endTime;"
        " endTime 1; deltaT 1; writeControl timeStep; writeInterval 1;"
        " writeFormat binary; writePrecision 17; writeCompression off;"
        " timeFormat general; timePrecision 6; runTimeModifiable false;\n";
    auto dictFile = [&](const std::string& name, const std::string& body)
    {
        dir.file
        (
            "system/" + name,
            "FoamFile\n{\n    version 2.0;\n    format ascii;\n"
            "    class dictionary;\n    object " + name + ";\n}\n" + body
        );
    };
    dictFile("controlDict", controls);
    // checkMesh makes an fvMesh: it reads these, empty will do
    dictFile("fvSchemes", "ddtSchemes {} gradSchemes {} divSchemes {}"
        " laplacianSchemes {} interpolationSchemes {} snGradSchemes {}\n");
    dictFile("fvSolution", "\n");
    {
        const std::filesystem::path casePath(dir.path());
        std::unique_ptr<Foam::Time> time
        (
            foam::newTime
            (
                Foam::dictionary(Foam::IStringStream(controls)()),
                casePath.parent_path().string(), casePath.filename().string()
            )
        );
        const foamRankMesh foamMesh(*time, std::move(mesh));
        EXPECT_EQ(foamMesh().nCells(), nTets + nPrisms);
        foamMesh.write();
    }

    const auto [log, status] = runFoam("checkMesh -case " + dir.path());
    EXPECT_EQ(status, 0) << log;
    EXPECT_HAS(log, "Mesh OK.");
    auto count = [&](const std::string& what) -> long
    {
        const std::size_t at = log.find("    " + what + ":");
        return at == std::string::npos ? -1 : std::stol(log.substr(at + what.size() + 5));
    };
    EXPECT_EQ(count("prisms"), nPrisms) << log;
    EXPECT_EQ(count("tetrahedra"), nTets) << log;
    // The prisms are the second zone
    const std::string zones = readFile(dir/"constant/polyMesh/cellZones");
    EXPECT_HAS(zones, "layers");
}
