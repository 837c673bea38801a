#include "cli/field_options.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/number_checks.h"
#include "cli/progress_bar.h"
#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/files/vdb_file.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/io/nrrd.h"

namespace sculpt::station::cli {

void add_density_options(CLI::App* command, DensityOptions& options) {
  command
      ->add_option("--window", options.window,
                   "LO,HI: map other voxels than uint8 to density, LO and below 0, HI and above "
                   "255, linear between")
      ->delimiter(',')
      ->expected(2)
      ->check(finite_range(-1e30, 1e30));
  command
      ->add_option("--data-iso", options.data_iso,
                   "V: map other voxels than uint8 to density by the narrowest window centred on "
                   "V that holds all of them (V becomes the surface)")
      ->check(finite_range(-1e30, 1e30))
      ->excludes("--window");
}

Result<std::optional<core::DensityWindow>> density_window(const DensityOptions& options,
                                                          const std::string& path) {
  const bool mapping = options.window.size() == 2 || std::isfinite(options.data_iso);
  if (mapping && core::is_vdb_path(path)) {
    return Error(path +
                 ": --window and --data-iso map NRRD voxels to density; a .vdb density "
                 "needs no mapping");
  }
  if (options.window.size() == 2) {
    if (!(options.window[1] > options.window[0])) return Error("--window: HI must be above LO");
    return std::optional(core::DensityWindow{options.window[0], options.window[1]});
  }
  if (std::isfinite(options.data_iso)) {
    auto window = core::window_around(path, options.data_iso);
    if (!window) return window.error();
    return std::optional(*window);
  }
  return std::optional<core::DensityWindow>();
}

CLI::Option* add_threads_option(CLI::App* command, int& threads) {
  return command->add_option("--threads", threads, "threads (0 = all cores)")
      ->check(finite_range(0, 1024));
}

Status write_field(const std::string& path, const core::DenseGrid<float>& field, bool as_distance) {
  return as_distance ? core::write_distance_file(path, field)
                     : core::write_density_file(path, core::density_from_distance_field(field));
}

const char* field_kind(bool as_distance) {
  return as_distance ? "float32 signed distance" : "uint8 density";
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

bool is_volume_file_name(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".nrrd" || ext == ".vdb";
}

Result<core::Volume> read_volume_input(const std::string& path, const DensityOptions& density,
                                       const core::VolumeOptions& options) {
  const auto window = density_window(density, path);
  if (!window) return window.error();
  return core::read_volume_file(path, options, {}, window->has_value() ? &**window : nullptr);
}

int write_volume_level(const std::string& command, const std::string& path,
                       const core::Volume& volume, int lod) {
  ProgressBar bar(command);
  const Status st = core::write_volume_file(path, volume, lod, bar.progress());
  if (bar.cancelled()) {
    // Ctrl-C after the level set, during the file's own write: the command
    // still ends cancelled, so the file it finished goes too.
    if (st) {
      std::error_code ignored;
      std::filesystem::remove(path, ignored);
    }
    return bar.cancel_exit();
  }
  bar.finish();
  if (!st) return report(st.error());
  const glm::ivec3 d = volume.level_dims(lod);
  std::printf("wrote level %d (%dx%dx%d) to %s\n", lod, d.x, d.y, d.z, path.c_str());
  return 0;
}

}  // namespace sculpt::station::cli
