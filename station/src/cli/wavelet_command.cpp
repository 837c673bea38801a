// sculpt wavelet IN.nrrd --levels L [--lod K] -o OUT.nrrd
//
// With --lod K: writes level K of the wavelet volume (level 0 is the input,
// bit for bit). Without: verifies the round trip and prints the sizes and the
// share of zero detail coefficients.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/field_options.h"
#include "cli/number_checks.h"
#include "sculpt/core/files/vdb_file.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/volume/volume_io.h"

namespace sculpt::station::cli {
namespace {

struct WaveletOptions {
  std::string input;
  std::string output;
  int levels = 5;
  int lod = -1;
  DensityOptions density;
};

int run_wavelet(const WaveletOptions& o) {
  core::VolumeOptions vo;
  vo.levels = o.levels;
  // A brick must hold every level: 32 holds 5, larger level counts need larger bricks.
  vo.brick_edge = std::max(32, 1 << o.levels);
  if (o.lod > o.levels) {
    return report(
        Error("--lod " + std::to_string(o.lod) + " exceeds --levels " + std::to_string(o.levels)));
  }
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const auto window = density_window(o.density, o.input);
  if (!window) return report(window.error());
  const core::DensityWindow* mapping = window->has_value() ? &**window : nullptr;
  auto volume = core::read_volume_file(o.input, vo, {}, mapping);
  if (!volume) return report(volume.error());
  const double build_s = std::chrono::duration<double>(clock::now() - t0).count();

  if (o.lod >= 0) {
    if (o.output.empty()) return report(Error("--lod needs an output file (-o OUT.nrrd)"));
    return write_volume_level("wavelet", o.output, *volume, o.lod);
  }

  // Round trip: decode everything and compare with the file, slice by slice
  // (a .vdb has no slices to stream: it is read again whole).
  std::optional<core::NrrdReader> reader;
  std::optional<core::DenseGrid<uint8_t>> whole;
  if (core::is_vdb_path(o.input)) {
    auto grid = core::read_density_file(o.input, mapping);
    if (!grid) return report(grid.error());
    whole = std::move(*grid);
  } else {
    auto opened = core::NrrdReader::open(o.input);
    if (!opened) return report(opened.error());
    reader.emplace(std::move(*opened));
  }
  const glm::ivec3 d = volume->dims();
  const auto t1 = clock::now();
  const core::DenseGrid<uint8_t> decoded = volume->to_dense(0);
  const double extract_s = std::chrono::duration<double>(clock::now() - t1).count();
  std::vector<uint8_t> slice(static_cast<size_t>(d.x) * d.y);
  int64_t mismatches = 0;
  for (int z = 0; z < d.z; ++z) {
    if (whole) {
      std::copy_n(whole->data() + z * slice.size(), slice.size(), slice.data());
    } else if (Status st = reader->read_density_slices(1, mapping, slice); !st) {
      return report(st.error());
    }
    for (size_t i = 0; i < slice.size(); ++i)
      mismatches += slice[i] != decoded[z * slice.size() + i];
  }
  const core::VolumeStats s = volume->stats();
  std::printf("volume      %dx%dx%d uint8 (%lld bytes dense)\n", d.x, d.y, d.z,
              static_cast<long long>(core::voxel_count(d)));
  std::printf("wavelets    %d levels, bricks of %d^3: %lld bricks, %lld uniform\n", o.levels,
              vo.brick_edge, static_cast<long long>(s.bricks),
              static_cast<long long>(s.uniform_bricks));
  std::printf(
      "memory      %zu bytes (%.1f%% of dense)\n", s.memory_bytes,
      100.0 * static_cast<double>(s.memory_bytes) / static_cast<double>(core::voxel_count(d)));
  std::printf("details     %lld coefficients in detailed bricks, %.1f%% zero\n",
              static_cast<long long>(s.detail_coefficients),
              s.detail_coefficients ? 100.0 * static_cast<double>(s.zero_detail_coefficients) /
                                          static_cast<double>(s.detail_coefficients)
                                    : 0.0);
  for (int k = 0; k <= o.levels; ++k) {
    const glm::ivec3 ld = volume->level_dims(k);
    std::printf("level %d     %dx%dx%d\n", k, ld.x, ld.y, ld.z);
  }
  std::printf("time        read+encode %.3f s, decode %.3f s\n", build_s, extract_s);
  if (mismatches != 0) {
    std::fprintf(stderr, "sculpt: %s: round trip FAILED: %lld voxels differ\n", o.input.c_str(),
                 static_cast<long long>(mismatches));
    return 1;
  }
  std::printf("round trip  bit-exact\n");
  if (!o.output.empty()) {
    if (Status st = core::write_volume_file(o.output, *volume, 0); !st) return report(st.error());
  }
  return 0;
}

}  // namespace

void add_wavelet_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<WaveletOptions>();
  CLI::App* cmd = app.add_subcommand(
      "wavelet", "3D Haar wavelet volume: extract a level, or verify the round trip");
  cmd->add_option("input", o->input,
                  "NRRD (uint8 density, or any type with --window) or .vdb volume")
      ->required()
      ->check(input_file());
  add_density_options(cmd, o->density);
  cmd->add_option("--levels", o->levels, "wavelet levels (1..7)")->check(finite_range(0, 7));
  cmd->add_option("--lod", o->lod, "level to write (0 = the input)")->check(finite_range(0, 7));
  cmd->add_option("-o,--output", o->output, "output volume (.nrrd, or .vdb: OpenVDB)");
  cmd->callback([o, &action] { action = [o] { return run_wavelet(*o); }; });
}

}  // namespace sculpt::station::cli
