#include "sculpt/station/window/keymap.h"

#include <GLFW/glfw3.h>

namespace sculpt::station {

std::optional<Action> shortcut(int key, int mods) {
  const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0;
  const bool shift = (mods & GLFW_MOD_SHIFT) != 0;
  if (ctrl) {
    switch (key) {
      case GLFW_KEY_Z:
        return shift ? Action::kRedo : Action::kUndo;
      case GLFW_KEY_Y:
        return Action::kRedo;
      case GLFW_KEY_S:
        return Action::kSave;
      case GLFW_KEY_E:
        return shift ? Action::kExportSheet : Action::kExportMesh;
      case GLFW_KEY_T:
        return shift ? Action::kSheetAsTool : Action::kUseSculptureAsTool;
      case GLFW_KEY_B:
        return shift ? Action::kSheetSubtractFromMaterial : Action::kSheetAddToMaterial;
      case GLFW_KEY_H:
        return Action::kHypertexture;
      case GLFW_KEY_R:
        return shift ? Action::kToggleToolRegion : Action::kUseRegionAsTool;
      case GLFW_KEY_N:
        return Action::kNewBlock;
      case GLFW_KEY_O:
        return Action::kOffsetSculpture;
      case GLFW_KEY_L:
        return Action::kCloseSculpture;
      default:
        return std::nullopt;
    }
  }
  switch (key) {
    case GLFW_KEY_TAB:
      return Action::kToggleAddSubtract;
    case GLFW_KEY_M:
      return Action::kSmooth;
    // The ball brushes on Blender's keys where they are free here (C and G
    // already mean the device's target and sheet editing: Shift with them).
    case GLFW_KEY_T:
      return shift ? std::optional(Action::kBrushFlatten) : std::nullopt;
    case GLFW_KEY_I:
      return Action::kBrushInflate;
    case GLFW_KEY_P:
      return Action::kBrushPinch;
    case GLFW_KEY_A:
      return shift ? std::optional(Action::kToggleAccumulate) : std::nullopt;
    case GLFW_KEY_1:
      return Action::kToolSphere;
    case GLFW_KEY_2:
      return Action::kToolCube;
    case GLFW_KEY_3:
      return Action::kToolCylinder;
    case GLFW_KEY_4:
      return Action::kToolRing;
    case GLFW_KEY_5:
      return Action::kToolCone;
    case GLFW_KEY_RIGHT_BRACKET:
      return Action::kToolBigger;
    case GLFW_KEY_LEFT_BRACKET:
      return Action::kToolSmaller;
    case GLFW_KEY_EQUAL:
      return Action::kStronger;
    case GLFW_KEY_MINUS:
      return Action::kWeaker;
    case GLFW_KEY_X:
      return Action::kToggleMirror;
    case GLFW_KEY_C:
      return shift ? Action::kBrushClay : Action::kToggleDeviceTarget;
    case GLFW_KEY_U:
      return Action::kToggleTouch;
    case GLFW_KEY_R:
      return Action::kToggleRecording;
    case GLFW_KEY_F:
      return Action::kFrameView;
    case GLFW_KEY_HOME:
      return Action::kCentreTool;
    case GLFW_KEY_Q:
      return shift ? Action::kTiltToolUp : Action::kTurnToolLeft;
    case GLFW_KEY_E:
      return shift ? Action::kTiltToolDown : Action::kTurnToolRight;
    case GLFW_KEY_N:
      return shift ? Action::kRemoveSheet : Action::kNewSheet;
    case GLFW_KEY_G:
      return shift ? Action::kBrushGrab : Action::kToggleSheetEditing;
    default:
      return std::nullopt;
  }
}

const char* shortcut_label(Action action) {
  switch (action) {
    case Action::kUndo:
      return "Ctrl+Z";
    case Action::kRedo:
      return "Ctrl+Y, Ctrl+Shift+Z";
    case Action::kToggleAddSubtract:
      return "Tab";
    case Action::kSmooth:
      return "M";
    case Action::kBrushClay:
      return "Shift+C";
    case Action::kBrushFlatten:
      return "Shift+T";
    case Action::kBrushInflate:
      return "I";
    case Action::kBrushPinch:
      return "P";
    case Action::kBrushGrab:
      return "Shift+G";
    case Action::kToggleAccumulate:
      return "Shift+A";
    case Action::kToolSphere:
      return "1";
    case Action::kToolCube:
      return "2";
    case Action::kToolCylinder:
      return "3";
    case Action::kToolRing:
      return "4";
    case Action::kToolCone:
      return "5";
    case Action::kToolBigger:
      return "]";
    case Action::kToolSmaller:
      return "[";
    case Action::kStronger:
      return "=";
    case Action::kWeaker:
      return "-";
    case Action::kToggleMirror:
      return "X";
    case Action::kToggleDeviceTarget:
      return "C";
    case Action::kToggleTouch:
      return "U";
    case Action::kCentreTool:
      return "Home";
    case Action::kToggleRecording:
      return "R";
    case Action::kSave:
      return "Ctrl+S";
    case Action::kExportMesh:
      return "Ctrl+E";
    case Action::kUseSculptureAsTool:
      return "Ctrl+T";
    case Action::kToggleToolRegion:
      return "Ctrl+Shift+R";
    case Action::kUseRegionAsTool:
      return "Ctrl+R";
    case Action::kNewBlock:
      return "Ctrl+N";
    case Action::kOffsetSculpture:
      return "Ctrl+O";
    case Action::kCloseSculpture:
      return "Ctrl+L";
    case Action::kHypertexture:
      return "Ctrl+H";
    case Action::kFrameView:
      return "F";
    case Action::kTurnToolLeft:
      return "Q";
    case Action::kTurnToolRight:
      return "E";
    case Action::kTiltToolUp:
      return "Shift+Q";
    case Action::kTiltToolDown:
      return "Shift+E";
    case Action::kNewSheet:
      return "N";
    case Action::kRemoveSheet:
      return "Shift+N";
    case Action::kToggleSheetEditing:
      return "G";
    case Action::kSheetAddToMaterial:
      return "Ctrl+B";
    case Action::kSheetSubtractFromMaterial:
      return "Ctrl+Shift+B";
    case Action::kSheetAsTool:
      return "Ctrl+Shift+T";
    case Action::kExportSheet:
      return "Ctrl+Shift+E";
  }
  return "";
}

}  // namespace sculpt::station
