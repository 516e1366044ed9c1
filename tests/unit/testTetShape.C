// The shape of tets as OpenFOAM judges it (tetShape.H): checkMesh's aspect
// ratio, and the dihedral and aspect-ratio extremes of a mesh.

#include "tetShape.H"

#include <gtest/gtest.h>

#include <cmath>

using namespace pmsh;

TEST(tetShape, aspectRatioIsCheckMeshs)
{
    // The corner tet of the unit cube: the face area magnitudes sum to
    // (1 1 1) component by component and the volume is 1/6, so
    // cellClosedness gives max(1, 3/6/(1/6)^(2/3)) = 1.6510
    const point3 o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
    EXPECT_NEAR(tetAspectRatio(o, x, y, z), 0.5/std::cbrt(1.0/36), 1e-12);

    // Scaled and moved: the same
    const auto f = [](const point3& p) { return point3{3*p[0] + 1, 3*p[1] - 2, 3*p[2]}; };
    EXPECT_NEAR(tetAspectRatio(f(o), f(x), f(y), f(z)), tetAspectRatio(o, x, y, z), 1e-12);

    // Stretched along z: the component ratio takes over (the x and y
    // faces grow, the z faces do not: sumMag = (10, 10, 1))
    EXPECT_NEAR(tetAspectRatio(o, x, y, point3{0, 0, 10}), 10, 1e-12);

    // Flat or inverted: infinite, never accepted
    EXPECT_GT(tetAspectRatio(o, x, y, point3{0.3, 0.3, 1e-5}), maxAcceptedAspectRatio);
    EXPECT_TRUE(std::isinf(tetAspectRatio(o, x, y, point3{0.3, 0.3, 0})));
    EXPECT_TRUE(std::isinf(tetAspectRatio(o, y, x, z)));
}


TEST(tetShape, rangeOfAMeshFindsItsWorstTet)
{
    TetMesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.3, 0.3, -1e-3}};
    m.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
    const tetShapeRange r = tetShapeRangeOf(m);
    EXPECT_NEAR(r.maxAspectRatio, tetAspectRatio(m.points[0], m.points[2], m.points[1], m.points[4]), 1e-9);
    EXPECT_GT(r.maxAspectRatio, 100);
    // The corner tet has right dihedral angles at its axes, the flat one
    // nearly 0 and nearly 180 degrees
    EXPECT_LT(r.minDihedral, 1);
    EXPECT_GT(r.maxDihedral, 179);
}
