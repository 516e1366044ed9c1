/*---------------------------------------------------------------------------*\
  Tests of a patch's prism layer entries (src/layers/layerSpecification):
  the spec read from a patch's sub-dictionary with OpenFOAM's readers, the
  layers' thicknesses from any consistent pair of entries, and the
  FatalIOError every problem raises (entry, valid values, file and line).
\*---------------------------------------------------------------------------*/

#include "layerSpecification.H"
#include "foamShims.H"
#include "testUtilities.H"

#include "error.H"
#include "IStringStream.H"

#include <gtest/gtest.h>

#include <cmath>

using namespace pmsh;
using namespace pmsh::test;

namespace
{

//- The spec of a patch sub-dictionary with these entries, read as if the
//  first line were line 1 of system/pmshDict.
layerSpecification specOf(const std::string& entries)
{
    Foam::FatalIOError.throwExceptions();
    Foam::FatalError.throwExceptions();
    Foam::autoPtr<Foam::IStringStream> is =
        foam::namedStringStream("case/system/pmshDict", entries);
    is->lineNumber(1);
    return readLayerSpecification(Foam::dictionary(is()), "ball");
}


//- The FatalIOError message of reading these entries, with its line.
std::string errorFor(const std::string& entries)
{
    try
    {
        specOf(entries);
    }
    catch (const Foam::IOerror& e)
    {
        return e.message() + " at line " + std::to_string(e.ioStartLineNumber());
    }
    catch (const Foam::error& e)
    {
        return e.message();
    }
    return "";
}

} // End anonymous namespace


TEST(layerSpecification, readsTheIssuesExample)
{
    const layerSpecification s = specOf
    (
        "type wall;\nmaxCellSize 0.1;\nlayers 5;\n"
        "firstLayerThickness 0.002;\nexpansionRatio 1.2;\n"
    );
    EXPECT_EQ(s.nLayers, 5);
    EXPECT_DOUBLE_EQ(s.firstLayerThickness, 0.002);
    EXPECT_DOUBLE_EQ(s.expansionRatio, 1.2);
    EXPECT_DOUBLE_EQ(s.layerThickness(3), 0.002*1.44);
    EXPECT_NEAR(s.totalThickness(), 0.002*(1 + 1.2 + 1.44 + 1.728 + 2.0736), 1e-15);
    EXPECT_DOUBLE_EQ(s.finalLayerThickness(), 0.002*2.0736);
    EXPECT_EQ(s.levelOffset(0), 0);
    EXPECT_EQ(s.levelOffset(5), s.totalThickness());
    // Defaults
    EXPECT_DOUBLE_EQ(s.minThickness, 0.002);
    EXPECT_DOUBLE_EQ(s.featureAngle, 60);
    EXPECT_DOUBLE_EQ(s.maxThicknessToGapRatio, 0.4);
}


TEST(layerSpecification, noLayersByDefault)
{
    EXPECT_FALSE(specOf("type wall;\n").layered());
    // layers 0 switches them off and keeps the other entries valid
    EXPECT_FALSE(specOf("layers 0;\nfirstLayerThickness 0.1;\n").layered());
    EXPECT_DOUBLE_EQ(specOf("layers 3;\nfirstLayerThickness 0.1;\n").expansionRatio, 1.2);
}


TEST(layerSpecification, thicknessFromAnyConsistentPair)
{
    // One thickness with the ratio
    EXPECT_DOUBLE_EQ(specOf("layers 5;\nfinalLayerThickness 16;\nexpansionRatio 2;\n").firstLayerThickness, 1);
    EXPECT_NEAR(specOf("layers 3;\ntotalThickness 4.75;\nexpansionRatio 1.5;\n").firstLayerThickness, 1, 1e-14);

    // Two thicknesses: the ratio follows
    const layerSpecification firstFinal = specOf("layers 5;\nfirstLayerThickness 1;\nfinalLayerThickness 16;\n");
    EXPECT_NEAR(firstFinal.expansionRatio, 2, 1e-12);
    EXPECT_NEAR(firstFinal.finalLayerThickness(), 16, 1e-10);

    const layerSpecification firstTotal = specOf("layers 3;\nfirstLayerThickness 1;\ntotalThickness 4.75;\n");
    EXPECT_NEAR(firstTotal.expansionRatio, 1.5, 1e-12);
    EXPECT_NEAR(firstTotal.totalThickness(), 4.75, 1e-10);

    const layerSpecification finalTotal = specOf("layers 3;\nfinalLayerThickness 2.25;\ntotalThickness 4.75;\n");
    EXPECT_NEAR(finalTotal.expansionRatio, 1.5, 1e-12);
    EXPECT_NEAR(finalTotal.firstLayerThickness, 1, 1e-10);

    // Uniform layers
    EXPECT_EQ(specOf("layers 4;\nfirstLayerThickness 0.5;\ntotalThickness 2;\n").expansionRatio, 1);
}


TEST(layerSpecification, readsTheLimits)
{
    const layerSpecification s = specOf
    (
        "layers 2;\nfirstLayerThickness 1;\nexpansionRatio 1;\nminThickness 0.5;\n"
        "featureAngle 45;\nmaxThicknessToGapRatio 0.25;\n"
    );
    EXPECT_EQ(s.minThickness, 0.5);
    EXPECT_EQ(s.featureAngle, 45);
    EXPECT_EQ(s.maxThicknessToGapRatio, 0.25);
}


TEST(layerSpecification, wrongValuesSayWhatIsWrongAsEveryPmshDictEntryDoes)
{
    // The one reader of pmshDict's entries (dictEntries.H): a layer entry
    // that is no number, or no integer where one is needed, says so, with
    // the value and the valid range, as the top-level entries do
    const std::string half = errorFor("layers 2.5;\nfirstLayerThickness 1;\n");
    EXPECT_HAS(half, "Entry 'layers' of patch 'ball' is 2.5 (not an integer)");
    EXPECT_HAS(half, "Valid values are 0 (no layers) .. 100");
    const std::string word = errorFor("layers 3;\nfirstLayerThickness thin;\n");
    EXPECT_HAS(word, "Entry 'firstLayerThickness' of patch 'ball' is thin (not a number)");
    EXPECT_HAS(word, "at line 2");
}


TEST(layerSpecification, errorsNameTheEntryTheValidValuesAndTheLine)
{
    const std::string layers = errorFor("type wall;\nlayers 101;\nfirstLayerThickness 1;\n");
    EXPECT_HAS(layers, "Entry 'layers' of patch 'ball' is 101");
    EXPECT_HAS(layers, "Valid values are 0 (no layers) .. 100");
    EXPECT_HAS(layers, "at line 2");

    EXPECT_HAS(errorFor("layers -1;\nfirstLayerThickness 1;\n"), "Entry 'layers' of patch 'ball' is -1");

    const std::string ratio = errorFor("layers 3;\nfirstLayerThickness 1;\nexpansionRatio 0.5;\n");
    EXPECT_HAS(ratio, "Entry 'expansionRatio' of patch 'ball' is 0.5");
    EXPECT_HAS(ratio, "Valid values are >= 1 and <= 5");
    EXPECT_HAS(ratio, "at line 3");

    EXPECT_HAS(errorFor("layers 3;\nfirstLayerThickness 0;\n"), "Valid values are > 0");
    EXPECT_HAS(errorFor("layers 3;\nfirstLayerThickness 1;\nfeatureAngle 200;\n"), "Entry 'featureAngle' of patch 'ball' is 200");
    EXPECT_HAS(errorFor("layers 3;\nfirstLayerThickness 1;\nmaxThicknessToGapRatio 0.6;\n"), "Valid values are > 0 and <= 0.5");
    EXPECT_HAS(errorFor("layers 2;\nfirstLayerThickness 1;\nexpansionRatio 1;\nminThickness 3;\n"), "Entry 'minThickness' of patch 'ball' is 3");
}


TEST(layerSpecification, thicknessEntriesMustBeOneOrAConsistentPair)
{
    const std::string none = errorFor("type wall;\nlayers 3;\n");
    EXPECT_HAS(none, "Patch 'ball' has layers 3 and no thickness");
    EXPECT_HAS(none, "Give one of firstLayerThickness, finalLayerThickness and totalThickness");
    EXPECT_HAS(none, "at line 2");

    EXPECT_HAS
    (
        errorFor("layers 3;\nfirstLayerThickness 1;\nfinalLayerThickness 2;\ntotalThickness 4;\n"),
        "too many thickness entries"
    );
    EXPECT_HAS
    (
        errorFor("layers 3;\nfirstLayerThickness 1;\ntotalThickness 4;\nexpansionRatio 1.2;\n"),
        "too many thickness entries"
    );

    // Thinner layers outwards would need a ratio below 1
    const std::string misfit = errorFor("layers 3;\nfirstLayerThickness 1;\ntotalThickness 2;\n");
    EXPECT_HAS(misfit, "Entries 'firstLayerThickness' and 'totalThickness' of patch 'ball' do not fit 3 layers");
    EXPECT_HAS(misfit, "at line 3");
}


TEST(layerSpecification, layerEntriesNeedLayers)
{
    const std::string e = errorFor("type wall;\nfirstLayerThickness 0.1;\n");
    EXPECT_HAS(e, "Entry 'firstLayerThickness' of patch 'ball' needs 'layers'");
    EXPECT_HAS(e, "at line 2");
}


TEST(layerSpecification, entriesListsEveryEntryItReads)
{
    // Each listed entry without 'layers' is refused as an entry this code
    // reads (not silently ignored)
    for (const std::string& key : layerSpecificationEntries())
    {
        if (key == "layers") continue;
        EXPECT_HAS(errorFor(key + " 1;\n"), "Entry '" + key + "' of patch 'ball' needs 'layers'");
    }
}
