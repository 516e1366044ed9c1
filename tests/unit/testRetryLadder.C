// The retry ladder (retryLadder.H) that the STL coarse mesh and the volume
// meshing of a partition climb: attempts in order until one succeeds,
// every failure's reason kept, a stopping failure or a refused start ending
// the climb.

#include "retryLadder.H"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace pmsh;

namespace
{

//- n attempts: attempt i's parameter is 10 i, its change "try i" (none
//  for the first)
std::vector<ladderAttempt<int>> numbered(int n)
{
    std::vector<ladderAttempt<int>> attempts;
    for (int i = 0; i < n; ++i)
    {
        attempts.push_back({10*i, i == 0 ? "" : "try " + std::to_string(i)});
    }
    return attempts;
}

} // End anonymous namespace


TEST(retryLadder, climbsUntilAnAttemptSucceedsKeepingTheEarlierReasons)
{
    const auto attempts = numbered(4);
    std::vector<std::size_t> ran;
    ladderFailures failed;
    const auto result = climbLadder
    (
        attempts,
        [&](const ladderAttempt<int>& a, std::size_t i)
        {
            ran.push_back(i);
            if (a.parameters < 20)
            {
                throw attemptFailed{"no " + std::to_string(a.parameters)};
            }
            return a.parameters;
        },
        failed
    );
    ASSERT_TRUE(result.has_value());
    EXPECT_EQ(*result, 20);
    EXPECT_EQ(ran, (std::vector<std::size_t>{0, 1, 2}));
    EXPECT_EQ(failed.reasons, (std::vector<std::string>{"no 0", "no 10"}));
    EXPECT_FALSE(failed.stopped);
}


TEST(retryLadder, allFailingGivesNoResultAndEveryReason)
{
    const auto attempts = numbered(3);
    ladderFailures failed;
    const auto result = climbLadder
    (
        attempts,
        [](const ladderAttempt<int>& a, std::size_t) -> int
        {
            throw attemptFailed{a.change};
        },
        failed
    );
    EXPECT_FALSE(result.has_value());
    EXPECT_EQ(failed.reasons, (std::vector<std::string>{"", "try 1", "try 2"}));
    EXPECT_EQ(failed.nTried(), 3u);
    EXPECT_FALSE(failed.stopped);
}


TEST(retryLadder, aStoppingFailureEndsTheClimb)
{
    const auto attempts = numbered(4);
    ladderFailures failed;
    const auto result = climbLadder
    (
        attempts,
        [](const ladderAttempt<int>& a, std::size_t i) -> int
        {
            throw attemptFailed{a.change, i == 1};
        },
        failed
    );
    EXPECT_FALSE(result.has_value());
    EXPECT_EQ(failed.nTried(), 2u);
    EXPECT_TRUE(failed.stopped);
}


TEST(retryLadder, aRefusedStartEndsTheClimbWithoutAReason)
{
    const auto attempts = numbered(4);
    ladderFailures failed;
    const auto result = climbLadder
    (
        attempts,
        [](const ladderAttempt<int>& a, std::size_t) -> int
        {
            throw attemptFailed{a.change};
        },
        failed,
        [](std::size_t i) { return i < 2; }
    );
    EXPECT_FALSE(result.has_value());
    EXPECT_EQ(failed.reasons, (std::vector<std::string>{"", "try 1"}));
    EXPECT_FALSE(failed.stopped);
}


// ************************************************************************* //
