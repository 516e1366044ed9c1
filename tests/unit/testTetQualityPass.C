// The quality pass after HXT (tetQualityPass.H): face measures as
// checkMesh's, flips and smoothing that make the worst faces better, the
// boundary kept bit for bit, the tets positive and conforming.

#include "tetQualityPass.H"
#include "tetShape.H"
#include "tetFaceMatching.H"
#include "Geometry.H"
#include "meshPatch.H"
#include "partitionCoarseMesh.H"
#include "surfaceRefinement.H"
#include "testMeshers.H"
#include "checkMeshMeasures.H"
#include "testPaths.H"
#include "wallCells.H"
#include "qualityPassMeasures.H"

#include <gtest/gtest.h>

#include <cmath>

#include <cmath>
#include <algorithm>
#include <cstring>
#include <map>

using namespace pmsh;
using namespace pmsh::test;

namespace
{

//- The faces of the tets on one tet only, outward.
std::vector<triVerts> boundaryOf(const TetMesh& m)
{
    std::map<std::array<label, 3>, std::pair<int, triVerts>> faces;
    for (const tetVerts& c : m.tets)
    {
        for (const triVerts& f : outwardTetFaces(c))
        {
            std::array<label, 3> key = f;
            std::sort(key.begin(), key.end());
            auto& entry = faces[key];
            ++entry.first;
            entry.second = f;
        }
    }
    std::vector<triVerts> triangles;
    for (const auto& [key, entry] : faces)
    {
        if (entry.first == 1) triangles.push_back(entry.second);
    }
    return triangles;
}


//- Tets made positive by swapping two points where they are not.
void orientPositive(TetMesh& m)
{
    for (tetVerts& c : m.tets)
    {
        if (tetVolume6(m.points[c[0]], m.points[c[1]], m.points[c[2]], m.points[c[3]]) < 0)
        {
            std::swap(c[2], c[3]);
        }
    }
}


//- Throws unless the mesh keeps the first nFixed points of `before` bit
//  for bit, has positive tets and has `triangles` as its boundary.
void expectValid
(
    const TetMesh& m,
    const std::vector<point3>& before,
    std::size_t nFixed,
    const std::vector<triVerts>& triangles
)
{
    ASSERT_GE(m.points.size(), nFixed);
    for (std::size_t i = 0; i < nFixed; ++i)
    {
        EXPECT_EQ(std::memcmp(m.points[i].data(), before[i].data(), sizeof(point3)), 0)
            << "boundary point " << i << " moved";
    }
    for (const tetVerts& c : m.tets)
    {
        EXPECT_GT
        (
            tetVolume6(m.points[c[0]], m.points[c[1]], m.points[c[2]], m.points[c[3]]), 0
        );
    }
    const tetFaceMatch match = matchTetFaces(m.points.size(), m.tets, triangles);
    EXPECT_TRUE(match.fits()) << match.problems;
}


//- The unit cube's 12 outward boundary triangles on its 8 corners.
std::vector<triVerts> cubeTriangles()
{
    // Corner i at (i & 1, (i >> 1) & 1, (i >> 2) & 1)
    return
    {
        {0, 2, 3}, {0, 3, 1},   // z = 0
        {4, 5, 7}, {4, 7, 6},   // z = 1
        {0, 1, 5}, {0, 5, 4},   // y = 0
        {2, 6, 7}, {2, 7, 3},   // y = 1
        {0, 4, 6}, {0, 6, 2},   // x = 0
        {1, 3, 7}, {1, 7, 5}    // x = 1
    };
}

//- The unit cube as the star of one interior point: the tet of each of
//  its boundary triangles (cubeTriangles) and that point, its point 8.
TetMesh cubeStar(const point3& inside)
{
    TetMesh m;
    for (int i = 0; i < 8; ++i)
    {
        m.points.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
    }
    m.points.push_back(inside);
    for (const triVerts& f : cubeTriangles())
    {
        // An outward triangle and a point inside: (a, c, b, p) is positive
        m.tets.push_back({f[0], f[2], f[1], 8});
    }
    return m;
}

} // End anonymous namespace


TEST(tetQualityPass, measuresTheWorstFacesAsCheckMesh)
{
    // Two tets on the face (a, b, c), their apexes below and above its
    // centre, the upper one moved sideways by its height: the cell centres
    // are a quarter of the way to the apexes, so the line between them
    // leans by atan(1/2) and crosses the face 1/8 off its centre, which
    // normalised by the face's extent that way (2/3) is a skewness of
    // 0.1875, twice that moved twice as far (then the worst of all faces)
    const point3 centre{1.0/3, 1.0/3, 0};
    for (const double sideways : {0.0, 1.0, 2.0})
    {
        TetMesh m;
        m.points =
        {
            {0, 0, 0}, {1, 0, 0}, {0, 1, 0},
            centre + point3{0, 0, -1}, centre + point3{sideways, 0, 1}
        };
        m.tets = {{3, 0, 1, 2}, {4, 0, 1, 2}};
        orientPositive(m);
        const checkMeshMeasures expected = checkMeshMeasuresOf(m);
        EXPECT_NEAR(expected.maxNonOrthogonality, std::atan(sideways/2)*180/M_PI, 1e-9);
        EXPECT_NEAR(expected.maxInternalSkewness, sideways*0.1875, 1e-9);

        // The pass's own measures of the mesh it was given
        const qualityPassStats stats = improveWorstCells(m, 5, boundaryOf(m), {}, 0);
        EXPECT_NEAR(stats.worstBefore.nonOrthogonality, expected.maxNonOrthogonality, 1e-9);
        EXPECT_NEAR(stats.worstBefore.skewness, expected.maxSkewness(), 1e-9);
    }
}


TEST(tetQualityPass, movesABadInteriorPointAndKeepsTheBoundary)
{
    // The cube as the star of one interior point, put close to a corner:
    // the faces between the tets lean badly
    TetMesh m = cubeStar({0.1, 0.12, 0.08});
    const std::vector<triVerts> triangles = cubeTriangles();
    const std::vector<point3> before = m.points;
    const double worstBefore = checkMeshMeasuresOf(m).maxNonOrthogonality;

    const qualityPassStats stats = improveWorstCells(m, 8, triangles, {}, 3);

    expectValid(m, before, 8, triangles);
    EXPECT_GT(stats.nMoved, 0);
    const double worstAfter = checkMeshMeasuresOf(m).maxNonOrthogonality;
    EXPECT_LT(worstAfter, worstBefore - 10) << "from " << worstBefore;
    EXPECT_NEAR(stats.worstBefore.nonOrthogonality, worstBefore, 1e-9);
}


TEST(tetQualityPass, liftsAnInteriorPointThatSitsJustAboveTheWall)
{
    // The cube as the star of a point 4 % of an edge above its bottom: the
    // two tets on the bottom are flat cells on the wall, a tenth as high
    // as their faces are wide, of the kind simpleFoam diverged on (HXT's
    // sphereDrag mesh). One step lifts the point off the wall. (Here the
    // faces round the point lean badly too, so the pass lifted it before
    // flat wall cells counted; countsAFlatCellOnTheWallAsBadAsAFaceOf55Degrees
    // and hxtVolumeMesher.leavesNoCellFlatAgainstTheBodyOfABodyInAFarField
    // are the tests that fail without the wall rule.)
    TetMesh m = cubeStar({0.5, 0.45, 0.04});
    const std::vector<triVerts> triangles = cubeTriangles();
    const std::vector<point3> before = m.points;
    ASSERT_LT(test::flattestWallCell(m, triangles), 0.05);

    improveWorstCells(m, 8, triangles, {}, 1);

    expectValid(m, before, 8, triangles);
    EXPECT_GT(test::flattestWallCell(m, triangles), 0.2);
}


TEST(tetQualityPass, countsAFlatCellOnTheWallAsBadAsAFaceOf55Degrees)
{
    // An equilateral wall face of edge 1 and the fourth point of its cell
    // above its centre: its boundary face's non-orthogonality and
    // skewness are 0 at any height, so only the height tells a flat cell
    using namespace qualityPass;
    const point3 a{0, 0, 0};
    const point3 b{1, 0, 0};
    const point3 c{0.5, std::sqrt(3.0)/2, 0};
    const point3 centre = (1.0/3.0)*(a + b + c);
    auto badnessAt = [&](double height, bool flatCounts)
    {
        const point3 d = centre + point3{0, 0, -height};
        return badness(boundaryMeasure(a, b, c, d, flatCounts), false);
    };
    EXPECT_GT(badnessAt(0.04, true), worstFaceBadness);
    EXPECT_NEAR(badnessAt(0.999999*wallHeight, true), 1, 1e-5) << "as bad as a 55-degree face";
    EXPECT_NEAR(badnessAt(wallHeight/1.1, true), 1.21, 1e-6);
    EXPECT_NEAR(badnessAt(0.29, true), sqr(wallHeight/0.29), 1e-6) << "visited";
    EXPECT_LT(badnessAt(0.31, true), 1e-20) << "below the visiting threshold";
    EXPECT_LT(badnessAt(std::sqrt(2.0/3.0), true), 1e-20) << "a regular tet";
    EXPECT_LT(badnessAt(0.04, false), 1e-20) << "sliver removal alone: not counted";
}


TEST(tetQualityPass, flipsAFlatPairIntoThreeTets)
{
    // Two flat tets on a large triangle, their apexes just above and below
    // its centre, every point fixed: only a 2-3 flip can help, and the
    // three tets around the edge between the apexes are far better
    TetMesh m;
    m.points =
    {
        {0, 0, 0}, {1, 0, 0}, {0.5, 0.9, 0},       // the shared face
        {0.5, 0.3, -0.1}, {0.5, 0.3, 0.1}          // apexes below, above
    };
    // (d, a, b, c) is positive for the face (a, b, c) outward from it
    m.tets = {{3, 0, 1, 2}, {4, 0, 2, 1}};
    for (const tetVerts& c : m.tets)
    {
        ASSERT_GT(tetVolume6(m.points[c[0]], m.points[c[1]], m.points[c[2]], m.points[c[3]]), 0);
    }
    const std::vector<triVerts> triangles =
    {
        {3, 1, 0}, {3, 2, 1}, {3, 0, 2},            // lower tet's other faces
        {4, 0, 1}, {4, 1, 2}, {4, 2, 0}             // upper tet's
    };
    ASSERT_TRUE(matchTetFaces(5, m.tets, triangles).fits());
    const std::vector<point3> before = m.points;
    const double skewnessBefore = checkMeshMeasuresOf(m).maxSkewness();

    const qualityPassStats stats = improveWorstCells(m, 5, triangles, {}, 1);

    expectValid(m, before, 5, triangles);
    EXPECT_EQ(stats.nFlips, 1);
    EXPECT_EQ(m.tets.size(), 3u);
    EXPECT_LT(checkMeshMeasuresOf(m).maxSkewness(), skewnessBefore);
}


TEST(tetQualityPass, removesASliverWithAllItsPointsFixed)
{
    // A flat tet on a unit square (diagonal a-c just above diagonal b-d)
    // between two tets above its upper faces and two below its lower ones:
    // its faces are fair (checkMesh's non-orthogonality and skewness
    // would not flag it), but checkMesh fails its aspect ratio. Every
    // point is fixed: only removing edge a-c (3-2) mends it
    TetMesh m;
    const double h = 1e-7;
    m.points =
    {
        {0, 0, h}, {1, 0, -h}, {1, 1, h}, {0, 1, -h},   // a, b, c, d
        {0.5, 0.5, 1}, {0.5, 0.5, -1}                   // above, below
    };
    m.tets = {{0, 1, 2, 3}, {4, 0, 1, 2}, {4, 0, 2, 3}, {5, 1, 3, 0}, {5, 1, 3, 2}};
    orientPositive(m);
    const std::vector<triVerts> triangles = boundaryOf(m);
    ASSERT_TRUE(matchTetFaces(6, m.tets, triangles).fits());
    const std::vector<point3> before = m.points;

    const qualityPassStats stats = improveWorstCells(m, 6, triangles, {}, 1);

    expectValid(m, before, 6, triangles);
    EXPECT_EQ(stats.nFlips, 1);
    ASSERT_EQ(m.tets.size(), 4u);
    for (const tetVerts& c : m.tets)
    {
        const point3* p[4] = {&m.points[c[0]], &m.points[c[1]], &m.points[c[2]], &m.points[c[3]]};
        EXPECT_GT(tetVolume6(*p[0], *p[1], *p[2], *p[3]), 0.1);
    }
}


TEST(tetQualityPass, edgeRemovalKeepsTheRingsTurnWhereTheRingIsNotConvex)
{
    // Six tets around edge a-b whose ring of points is not convex (the
    // last point sits in towards the edge), every point fixed. A
    // triangulation of the ring with a triangle outside it makes a
    // positive tet of that triangle if each triangle is oriented by the
    // sign of its own tet: the new tets then overlap, and a partition's
    // mesh failed the volume contract ("overlapping tets") for it (a body
    // with layers, hxt). Oriented by the ring's turn, that triangle's tets
    // are inverted and the triangulation is refused. (One of the two
    // failures among 20,000 random rings of 4-6 points with one point
    // sitting in.)
    TetMesh m;
    m.points =
    {
        {0.023999824278483642, 0.039103107411750763, 0.61892283574059637},      // a
        {-0.04446316776704503, -0.028854405141051212, -0.28906075054686431},    // b
        {0.97855583267206403, -0.1133295121567717, 0.099237571709696965},
        {0.39193020906876319, 0.89566285437437043, -0.044455476211786242},
        {-0.51918049120323906, 1.2189624565469399, -0.051615375693474498},
        {-1.3865375517444165, -0.003931394954943386, -0.021939155710737124},
        {-0.56159350201107539, -0.90676747886431863, 0.038083923789667073},
        {0.098122803612446977, -0.16882298485686259, 0.0072029108829158028}     // sits in
    };
    m.tets = {{0, 1, 3, 2}, {0, 1, 4, 3}, {0, 1, 5, 4}, {0, 1, 6, 5}, {0, 1, 7, 6}, {0, 1, 2, 7}};
    const std::vector<triVerts> triangles = boundaryOf(m);
    ASSERT_TRUE(matchTetFaces(m.points.size(), m.tets, triangles).fits());
    const std::vector<point3> before = m.points;

    improveWorstCells(m, label(before.size()), triangles, {}, 1);

    expectValid(m, before, before.size(), triangles);
}


TEST(tetQualityPass, aFlatTetThatNoFlipMendsGetsAPointInTheFullPassToo)
{
    // A tet flat to the last bit (HXT returns one now and then) on a unit
    // square: diagonal a-c lies on the boundary below, diagonal b-d inside,
    // with a fan of eight tets around b-d above it (apexes on an arc from
    // a's side to c's). Every point is fixed and every other edge of the
    // flat tet is on the boundary: the ring around b-d is too large to
    // flip, and no 2-3 flip sees across it. Only a new point inside the
    // ring mends it; without one the mesh stays invalid
    TetMesh m;
    const double h = 1e-3;      // a-c below b-d while orienting, then flat
    m.points = {{0, 0, -h}, {1, 0, h}, {1, 1, -h}, {0, 1, h}};
    const int nArc = 6;
    for (int i = 1; i <= nArc; ++i)
    {
        const double theta = M_PI*(1 - double(i)/(nArc + 1));
        const double along = 0.5*std::cos(theta)/std::sqrt(2.0);
        m.points.push_back({0.5 + along, 0.5 + along, 0.5*std::sin(theta)});
    }
    m.tets = {{0, 1, 2, 3}, {0, 1, 3, 4}};
    for (int i = 1; i < nArc; ++i)
    {
        m.tets.push_back({3 + i, 4 + i, 1, 3});
    }
    m.tets.push_back({3 + nArc, 2, 1, 3});
    orientPositive(m);
    const std::vector<triVerts> triangles = boundaryOf(m);
    for (label p = 0; p < 4; ++p) m.points[p][2] = 0;
    const point3* a[4] = {&m.points[0], &m.points[1], &m.points[2], &m.points[3]};
    ASSERT_EQ(tetVolume6(*a[0], *a[1], *a[2], *a[3]), 0);
    ASSERT_TRUE(matchTetFaces(m.points.size(), m.tets, triangles).fits());
    const std::vector<point3> before = m.points;

    const qualityPassStats stats = improveWorstCells(m, label(before.size()), triangles, {}, 3);

    expectValid(m, before, before.size(), triangles);
    // The flat tet's point; the worst faces' steps may add one for a face
    // of the fan
    EXPECT_GE(stats.nInserted, 1);
}


TEST(tetQualityPass, sliverRemovalRemovesASliverAndLeavesFairCellsAlone)
{
    // optimisationSteps 0: the sliver above (aspect ratio far above the
    // 1000 checkMesh accepts) goes, as with a step of the pass
    {
        TetMesh m;
        const double h = 1e-7;
        m.points =
        {
            {0, 0, h}, {1, 0, -h}, {1, 1, h}, {0, 1, -h},
            {0.5, 0.5, 1}, {0.5, 0.5, -1}
        };
        m.tets = {{0, 1, 2, 3}, {4, 0, 1, 2}, {4, 0, 2, 3}, {5, 1, 3, 0}, {5, 1, 3, 2}};
        orientPositive(m);
        const std::vector<triVerts> triangles = boundaryOf(m);
        const std::vector<point3> before = m.points;
        ASSERT_GT(tetShapeRangeOf(m).maxAspectRatio, maxAcceptedAspectRatio);

        const qualityPassStats stats = removeSlivers(m, 6, triangles, {});

        expectValid(m, before, 6, triangles);
        EXPECT_EQ(stats.nFlips, 1);
        EXPECT_LE(tetShapeRangeOf(m).maxAspectRatio, maxAcceptedAspectRatio);
    }

    // A cube's star around an interior point off its centre: faces the
    // pass's steps make better (about 60 degrees), but that checkMesh
    // accepts: sliver removal leaves them as they are
    {
        TetMesh m = cubeStar({0.12, 0.15, 0.1});
        const std::vector<triVerts> triangles = cubeTriangles();
        const TetMesh original = m;
        const double worst = checkMeshMeasuresOf(m).maxNonOrthogonality;
        ASSERT_GT(worst, 50);
        ASSERT_LT(worst, 75);

        const qualityPassStats stats = removeSlivers(m, 8, triangles, {});
        EXPECT_EQ(stats.nMoved + stats.nFlips, 0);
        EXPECT_EQ(m.points, original.points);
        EXPECT_EQ(m.tets, original.tets);

        TetMesh improved = original;
        EXPECT_GT(improveWorstCells(improved, 8, triangles, {}, 3).nMoved, 0);
    }
}


TEST(tetQualityPass, partitionMeshesGetBetterAndKeepTheirSurface)
{
    // Both partitions of a refined sphere, with processor faces: Netgen's
    // meshes without its optimiser, then the pass; and HXT with the pass
    // (its contract, checked by VolumeMesher::mesh, holds)
    auto g = Geometry::New(std::string(PMSH_TEST_DATA) + "/geometry/sphere.geo");
    const CoarseMesh coarse = g->coarseMesh({0.3, 0.3});
    const std::vector<label> cellPart = partitionCells(coarse, 2);
    for (label part = 0; part < 2; ++part)
    {
        const FineSurface s = refinePartSurface(coarse, cellPart, part, g.get(), 2);
        volumeMeshParameters p;
        p.maxCellSize = 0.3/4;
        for (label region : s.region)
        {
            p.interfaceTriangles.push_back(isInterfaceRegion(region));
        }
        ASSERT_TRUE
        (
            std::find(p.interfaceTriangles.begin(), p.interfaceTriangles.end(), 1)
         != p.interfaceTriangles.end()
        );

        p.optimisationSteps = 0;
        TetMesh m = VolumeMesher::New("netgen")->mesh(s.points, s.triangles, p);
        const checkMeshMeasures before = checkMeshMeasuresOf(m);
        const qualityPassStats stats = improveWorstCells
        (
            m, label(s.points.size()), s.triangles, p.interfaceTriangles, 3
        );
        expectValid(m, s.points, s.points.size(), s.triangles);
        EXPECT_GT(stats.nFlips + stats.nMoved, 0);
        const checkMeshMeasures after = checkMeshMeasuresOf(m);
        EXPECT_LT(after.maxNonOrthogonality, before.maxNonOrthogonality - 5)
            << "partition " << part;
        EXPECT_LE(after.maxSkewness(), before.maxSkewness()) << "partition " << part;

        p.optimisationSteps = 3;
        const TetMesh h = VolumeMesher::New("hxt")->mesh(s.points, s.triangles, p);
        expectValid(h, s.points, s.points.size(), s.triangles);
    }
}



TEST(tetQualityPass, theWorstFacesGetAPointWhereNoFlipOrMoveMendsThem)
{
    // HXT's raw mesh of a sphere partition with every point fixed: no
    // smoothing but of new points, so what flips leave of the worst faces
    // only a new point can mend, in the worst faces' steps
    auto g = Geometry::New(std::string(PMSH_TEST_DATA) + "/geometry/sphere.geo");
    const CoarseMesh coarse = g->coarseMesh({0.3, 0.3});
    const std::vector<label> cellPart = partitionCells(coarse, 2);
    const FineSurface s = refinePartSurface(coarse, cellPart, 0, g.get(), 2);
    volumeMeshParameters p;
    p.maxCellSize = 0.3/4;
    p.optimisationSteps = 0;
    TetMesh m = VolumeMesher::New("hxt")->mesh(s.points, s.triangles, p);
    const std::vector<point3> fixedPoints = m.points;
    const checkMeshMeasures before = checkMeshMeasuresOf(m);

    const qualityPassStats stats = improveWorstCells
    (
        m, label(fixedPoints.size()), s.triangles, {}, 1
    );

    expectValid(m, fixedPoints, fixedPoints.size(), s.triangles);
    EXPECT_GT(stats.nInsertedAtWorstFaces, 0);
    EXPECT_LT(checkMeshMeasuresOf(m).maxNonOrthogonality, before.maxNonOrthogonality);
}


TEST(tetQualityPass, measuresARealMeshAsCheckMesh)
{
    // The pass's worst faces of a whole sphere as Netgen meshes it without
    // its optimiser (a real mesh: thousands of faces, the worst skewness
    // on an internal one), against checkMesh's formulas written out apart
    // from the pass (checkMeshMeasuresOf). summary.json's quality, from
    // the same kernel, is compared with checkMesh itself by the tutorial
    // test sphere.test_faceMetricsAsCheckMesh.
    auto g = Geometry::New(std::string(PMSH_TEST_DATA) + "/geometry/sphere.geo");
    const CoarseMesh coarse = g->coarseMesh({0.3, 0.3});
    const std::vector<label> cellPart(coarse.tets.size(), 0);
    const FineSurface s = refinePartSurface(coarse, cellPart, 0, g.get(), 1);
    volumeMeshParameters p;
    p.maxCellSize = 0.3/2;
    p.optimisationSteps = 0;
    TetMesh m = VolumeMesher::New("netgen")->mesh(s.points, s.triangles, p);
    ASSERT_GT(m.tets.size(), 1000u);
    const checkMeshMeasures expected = checkMeshMeasuresOf(m);

    const qualityPassStats stats = improveWorstCells
    (
        m, label(s.points.size()), s.triangles, {}, 0
    );
    EXPECT_GT(expected.maxNonOrthogonality, 0);
    EXPECT_NEAR(stats.worstBefore.nonOrthogonality, expected.maxNonOrthogonality, 1e-9);
    EXPECT_NEAR(stats.worstBefore.skewness, expected.maxSkewness(), 1e-9);
}

// ************************************************************************* //
