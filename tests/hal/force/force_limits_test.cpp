#include "sculpt/hal/force/force_limits.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace sculpt::hal {
namespace {

TEST(ForceLimits, TheFalconsFigures) {
  const ForceLimits* falcon = find_force_limits(0x0403, 0xcb48);
  ASSERT_NE(falcon, nullptr);
  EXPECT_EQ(falcon->name, "Novint Falcon");
  EXPECT_EQ(falcon->capability, ForceCapability::kForce3);
  EXPECT_FLOAT_EQ(falcon->max_force_n, 8.0f);
  EXPECT_FLOAT_EQ(falcon->max_stiffness_n_per_mm, 3.0f);
  EXPECT_FLOAT_EQ(falcon->max_damping_ns_per_m, 20.0f);
  EXPECT_FLOAT_EQ(falcon->workspace_radius_mm, 40.0f);
  // Another FTDI product is not a Falcon.
  EXPECT_EQ(find_force_limits(0x0403, 0x6001), nullptr);
  EXPECT_EQ(&sim_arm_limits(), find_force_limits(0x0000, 0x0001));
}

TEST(ForceLimits, SettingsAreClampedToTheDevice) {
  const ForceLimits& l = *find_force_limits(0x0403, 0xcb48);
  EXPECT_FLOAT_EQ(l.clamp_stiffness(1.5f), 1.5f);
  EXPECT_FLOAT_EQ(l.clamp_stiffness(30.0f), 3.0f);
  EXPECT_FLOAT_EQ(l.clamp_damping(100.0f), 20.0f);
  EXPECT_FLOAT_EQ(l.clamp_stiffness(-1.0f), 0.0f);
  EXPECT_FLOAT_EQ(l.clamp_stiffness(std::numeric_limits<float>::quiet_NaN()), 0.0f);
  EXPECT_FLOAT_EQ(l.clamp_damping(std::numeric_limits<float>::infinity()), 0.0f);
}

TEST(ForceLimits, EveryEntryIsSane) {
  for (const ForceLimits& l : all_force_limits()) {
    EXPECT_GT(l.max_force_n, 0.0f) << l.name;
    EXPECT_GT(l.max_stiffness_n_per_mm, 0.0f) << l.name;
    EXPECT_GT(l.workspace_radius_mm, 0.0f) << l.name;
    EXPECT_EQ(find_force_limits(l.vendor_id, l.product_id), &l) << l.name;
  }
}

}  // namespace
}  // namespace sculpt::hal
