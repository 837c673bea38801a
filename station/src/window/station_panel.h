#pragma once
// The Dear ImGui panel: every setting of the station and its figures. It only
// reads the controller's state and calls its methods.

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "sculpt/station/app/station_controller.h"
#include "sculpt/station/haptics/haptic_station.h"

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
  ~StationPanel();
  StationPanel(const StationPanel&) = delete;
  StationPanel& operator=(const StationPanel&) = delete;
  void draw(const FrameFigures& figures, int64_t now_ns);
  /// Opens the new block's confirmation (its key's way in).
  void ask_new_block();
  /// A force device's section (null: none).
  void set_haptics(HapticStation* haptics) { haptics_ = haptics; }
  /// Changes when a texture the panel shows is made or dropped (PanelLayer).
  uint64_t textures_version() const { return textures_version_; }

  /// How often figures that change every frame are shown anew.
  static constexpr int64_t kFiguresEveryNs = 250'000'000;

 private:
  void draw_sheet(int64_t now_ns);
  void draw_tool_region(int64_t now_ns);
  void draw_new_block(int64_t now_ns);
  void draw_morphology(int64_t now_ns);
  void draw_tool_files(int64_t now_ns);
  // Scans the tool folder again and uploads each thumbnail as a texture.
  void refresh_library();
  void drop_thumbnails();
  void draw_haptics(int64_t now_ns);
  // A line of figures (rates, latencies, forces) as it read at the last
  // refresh: numbers that change sixty times a second cannot be read, and a
  // panel that looks as it did is drawn from PanelLayer's picture of it.
  // Each call site's format string names its line.
  void figure(const char* format, ...) __attribute__((format(printf, 2, 3)));

  StationController& c_;
  HapticStation* haptics_ = nullptr;
  bool ask_new_block_ = false;
  char tool_file_[512] = {};
  char mesh_file_[512] = {};
  int mesh_tool_edge_ = 48;
  struct LibraryEntry {
    std::string path;
    std::string label;  // file name and size
    unsigned int texture = 0;
  };
  std::vector<LibraryEntry> library_;
  int library_unreadable_ = 0;
  bool library_scanned_ = false;
  int64_t haptic_ticks_ = 0;  // at haptic_since_ns_, for the loop rate
  int64_t haptic_since_ns_ = 0;
  double haptic_rate_hz_ = 0.0;
  char project_[512] = {};
  char mesh_[512] = {};
  char recording_[512] = {};
  float sensitivity_ = 1.0f;
  float deadzone_ = 0.06f;
  uint64_t textures_version_ = 0;
  bool figures_due_ = true;
  int64_t figures_at_ = 0;
  std::unordered_map<const char*, std::string> figure_lines_;
};

}  // namespace sculpt::station
