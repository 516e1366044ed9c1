/*---------------------------------------------------------------------------*\
  pmshFoam tests: tetsToPolyMesh on small hand-built meshes.

  The expected boundary of each test mesh is computed independently of the
  library (testMeshes.H), and every result is checked against OpenFOAM's
  rules: face blocks, owner < neighbour, upper-triangular order, normals
  from owner to neighbour and out of the domain, patch layout, and
  processor faces that are reverseFace of each other.
\*---------------------------------------------------------------------------*/

#include "tetsToPolyMesh.H"
#include "testMeshes.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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


//- Every OpenFOAM ordering and orientation rule, checked on a tetPolyMesh.
void expectValidPolyMesh(const tetPolyMesh& mesh, const std::vector<tetVerts>& tets)
{
    const auto& p = mesh.points;
    const label nInt = mesh.nInternalFaces();

    ASSERT_EQ(mesh.nCells, label(tets.size()));
    ASSERT_EQ(mesh.owner.size(), mesh.faces.size());

    // Each tet has 4 faces: 4*nCells = 2*nInternal + nBoundary
    EXPECT_EQ(4*mesh.nCells, 2*nInt + (mesh.nFaces() - nInt));

    std::vector<point3> C(tets.size());
    for (std::size_t c = 0; c < tets.size(); ++c)
    {
        C[c] = cellCentre(p, tets[c]);
    }

    std::vector<vector3> sumS(tets.size(), {0, 0, 0});
    std::vector<int> nCellFaces(tets.size(), 0);

    for (label f = 0; f < mesh.nFaces(); ++f)
    {
        const triVerts& face = mesh.faces[f];
        const label own = mesh.owner[f];
        ASSERT_GE(own, 0);
        ASSERT_LT(own, mesh.nCells);

        const vector3 S = faceNormal(p, face);
        const point3 fc = centroid(p, {face[0], face[1], face[2]});

        // The face's points are points of its owner tet
        for (label v : face)
        {
            EXPECT_NE
            (
                std::find(tets[own].begin(), tets[own].end(), v),
                tets[own].end()
            ) << "face " << f << " has a point not on its owner";
        }

        sumS[own] = sumS[own] + S;
        ++nCellFaces[own];

        if (f < nInt)
        {
            const label nei = mesh.neighbour[f];
            EXPECT_LT(own, nei) << "face " << f;
            EXPECT_GT(dot(S, C[nei] - C[own]), 0)
                << "internal face " << f << " does not point owner->neighbour";
            sumS[nei] = sumS[nei] - S;
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

    for (std::size_t c = 0; c < tets.size(); ++c)
    {
        EXPECT_EQ(nCellFaces[c], 4) << "cell " << c;
        EXPECT_LT(std::sqrt(magSqr(sumS[c])), 1e-12) << "cell " << c << " not closed";
    }

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
