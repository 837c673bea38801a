// sculpt run [--headless] [--out DIR] [--size N]
//
// The station's main job. Until the window, the devices and the sessions exist
// (later issues), it runs the best end-to-end path available: it builds the
// demo block, carves it through the wavelet volume's brick-edit path, and
// writes the result (volume, every level of detail, statistics) to DIR.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "sculpt/core/io/atomic_file.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/volume/volume_io.h"

namespace sculpt::station::cli {
namespace {

struct RunOptions {
  bool headless = false;
  std::string out_dir = "sculpt-out";
  int size = 256;
};

int run_station(const RunOptions& o) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  if (ec)
    return report(core::Error(o.out_dir + ": cannot create the output folder: " + ec.message()));

  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  core::Volume volume = core::sphere_volume(o.size);
  const double build_s = std::chrono::duration<double>(clock::now() - t0).count();

  // Carve a ring of spherical cavities around the equator through the
  // brick-edit path (decode, edit, re-encode only touched bricks).
  const float c = static_cast<float>(o.size - 1) / 2.0f;
  const float ring = 0.35f * static_cast<float>(o.size);
  const float hole = 0.06f * static_cast<float>(o.size);
  const auto t1 = clock::now();
  int64_t touched = 0;
  for (int k = 0; k < 12; ++k) {
    const float a = static_cast<float>(k) * 6.2831853f / 12.0f;
    const glm::vec3 centre(c + ring * std::cos(a), c + ring * std::sin(a), c);
    const core::Box box{glm::ivec3(centre - hole - 2.0f), glm::ivec3(centre + hole + 3.0f)};
    volume.edit(box, [&](glm::ivec3 origin, std::span<uint8_t> voxels) {
      const int e = volume.brick_edge();
      for (int z = 0; z < e; ++z)
        for (int y = 0; y < e; ++y)
          for (int x = 0; x < e; ++x) {
            const glm::vec3 p = glm::vec3(origin + glm::ivec3(x, y, z)) - centre;
            const uint8_t cut = core::density_from_distance(std::sqrt(glm::dot(p, p)) - hole);
            uint8_t& v = voxels[(static_cast<size_t>(z) * e + y) * e + x];
            v = static_cast<uint8_t>(std::max(0, v - cut));
          }
    });
    touched += static_cast<int64_t>(volume.take_dirty_bricks().size());
  }
  const double carve_s = std::chrono::duration<double>(clock::now() - t1).count();

  const fs::path dir(o.out_dir);
  if (core::Status st = core::write_volume_nrrd(dir / "volume.nrrd", volume); !st)
    return report(st.error());
  for (int k = 1; k <= volume.levels(); ++k) {
    const fs::path p = dir / ("level" + std::to_string(k) + ".nrrd");
    if (core::Status st = core::write_volume_nrrd(p, volume, k); !st) return report(st.error());
  }
  const core::VolumeStats s = volume.stats();
  nlohmann::json stats = {
      {"size", o.size},
      {"levels", volume.levels()},
      {"bricks", s.bricks},
      {"uniform_bricks", s.uniform_bricks},
      {"memory_bytes", s.memory_bytes},
      {"zero_detail_share", s.detail_coefficients
                                ? static_cast<double>(s.zero_detail_coefficients) /
                                      static_cast<double>(s.detail_coefficients)
                                : 0.0},
      {"carved_bricks", touched},
      {"build_seconds", build_s},
      {"carve_seconds", carve_s},
      {"volume_hash", volume.content_hash()},
  };
  core::AtomicFileWriter out(dir / "stats.json");
  out.write(stats.dump(2) + "\n");
  if (core::Status st = out.commit(); !st) return report(st.error());
  std::printf("%s\n", stats.dump(2).c_str());
  std::printf("wrote %s/volume.nrrd, level1..%d.nrrd and stats.json\n", o.out_dir.c_str(),
              volume.levels());
  return 0;
}

}  // namespace

void add_run_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "run the station's main job");
  cmd->add_flag("--headless", o->headless, "no window (the only mode until the renderer exists)");
  cmd->add_option("--out", o->out_dir, "folder for the results")->capture_default_str();
  cmd->add_option("--size", o->size, "edge of the demo block in voxels")
      ->check(CLI::Range(16, 1024))
      ->capture_default_str();
  cmd->callback([o, &action] { action = [o] { return run_station(*o); }; });
}

}  // namespace sculpt::station::cli
