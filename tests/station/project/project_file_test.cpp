#include "sculpt/station/project/project_file.h"

#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "crc32.h"
#include "scratch_dir.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::station {
namespace {

std::vector<char> bytes_of(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::filesystem::path& p, const std::vector<char>& b) {
  std::ofstream(p, std::ios::binary).write(b.data(), static_cast<std::streamsize>(b.size()));
}

class ProjectFile : public ::testing::Test {
 protected:
  test::ScratchDir dir_;
  // A sculpture with uniform and detailed bricks, odd dims (padding) included.
  core::Volume volume_ = core::Volume::from_dense(core::sphere_density(70));
  StationSettings settings() const {
    StationSettings s;
    s.shape = sim::ToolShape::kRing;
    s.size_a_vox = 9.5f;
    s.size_b_vox = 2.25f;
    s.mode = core::SculptMode::kSmooth;
    s.strength = 0.625f;
    s.hardness = 0.375f;
    s.spacing = 0.3f;
    s.mirror = core::MirrorPlane{2, 34.5f};
    return s;
  }
};

TEST_F(ProjectFile, RoundTripsVolumeSettingsToolAndView) {
  StationSettings s = settings();
  s.custom_tool = true;
  s.custom_region = core::Box{{10, 11, 12}, {30, 31, 33}};
  const core::Tool tool = core::tool_from_volume(volume_, s.custom_region);
  ProjectView view;
  view.camera_target = {1.5f, 2.5f, 3.5f};
  view.camera_yaw = -0.75f;
  view.camera_distance = 321.0f;
  view.lod.fixed_level = 1;
  const auto path = dir_.path() / "a.sculpt";
  ASSERT_TRUE(save_project(path, volume_, s, &tool, view).ok());

  auto p = load_project(path);
  ASSERT_TRUE(p.ok()) << p.error().message();
  EXPECT_EQ(p->volume->dims(), volume_.dims());
  EXPECT_EQ(p->volume->content_hash(), volume_.content_hash());
  EXPECT_EQ(p->volume->to_dense().data()[12345], volume_.to_dense().data()[12345]);
  EXPECT_EQ(p->settings.shape, s.shape);
  EXPECT_EQ(p->settings.size_a_vox, s.size_a_vox);
  EXPECT_EQ(p->settings.size_b_vox, s.size_b_vox);
  EXPECT_EQ(p->settings.mode, s.mode);
  EXPECT_EQ(p->settings.strength, s.strength);
  EXPECT_EQ(p->settings.hardness, s.hardness);
  EXPECT_EQ(p->settings.spacing, s.spacing);
  ASSERT_TRUE(p->settings.mirror.has_value());
  EXPECT_EQ(p->settings.mirror->axis, 2);
  EXPECT_EQ(p->settings.mirror->centre_vox, 34.5f);
  EXPECT_TRUE(p->settings.custom_tool);
  EXPECT_EQ(p->settings.custom_region.lo, s.custom_region.lo);
  ASSERT_TRUE(p->custom_tool.has_value());
  EXPECT_EQ(p->custom_tool->pivot, tool.pivot);
  EXPECT_EQ(p->custom_tool->density.dims(), tool.density.dims());
  EXPECT_TRUE(std::equal(tool.density.data(), tool.density.data() + tool.density.size(),
                         p->custom_tool->density.data()));
  EXPECT_EQ(p->view.camera_target, view.camera_target);
  EXPECT_EQ(p->view.camera_yaw, view.camera_yaw);
  EXPECT_EQ(p->view.camera_distance, view.camera_distance);
  EXPECT_EQ(p->view.lod.fixed_level, 1);
  // Nothing is left dirty: the station re-meshes from scratch anyway.
  EXPECT_TRUE(p->volume->take_dirty_bricks().empty());
}

TEST_F(ProjectFile, StoresTheWaveletBricksCompressed) {
  const auto path = dir_.path() / "b.sculpt";
  ASSERT_TRUE(save_project(path, volume_, settings(), nullptr, {}).ok());
  const auto size = std::filesystem::file_size(path);
  // 70^3 voxels = 343,000 bytes raw; the bricks' coefficients deflate far below.
  EXPECT_LT(size, 343000u / 3);
  auto p = load_project(path);
  ASSERT_TRUE(p.ok());
  EXPECT_FALSE(p->custom_tool.has_value());
  EXPECT_FALSE(p->settings.custom_tool);
}

TEST_F(ProjectFile, RefusesDamagedFilesWithOneClearError) {
  const auto path = dir_.path() / "c.sculpt";
  ASSERT_TRUE(save_project(path, volume_, settings(), nullptr, {}).ok());
  const std::vector<char> good = bytes_of(path);
  struct Case {
    const char* what;
    std::vector<char> bytes;
    const char* message;
  };
  std::vector<Case> cases;
  cases.push_back({"empty", {}, "not a sculpt project file"});
  cases.push_back(
      {"truncated", {good.begin(), good.begin() + static_cast<long>(good.size() / 2)}, "checksum"});
  std::vector<char> flipped = good;
  flipped[flipped.size() / 2] ^= 0x10;
  cases.push_back({"flipped byte", flipped, "checksum"});
  std::vector<char> magic = good;
  magic[0] = 'X';
  cases.push_back({"magic", magic, "not a sculpt project file"});
  std::vector<char> version = good;
  version[8] = 9;
  cases.push_back({"version", version, "version 9"});
  for (const Case& c : cases) {
    write_bytes(path, c.bytes);
    auto p = load_project(path);
    ASSERT_FALSE(p.ok()) << c.what;
    EXPECT_NE(p.error().message().find(path.string()), std::string::npos) << c.what;
    EXPECT_NE(p.error().message().find(c.message), std::string::npos)
        << c.what << ": " << p.error().message();
    EXPECT_EQ(p.error().message().find('\n'), std::string::npos);
  }
  auto missing = load_project(dir_.path() / "none.sculpt");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message().find("cannot open"), std::string::npos);
}

// A project whose description says `edit` (a JSON pointer and a value),
// sealed with a valid checksum: what a hostile or buggy writer could hand
// us, past the CRC.
std::vector<uint8_t> with_description(const std::vector<char>& good,
                                      const std::function<void(nlohmann::json&)>& edit) {
  auto u32 = [&](size_t at) {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i)
      v |= uint32_t(uint8_t(good[at + size_t(i)])) << (8 * i);
    return v;
  };
  const uint32_t n = u32(12);
  nlohmann::json j = nlohmann::json::parse(good.begin() + 16, good.begin() + 16 + n);
  edit(j);
  const std::string text = j.dump();
  std::vector<uint8_t> out(good.begin(), good.begin() + 12);
  for (int i = 0; i < 4; ++i)
    out.push_back(uint8_t(text.size() >> (8 * i)));
  out.insert(out.end(), text.begin(), text.end());
  out.insert(out.end(), good.begin() + 16 + n, good.end() - 4);
  const uint32_t crc = sculpt::test::crc32_of(out);
  for (int i = 0; i < 4; ++i)
    out.push_back(uint8_t(crc >> (8 * i)));
  return out;
}

std::vector<uint8_t> with_description_edit(const std::vector<char>& good,
                                           const std::string& pointer,
                                           const nlohmann::json& value) {
  return with_description(
      good, [&](nlohmann::json& j) { j[nlohmann::json::json_pointer(pointer)] = value; });
}

// Reproducers from the hardening review: fields past the checksum were read
// with nlohmann's get<int>() (undefined for 1e300) and tool sizes, poses and
// spacings were never bounded (a size of 1e30 exhausts memory when used).
TEST_F(ProjectFile, EveryDescriptionFieldIsTypedAndBounded) {
  const auto path = dir_.path() / "f.sculpt";
  ASSERT_TRUE(save_project(path, volume_, settings(), nullptr, {}).ok());
  const std::vector<char> good = bytes_of(path);
  ASSERT_TRUE(parse_project(with_description_edit(good, "/settings/strength", 0.5), "x").ok());
  struct Case {
    const char* pointer;
    nlohmann::json value;
    const char* message;
  };
  const Case cases[] = {
      {"/volume/dims/0", 1e300, "volume.dims[0]: expected a whole number"},
      {"/volume/dims/1", -5, "volume.dims[1]: not in"},
      {"/volume/brick_edge", "32", "volume.brick_edge: expected a whole number"},
      {"/settings/size/0", 1e30, "settings.size[0]: not in [0, 256]"},
      {"/settings/spacing", 0, "settings.spacing: not in"},
      {"/settings/strength", nullptr, "settings.strength: expected a number"},
      {"/settings/hardness", 2, "settings.hardness: not in [0, 1]"},
      {"/settings/accumulate", 1, "settings.accumulate: expected true or false"},
      {"/settings/tool_scale", 9, "settings.tool_scale: not in [0.125, 8]"},
      {"/settings/mode", "smudge", "settings.mode: unknown mode"},
      {"/settings/custom_region/3", int64_t{4'000'000'000}, "settings.custom_region[3]: not in"},
      {"/settings/mirror/axis", 7, "settings.mirror.axis: not in [0, 2]"},
      {"/settings/custom_tool", 1, "settings.custom_tool: expected true or false"},
      {"/view/camera_target/2", 1e30, "view.camera_target[2]: not in"},
      {"/view/camera_distance", -1, "view.camera_distance: not in"},
      {"/view/lod/max_level", uint64_t{1} << 63, "view.lod.max_level: not in"},
      {"/settings/shape", 3, "settings.shape: expected a string"},
  };
  for (const Case& c : cases) {
    const Result<Project> p = parse_project(with_description_edit(good, c.pointer, c.value), "f");
    ASSERT_FALSE(p.ok()) << c.pointer;
    EXPECT_NE(p.error().message().find(std::string("f: ") + c.message), std::string::npos)
        << c.pointer << ": " << p.error().message();
  }
  const auto folder = dir_.path() / "folder.sculpt";
  std::filesystem::create_directory(folder);
  const Result<Project> dir = load_project(folder);
  ASSERT_FALSE(dir.ok());
  EXPECT_NE(dir.error().message().find("folder.sculpt: is a directory"), std::string::npos);
}

TEST_F(ProjectFile, AFailedSaveLeavesTheOldFileWhole) {
  const auto path = dir_.path() / "d.sculpt";
  ASSERT_TRUE(save_project(path, volume_, settings(), nullptr, {}).ok());
  const std::vector<char> before = bytes_of(path);
  EXPECT_FALSE(
      save_project(dir_.path() / "no" / "such" / "dir.sculpt", volume_, settings(), nullptr, {})
          .ok());
  EXPECT_EQ(bytes_of(path), before);
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir_.path()))
    files.push_back(e.path());
  EXPECT_EQ(files.size(), 1u);  // no temporary left behind
}

TEST_F(ProjectFile, ASaveThatWouldNotLoadBackIsRefusedAndTheOldFileKept) {
  const auto path = dir_.path() / "e.sculpt";
  ASSERT_TRUE(save_project(path, volume_, settings(), nullptr, {}).ok());
  const std::vector<char> before = bytes_of(path);
  StationSettings nan_strength = settings();
  nan_strength.strength = std::nanf("");
  ProjectView far_camera;
  far_camera.camera_distance = std::numeric_limits<float>::infinity();
  const std::pair<Status, std::string> saves[] = {
      {save_project(path, volume_, nan_strength, nullptr, {}), "settings.strength"},
      {save_project(path, volume_, settings(), nullptr, far_camera), "view.camera_distance"}};
  for (const auto& [st, field] : saves) {
    ASSERT_FALSE(st.ok()) << field;
    EXPECT_NE(st.error().message().find("e.sculpt: " + field), std::string::npos)
        << st.error().message();
    EXPECT_NE(st.error().message().find("would not load back"), std::string::npos);
  }
  EXPECT_EQ(bytes_of(path), before);
}

// A ball brush is saved as the mode and the accumulate option beside it; a
// project saved before either loads with the old defaults (the mode it
// names, no brush, accumulate off).
TEST_F(ProjectFile, KeepsTheBrushAndAccumulateAndOldProjectsLoadWithoutThem) {
  StationSettings s = settings();
  s.brush = BallBrush::kInflate;
  s.accumulate = true;
  const auto path = dir_.path() / "b.sculpt";
  ASSERT_TRUE(save_project(path, volume_, s, nullptr, {}).ok());
  const auto p = load_project(path);
  ASSERT_TRUE(p.ok()) << p.error().message();
  EXPECT_EQ(p->settings.brush, BallBrush::kInflate);
  EXPECT_TRUE(p->settings.accumulate);

  ASSERT_TRUE(save_project(path, volume_, settings(), nullptr, {}).ok());
  const auto old = parse_project(with_description(bytes_of(path),
                                                  [](nlohmann::json& j) {
                                                    j["settings"].erase("accumulate");
                                                    ASSERT_EQ(j["settings"]["mode"], "smooth");
                                                  }),
                                 "old");
  ASSERT_TRUE(old.ok()) << old.error().message();
  EXPECT_FALSE(old->settings.brush.has_value());
  EXPECT_EQ(old->settings.mode, core::SculptMode::kSmooth);
  EXPECT_FALSE(old->settings.accumulate);
}

// A custom tool's scale (issue 23) is kept; projects from before it open
// with the tool as made.
TEST_F(ProjectFile, KeepsTheToolScaleAndOldProjectsLoadAtScaleOne) {
  StationSettings s = settings();
  s.tool_scale = 1.5f;
  const auto path = dir_.path() / "s.sculpt";
  ASSERT_TRUE(save_project(path, volume_, s, nullptr, {}).ok());
  const auto p = load_project(path);
  ASSERT_TRUE(p.ok()) << p.error().message();
  EXPECT_EQ(p->settings.tool_scale, 1.5f);
  const auto old =
      parse_project(with_description(bytes_of(path),
                                     [](nlohmann::json& j) { j["settings"].erase("tool_scale"); }),
                    "old");
  ASSERT_TRUE(old.ok()) << old.error().message();
  EXPECT_EQ(old->settings.tool_scale, 1.0f);
}

}  // namespace
}  // namespace sculpt::station
