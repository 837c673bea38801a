#pragma once
// Probe files, the input of `sculpt haptics trace`, and the trace lines it
// writes. Both are JSON Lines, one object per line; lines of only whitespace
// are skipped.
//
// A probe file lists where the device was, in voxel coordinates of the
// volume, with "t" in seconds increasing strictly from >= 0:
//   {"t": 0.001, "at": [32.5, 40, 12]}
//   {"t": 0.002, "at": [32.5, 40, 11.75], "quat": [1, 0, 0, 0]}   (w, x, y, z)
// Every key is checked: a missing, unknown or malformed one, or a line that is
// not a JSON object, is one error naming the input and the line,
// e.g. "probe.jsonl:3: "t" must increase strictly (2.5 after 2.5)".
//
// A trace line is what the haptic loop did at one step:
//   {"t":0.001,"device":[x,y,z],"proxy":[x,y,z],"force":[x,y,z],"torque":[x,y,z],"contact":true}
// ("torque" only when known). Numbers are written with enough digits to read
// back bit for bit.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "sculpt/base/result.h"

namespace sculpt::core {

/// Most lines a probe or trace text may have (empty lines count).
constexpr size_t kMaxProbeLines = 10'000'000;
/// Longest line accepted, in bytes without the '\n'; bounds the JSON parser's work.
constexpr size_t kMaxProbeLineBytes = 4096;
/// Largest |coordinate| of "at", in voxels.
constexpr double kMaxProbeCoordinateVox = 1e6;

/// One line of a probe file.
struct ProbeSample {
  /// Seconds from the start of the probe.
  double t_s = 0.0;
  /// Device position in voxel coordinates.
  glm::vec3 at_vox{0.0f};
  /// Device orientation, normalised; absent when the line has no "quat".
  std::optional<glm::quat> orientation;
};

/// Parses a probe file's text; `name` starts every error ("NAME:LINE: problem").
/// Text without any sample is an error ("NAME: no probe samples").
Result<std::vector<ProbeSample>> parse_probe_text(std::string_view text, const std::string& name);
/// Reads and parses a probe file; errors name the path.
Result<std::vector<ProbeSample>> read_probe_file(const std::filesystem::path& path);

/// One step of the haptic loop, as `sculpt haptics trace` writes it.
struct TraceLine {
  /// Seconds from the start of the probe.
  double t_s = 0.0;
  /// Device and proxy positions in voxel coordinates.
  glm::vec3 device_vox{0.0f};
  glm::vec3 proxy_vox{0.0f};
  /// Force on the device, in newtons.
  glm::vec3 force_n{0.0f};
  /// Torque on the device in newton metres, when the device renders one.
  std::optional<glm::vec3> torque_nm;
  /// Whether the proxy touches the material.
  bool contact = false;
};

/// One JSON object and '\n'. Floats are written with 9 significant digits,
/// t_s with 17, so parse_trace_text() gives back the same bits. A non-finite
/// number (a bug upstream) is written as null, which parse_trace_text() refuses.
std::string format_trace_line(const TraceLine& line);
/// Whether every number of `line` is finite (the reader refuses any other,
/// so a trace with one is refused before it is written).
bool trace_line_finite(const TraceLine& line);
/// Parses trace text (format_trace_line()'s output, one line after another);
/// errors like parse_probe_text()'s. Text without any line is an error.
Result<std::vector<TraceLine>> parse_trace_text(std::string_view text, const std::string& name);

}  // namespace sculpt::core
