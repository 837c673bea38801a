#pragma once
// The Dear ImGui panel: every setting of the station and its figures. It only
// reads the controller's state and calls its methods.

#include <cstdint>
#include <string>

#include "sculpt/station/app/station_controller.h"

namespace sculpt::station {

struct FrameFigures {
  double fps = 0;
  double frame_ms = 0;
  int64_t triangles = 0;
  int64_t uploaded = 0;
};

class StationPanel {
 public:
  explicit StationPanel(StationController& controller);
  void draw(const FrameFigures& figures, int64_t now_ns);

 private:
  void draw_sheet(int64_t now_ns);

  StationController& c_;
  char project_[512] = {};
  char mesh_[512] = {};
  char recording_[512] = {};
  float sensitivity_ = 1.0f;
  float deadzone_ = 0.06f;
};

}  // namespace sculpt::station
