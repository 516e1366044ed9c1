// What the OpenFOAM build's label can hold: a count past the limit stops,
// naming the label size, the count and the cure. Counts past 2^31 and 2^32
// through the real numbering are tested in tests/mpi/testParallelNumbering.C.

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
    EXPECT_NO_THROW(checkFitsLabel(0, "points"));
    EXPECT_NO_THROW(checkFitsLabel(labelLimit, "cells"));
}


TEST(labelLimit, aCountPastTheLimitStopsNamingTheLabelSizeTheCountAndTheCure)
{
    if (labelBits == 64)
    {
        // Every count is a 64-bit integer: past 32-bit labels, none stops
        EXPECT_NO_THROW(checkFitsLabel(3000000000, "cells"));
        EXPECT_NO_THROW(checkFitsLabel(labelLimit, "cells"));
        return;
    }
    const std::string error = test::errorOf([&]
    {
        checkFitsLabel(std::int64_t(1) << 31, "faces");     // labelLimit + 1
    });
    EXPECT_HAS
    (
        error,
        "too large for this OpenFOAM's 32-bit labels (largest label 2147483647)"
    );
    EXPECT_HAS(error, "it has 2147483648 faces");
    EXPECT_HAS(error, "WM_LABEL_SIZE=64");
    EXPECT_HAS(error, "fewer refinementLevels");
}
