// The estimate's count of tets from the fine size field
// (forecast/sizeFieldCells.H), on the structured unit cube of cubeMesh.H:
// each refinement level gives 8 times the tets of a uniform field and
// fewer of a graded one (its interior grows from the finer surface at the
// same rate, as the meshers' does), a region of small size
// adds tets and faster grading takes them away, and the layers' volume
// comes off in proportion to the stacks' thickness, never below a tenth.

#include "cubeMesh.H"
#include "sizeFieldCells.H"

#include <gtest/gtest.h>

using namespace pmsh;

namespace
{

const CoarseMesh& cube()
{
    static const CoarseMesh m = test::cubeMesh(6);
    return m;
}

sizeFieldTerms termsOf
(
    int r,
    double grading = 0.3,
    const std::vector<sizeRegion>& regions = {},
    const std::map<label, layerSpecification>& layers = {}
)
{
    // maxCellSize far above the cube's edges: the field grows from the
    // boundary as grading lets it
    return sizeFieldCells(cube(), 10, grading, r, regions, layers);
}

layerSpecification stack(double firstLayer)
{
    layerSpecification s;
    s.nLayers = 3;
    s.firstLayerThickness = firstLayer;
    s.expansionRatio = 1.2;
    return s;
}

} // End anonymous namespace


TEST(sizeFieldCells, eachLevelGivesEightTimesTheTetsOfAUniformFieldAndFewerOfAGradedOne)
{
    const sizeFieldTerms one = termsOf(1, 0), two = termsOf(2, 0);
    EXPECT_GT(one.sizeField, 0);
    EXPECT_NEAR(two.sizeField/one.sizeField, 8, 1e-9);
    EXPECT_NEAR(two.coarse/one.coarse, 8, 1e-12);
    EXPECT_DOUBLE_EQ(one.coarse, 8.0*cube().nCells());

    const double graded = termsOf(2).sizeField/termsOf(1).sizeField;
    EXPECT_GT(graded, 2);
    EXPECT_LT(graded, 7);
}


TEST(sizeFieldCells, aUniformFieldHoldsTheVolumeOverTheSizeCubed)
{
    // No grading: the smallest boundary size everywhere. The cube's
    // smallest mean boundary edge is at a corner point of a face
    // diagonal's end; whatever it is, every tet has that size
    const sizeFieldTerms t = termsOf(0, 0);
    const double s = std::cbrt(1/t.sizeField);
    EXPECT_GT(s, 1.0/6);                     // above the axis edges
    EXPECT_LT(s, std::sqrt(2.0)/6);          // below the face diagonals
}


TEST(sizeFieldCells, aSmallRegionAddsTetsAndFasterGradingTakesThemAway)
{
    sizeRegion centre;
    centre.type = sizeRegion::shape::box;
    centre.min = {0.3, 0.3, 0.3};
    centre.max = {0.7, 0.7, 0.7};
    centre.size = 0.01;
    const double plain = termsOf(1).sizeField;
    EXPECT_GT(termsOf(1, 0.3, {centre}).sizeField, 2*plain);
    EXPECT_LT(termsOf(1, 0.6).sizeField, plain);
    EXPECT_GT(termsOf(1, 0.1).sizeField, plain);
}


TEST(sizeFieldCells, theLayersVolumeComesOffInProportionToTheStackButNeverBelowATenth)
{
    const sizeFieldTerms bare = termsOf(1);
    EXPECT_EQ(bare.layers, 0);
    const label zMin = 4;
    const sizeFieldTerms thin = termsOf(1, 0.3, {}, {{zMin, stack(0.001)}});
    const sizeFieldTerms thick = termsOf(1, 0.3, {}, {{zMin, stack(0.002)}});
    EXPECT_GT(thin.layers, 0);
    EXPECT_NEAR(thick.layers/thin.layers, 2, 1e-9);
    EXPECT_LT(thin.weighted(), bare.weighted());
    EXPECT_DOUBLE_EQ(thin.sizeField, bare.sizeField);

    // Stacks thicker than the cube: the tets never go below a tenth
    const sizeFieldTerms huge = termsOf(1, 0.3, {}, {{zMin, stack(10)}});
    EXPECT_DOUBLE_EQ
    (
        huge.weighted(),
        0.1*huge.sizeField + sizeFieldTerms::coarseShare*huge.coarse
    );
}
