// sculpt rotate TOOL.nrrd --euler RX,RY,RZ [--method brute|incremental] [--aa] -o OUT.nrrd
//
// Rotates a tool ("Discrete tools for virtual sculpture" §3.1-3.2) about its
// centre (or its pivot with --about pivot) by Euler angles in degrees,
// extrinsic x then y then z (scipy's Rotation.from_euler("xyz")). The output
// grid is the bounding box of the rotated tool; the output is itself a tool
// file whose sculpt_pivot is where the rotation centre landed.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <glm/vector_relational.hpp>

#include "cli/commands.h"
#include "cli/number_checks.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/core/tool/tool_rotation.h"

namespace sculpt::station::cli {
namespace {

struct RotateOptions {
  std::string input;
  std::string output;
  std::vector<float> euler;
  std::string method = "incremental";
  std::string about = "centre";
  bool aa = false;
};

int run_rotate(const RotateOptions& o) {
  for (float a : o.euler) {
    if (!std::isfinite(a)) return report(Error("--euler: angles must be finite numbers"));
  }
  auto tool = core::read_tool_file(o.input);
  if (!tool) return report(tool.error());
  // The rotated box can be sqrt(3) times the tool's edge: keep it a tool.
  constexpr int kMaxToolEdge = 1024;
  if (glm::any(glm::greaterThan(tool->density.dims(), glm::ivec3(kMaxToolEdge)))) {
    return report(
        Error("tool is larger than " + std::to_string(kMaxToolEdge) + " voxels on an edge")
            .in(o.input));
  }
  if (o.about == "centre") tool->pivot = core::grid_centre(tool->density.dims());
  const glm::ivec3 in_dims = tool->density.dims();
  const glm::vec3 pivot = tool->pivot;
  const core::PreparedTool prepared(std::move(tool.value()));
  const glm::mat3 r = core::euler_xyz_deg({o.euler[0], o.euler[1], o.euler[2]});
  const auto method =
      o.method == "brute" ? core::RotationMethod::kBrute : core::RotationMethod::kIncremental;
  const auto sampling = o.aa ? core::Sampling::kTrilinear : core::Sampling::kNearest;
  const auto t0 = std::chrono::steady_clock::now();
  core::RotatedTool rotated = core::rotate_tool(prepared, r, pivot, method, sampling);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const glm::ivec3 d = rotated.density.dims();
  int64_t mass_in = 0, mass_out = 0;
  for (uint8_t v : prepared.tool().density.values())
    mass_in += v;
  for (uint8_t v : rotated.density.values())
    mass_out += v;
  const core::Tool out{std::move(rotated.density), pivot - glm::vec3(rotated.origin)};
  if (Status st = core::write_tool_file(o.output, out); !st) return report(st.error());
  std::printf(
      "rotated %dx%dx%d by (%g, %g, %g) deg about (%g, %g, %g), %s%s: %dx%dx%d in %.3f ms\n",
      in_dims.x, in_dims.y, in_dims.z, o.euler[0], o.euler[1], o.euler[2], pivot.x, pivot.y,
      pivot.z, o.method.c_str(), o.aa ? " + trilinear" : "", d.x, d.y, d.z, ms);
  std::printf("mass %lld -> %lld (%.2f%%); pivot in output (%g, %g, %g); wrote %s\n",
              static_cast<long long>(mass_in), static_cast<long long>(mass_out),
              mass_in ? 100.0 * static_cast<double>(mass_out) / static_cast<double>(mass_in) : 0.0,
              out.pivot.x, out.pivot.y, out.pivot.z, o.output.c_str());
  return 0;
}

}  // namespace

void add_rotate_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<RotateOptions>();
  CLI::App* cmd =
      app.add_subcommand("rotate", "rotate a tool volume into the bounding box of its rotation");
  cmd->add_option("tool", o->input, "tool: uint8 NRRD (optional sculpt_pivot:=X Y Z line) or .vdb")
      ->required()
      ->check(input_file());
  cmd->add_option("--euler", o->euler, "RX,RY,RZ in degrees, extrinsic x then y then z")
      ->required()
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--method", o->method,
                  "inverse mapping: brute (matrix per voxel) or incremental (Algorithm 1)")
      ->check(CLI::IsMember({"brute", "incremental"}));
  cmd->add_flag("--aa", o->aa, "trilinear antialiasing (default nearest voxel)");
  cmd->add_option("--about", o->about, "rotate about the grid centre or the file's pivot")
      ->check(CLI::IsMember({"centre", "pivot"}));
  cmd->add_option("-o,--output", o->output, "output tool (.nrrd or .vdb)")->required();
  cmd->callback([o, &action] { action = [o] { return run_rotate(*o); }; });
}

}  // namespace sculpt::station::cli
