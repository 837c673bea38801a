// The keyboard shortcuts: GLFW key codes to the controller's actions.

#include "sculpt/station/window/keymap.h"

#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

namespace sculpt::station {
namespace {

TEST(StationShortcuts, MapKeysToActions) {
  EXPECT_EQ(shortcut(GLFW_KEY_Z, GLFW_MOD_CONTROL), Action::kUndo);
  EXPECT_EQ(shortcut(GLFW_KEY_Z, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT), Action::kRedo);
  EXPECT_EQ(shortcut(GLFW_KEY_Y, GLFW_MOD_CONTROL), Action::kRedo);
  EXPECT_EQ(shortcut(GLFW_KEY_S, GLFW_MOD_CONTROL), Action::kSave);
  EXPECT_EQ(shortcut(GLFW_KEY_TAB, 0), Action::kToggleAddSubtract);
  EXPECT_EQ(shortcut(GLFW_KEY_3, 0), Action::kToolCylinder);
  EXPECT_EQ(shortcut(GLFW_KEY_H, GLFW_MOD_CONTROL), Action::kHypertexture);
  EXPECT_EQ(shortcut(GLFW_KEY_Z, 0), std::nullopt);
  EXPECT_EQ(shortcut(GLFW_KEY_Q, GLFW_MOD_CONTROL), std::nullopt);
  EXPECT_STREQ(shortcut_label(Action::kUndo), "Ctrl+Z");
}

TEST(StationShortcuts, ReachTheSheetAndTurnTheTool) {
  EXPECT_EQ(shortcut(GLFW_KEY_N, 0), Action::kNewSheet);
  EXPECT_EQ(shortcut(GLFW_KEY_O, GLFW_MOD_CONTROL), Action::kOffsetSculpture);
  EXPECT_EQ(shortcut(GLFW_KEY_L, GLFW_MOD_CONTROL), Action::kCloseSculpture);
  EXPECT_EQ(shortcut(GLFW_KEY_N, GLFW_MOD_SHIFT), Action::kRemoveSheet);
  EXPECT_EQ(shortcut(GLFW_KEY_G, 0), Action::kToggleSheetEditing);
  EXPECT_EQ(shortcut(GLFW_KEY_B, GLFW_MOD_CONTROL), Action::kSheetAddToMaterial);
  EXPECT_EQ(shortcut(GLFW_KEY_B, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT),
            Action::kSheetSubtractFromMaterial);
  EXPECT_EQ(shortcut(GLFW_KEY_T, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT), Action::kSheetAsTool);
  EXPECT_EQ(shortcut(GLFW_KEY_E, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT), Action::kExportSheet);
  EXPECT_EQ(shortcut(GLFW_KEY_Q, 0), Action::kTurnToolLeft);
  EXPECT_EQ(shortcut(GLFW_KEY_E, GLFW_MOD_SHIFT), Action::kTiltToolDown);
  EXPECT_STREQ(shortcut_label(Action::kNewSheet), "N");
  EXPECT_EQ(shortcut(GLFW_KEY_U, 0), Action::kToggleTouch);
  EXPECT_STREQ(shortcut_label(Action::kToggleTouch), "U");
}

// The ball brushes on Blender's keys where they are free; C and G alone keep
// their meaning (the device's target, sheet editing).
TEST(StationShortcuts, ChooseTheBallBrushesAndAccumulate) {
  EXPECT_EQ(shortcut(GLFW_KEY_C, GLFW_MOD_SHIFT), Action::kBrushClay);
  EXPECT_EQ(shortcut(GLFW_KEY_C, 0), Action::kToggleDeviceTarget);
  EXPECT_EQ(shortcut(GLFW_KEY_T, GLFW_MOD_SHIFT), Action::kBrushFlatten);
  EXPECT_EQ(shortcut(GLFW_KEY_T, 0), std::nullopt);
  EXPECT_EQ(shortcut(GLFW_KEY_I, 0), Action::kBrushInflate);
  EXPECT_EQ(shortcut(GLFW_KEY_P, 0), Action::kBrushPinch);
  EXPECT_EQ(shortcut(GLFW_KEY_G, GLFW_MOD_SHIFT), Action::kBrushGrab);
  EXPECT_EQ(shortcut(GLFW_KEY_G, 0), Action::kToggleSheetEditing);
  EXPECT_EQ(shortcut(GLFW_KEY_A, GLFW_MOD_SHIFT), Action::kToggleAccumulate);
  EXPECT_STREQ(shortcut_label(Action::kBrushClay), "Shift+C");
  EXPECT_STREQ(shortcut_label(Action::kToggleAccumulate), "Shift+A");
}

// The tool region (issue 23): Ctrl+Shift+R shows or hides it, Ctrl+R makes
// it the tool; Ctrl+N asks for a new block; Ctrl+O and Ctrl+L offset and
// close the sculpture.
TEST(StationShortcuts, ReachTheToolRegion) {
  EXPECT_EQ(shortcut(GLFW_KEY_R, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT), Action::kToggleToolRegion);
  EXPECT_EQ(shortcut(GLFW_KEY_R, GLFW_MOD_CONTROL), Action::kUseRegionAsTool);
  EXPECT_EQ(shortcut(GLFW_KEY_R, 0), Action::kToggleRecording);
  EXPECT_STREQ(shortcut_label(Action::kUseRegionAsTool), "Ctrl+R");
  EXPECT_EQ(shortcut(GLFW_KEY_N, GLFW_MOD_CONTROL), Action::kNewBlock);
  EXPECT_EQ(shortcut(GLFW_KEY_N, 0), Action::kNewSheet);
  EXPECT_EQ(shortcut(GLFW_KEY_O, GLFW_MOD_CONTROL), Action::kOffsetSculpture);
  EXPECT_EQ(shortcut(GLFW_KEY_L, GLFW_MOD_CONTROL), Action::kCloseSculpture);
}

}  // namespace
}  // namespace sculpt::station
