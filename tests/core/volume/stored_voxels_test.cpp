// A brick stored twice before the mesher took it: what changed since the
// first one's version is both changes' box, if the second changed from the
// first (sculptor.cpp, surface_mesher.cpp).

#include "sculpt/core/volume/stored_voxels.h"

#include <gtest/gtest.h>

namespace sculpt::core {
namespace {

TEST(StoredVoxels, FollowingAChangeKeepsItsVersionAndJoinsTheBoxes) {
  StoredVoxels first;
  first.version = 5;
  first.changed_from = 4;
  first.changed = Box{glm::ivec3(0), glm::ivec3(4)};
  StoredVoxels second;
  second.version = 6;
  second.changed_from = 5;
  second.changed = Box{glm::ivec3(10), glm::ivec3(12)};
  follow(first, second);
  ASSERT_TRUE(second.changed_from.has_value());
  EXPECT_EQ(*second.changed_from, 4u);
  EXPECT_EQ(second.changed.lo, glm::ivec3(0));
  EXPECT_EQ(second.changed.hi, glm::ivec3(12));
}

TEST(StoredVoxels, AChangeFromAnotherVersionOrAnUnknownOneIsUnknown) {
  StoredVoxels first;
  first.version = 5;
  first.changed_from = 4;
  StoredVoxels second;
  second.version = 7;
  second.changed_from = 6;  // a store between them was not seen
  follow(first, second);
  EXPECT_FALSE(second.changed_from.has_value());

  StoredVoxels unknown;
  unknown.version = 5;  // no changed_from
  StoredVoxels third;
  third.version = 6;
  third.changed_from = 5;
  follow(unknown, third);
  EXPECT_FALSE(third.changed_from.has_value());
}

}  // namespace
}  // namespace sculpt::core
