// What the OpenFOAM build's label can hold: a count past the limit stops,
// naming the label size, the count and the cure; the limit is lowered here
// so that a small count reaches it. Counts past 2^31 and 2^32 through the
// real numbering are tested in tests/mpi/testParallelNumbering.C.

#include "labelLimit.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <cstdint>
#include <type_traits>

using namespace pmsh;


TEST(labelLimit, pmshLabelIsTheOpenFOAMBuildsLabel)
{
    static_assert(std::is_same<label, Foam::label>::value, "pmsh::label is Foam::label");
    EXPECT_EQ(labelBits, WM_LABEL_SIZE);
    EXPECT_EQ(labelLimit, std::int64_t(Foam::labelMax));
}


TEST(labelLimit, countsUpToTheLimitPass)
{
    EXPECT_NO_THROW(checkFitsLabel(100, "faces", 100));
    EXPECT_NO_THROW(checkFitsLabel(0, "points", 100));
    EXPECT_NO_THROW(checkFitsLabel(labelLimit, "cells"));
}


TEST(labelLimit, aCountPastTheLimitStopsNamingTheLabelSizeTheCountAndTheCure)
{
    const std::string error = test::errorOf([&]
    {
        checkFitsLabel(101, "faces", 100);
    });
    EXPECT_HAS
    (
        error,
        "too large for this OpenFOAM's " + std::to_string(labelBits)
      + "-bit labels (largest label 100)"
    );
    EXPECT_HAS(error, "it has 101 faces");
    EXPECT_HAS(error, "WM_LABEL_SIZE=64");
    EXPECT_HAS(error, "fewer refinementLevels");
}


TEST(labelLimit, theBuildsOwnLimitStopsOnlyWhereItsLabelsCannotHoldTheCount)
{
    // Three billion: past 32-bit labels, far within 64-bit ones
    const std::int64_t threeBillion = 3000000000;
    if (labelBits == 32)
    {
        EXPECT_HAS
        (
            test::errorOf([&] { checkFitsLabel(threeBillion, "cells"); }),
            "32-bit labels (largest label 2147483647): it has 3000000000 cells"
        );
    }
    else
    {
        EXPECT_NO_THROW(checkFitsLabel(threeBillion, "cells"));
    }
}
