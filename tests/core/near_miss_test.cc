// Near-miss suggestions (core/near_miss.h): edit distance with adjacent
// transpositions, and which candidate is close enough to suggest.
#include <gtest/gtest.h>

#include "core/near_miss.h"

namespace {

TEST(NearMiss, EditDistance) {
  EXPECT_EQ(ipstep::EditDistance("", ""), 0);
  EXPECT_EQ(ipstep::EditDistance("abc", ""), 3);
  EXPECT_EQ(ipstep::EditDistance("optimiser", "optimizer"), 1);  // substitution
  EXPECT_EQ(ipstep::EditDistance("tolerence", "tolerance"), 1);
  EXPECT_EQ(ipstep::EditDistance("newtn", "newton"), 1);  // insertion
  EXPECT_EQ(ipstep::EditDistance("stpes", "steps"), 1);   // transposition
  EXPECT_EQ(ipstep::EditDistance("kitten", "sitting"), 3);
}

TEST(NearMiss, SuggestsOnlyCloseNames) {
  const std::vector<std::string> flags = {"optimizer", "optimizers", "scene", "steps", "dt"};
  EXPECT_EQ(ipstep::NearMiss("optimiser", flags), "optimizer");
  EXPECT_EQ(ipstep::NearMiss("optimisers", flags), "optimizers");
  EXPECT_EQ(ipstep::NearMiss("sene", flags), "scene");
  EXPECT_EQ(ipstep::NearMiss("stpes", flags), "steps");
  EXPECT_EQ(ipstep::NearMiss("dx", flags), "dt");
  EXPECT_EQ(ipstep::NearMiss("xy", flags), "");  // 2 edits in a short name
  EXPECT_EQ(ipstep::NearMiss("completely_unrelated", flags), "");
  EXPECT_EQ(ipstep::NearMiss("scene", flags), "");  // not a miss
}

}  // namespace
