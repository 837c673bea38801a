#include "sculpt/station/project/project_file.h"

#include <zlib.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "sculpt/base/atomic_file.h"
#include "sculpt/base/input_file.h"
#include "sculpt/core/grid/grid_index.h"
#include "sculpt/core/nurbs/nurbs_json.h"
#include "sculpt/core/wavelet/wavelet_pyramid.h"
#include "sculpt/sim/session/command_limits.h"
#include "sculpt/station/settings/command_codec.h"

namespace sculpt::station {
namespace {

using json = nlohmann::json;
constexpr std::array<char, 8> kMagic = {'S', 'C', 'U', 'L', 'P', 'T', 'P', 'J'};
constexpr uint8_t kUniformBrick = 0;
constexpr uint8_t kPyramidBrick = 1;
// The JSON part is small; anything larger is not a project file.
constexpr uint32_t kMaxJsonBytes = 1u << 20;

template <typename T>
void put(std::vector<uint8_t>& out, T v) {
  for (size_t i = 0; i < sizeof(T); ++i)
    out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

json vec_json(glm::vec3 v) {
  return json::array({v.x, v.y, v.z});
}

json settings_json(const StationSettings& s) {
  json j = {{"shape", sim::tool_shape_name(s.shape)},
            {"size", {s.size_a_vox, s.size_b_vox}},
            // A ball brush is saved as the mode, as a session's mode command
            // carries it.
            {"mode", sim::sculpt_mode_name(static_cast<sim::SculptModeId>(mode_choice_of(s)))},
            {"strength", s.strength},
            {"hardness", s.hardness},
            {"spacing", s.spacing},
            {"accumulate", s.accumulate},
            {"custom_tool", s.custom_tool},
            {"tool_scale", s.tool_scale},
            {"custom_region",
             {s.custom_region.lo.x, s.custom_region.lo.y, s.custom_region.lo.z,
              s.custom_region.hi.x, s.custom_region.hi.y, s.custom_region.hi.z}}};
  j["mirror"] =
      s.mirror ? json{{"axis", s.mirror->axis}, {"at", s.mirror->centre_vox}} : json(nullptr);
  j["sheet_editing"] = s.sheet_editing;
  j["sheet_influence"] = static_cast<int>(s.sheet_drag.influence);
  j["sheet_radius"] = s.sheet_drag.radius;
  return j;
}

json view_json(const ProjectView& v) {
  return {{"camera_target", vec_json(v.camera_target)},
          {"camera_yaw", v.camera_yaw},
          {"camera_pitch", v.camera_pitch},
          {"camera_distance", v.camera_distance},
          {"lod",
           {{"max_pixel_error", v.lod.max_pixel_error},
            {"max_level", v.lod.max_level},
            {"frame_budget_ms", v.lod.frame_budget_ms},
            {"fixed_level", v.lod.fixed_level}}}};
}

// Deflates everything handed to it into `out`.
class Deflater {
 public:
  explicit Deflater(std::vector<uint8_t>& out) : out_(out) {
    // Level 1: the zero runs of detail bands compress nearly as well as at
    // level 9, in a fraction of the time (saves and autosaves must be quick).
    deflateInit(&z_, 1);
  }
  ~Deflater() { deflateEnd(&z_); }
  void add(const void* data, size_t size) { run(data, size, Z_NO_FLUSH); }
  void finish() { run(nullptr, 0, Z_FINISH); }

 private:
  void run(const void* data, size_t size, int flush) {
    z_.next_in = static_cast<Bytef*>(const_cast<void*>(data));
    z_.avail_in = static_cast<uInt>(size);
    std::array<uint8_t, 1 << 16> chunk;
    do {
      z_.next_out = chunk.data();
      z_.avail_out = chunk.size();
      deflate(&z_, flush);
      out_.insert(out_.end(), chunk.data(), chunk.data() + (chunk.size() - z_.avail_out));
    } while (z_.avail_out == 0 || (flush == Z_FINISH && z_.avail_in > 0));
  }
  z_stream z_{};
  std::vector<uint8_t>& out_;
};

// Inflates a buffer piece by piece; every read says whether it got all it asked.
class Inflater {
 public:
  Inflater(const uint8_t* data, size_t size) {
    inflateInit(&z_);
    z_.next_in = const_cast<Bytef*>(data);
    z_.avail_in = static_cast<uInt>(size);
  }
  ~Inflater() { inflateEnd(&z_); }
  bool read(void* out, size_t size) {
    z_.next_out = static_cast<Bytef*>(out);
    z_.avail_out = static_cast<uInt>(size);
    while (z_.avail_out > 0) {
      const int rc = inflate(&z_, Z_NO_FLUSH);
      if (rc == Z_STREAM_END) return z_.avail_out == 0;
      if (rc != Z_OK) return false;
    }
    return true;
  }
  bool at_end() {
    uint8_t extra;
    return !read(&extra, 1);
  }

 private:
  z_stream z_{};
};

// The description's readers, below: save_project() checks with them.
StationSettings settings_of(const json& j);
ProjectView view_of(const json& j);

}  // namespace

ProjectView project_view(const OrbitCamera& camera, const LodPolicy& lod) {
  ProjectView v;
  v.camera_target = camera.target();
  v.camera_yaw = camera.yaw();
  v.camera_pitch = camera.pitch();
  v.camera_distance = camera.distance();
  v.lod = lod;
  return v;
}

Status save_project(const std::filesystem::path& path, const core::Volume& volume,
                    const StationSettings& settings, const core::Tool* custom_tool,
                    const ProjectView& view, const core::nurbs::NurbsSurface* sheet) {
  const glm::ivec3 d = volume.dims();
  json j = {
      {"volume",
       {{"dims", {d.x, d.y, d.z}},
        {"brick_edge", volume.brick_edge()},
        {"levels", volume.levels()},
        {"content_hash", volume.content_hash()}}},
      {"settings", settings_json(settings)},
      {"view", view_json(view)},
      {"tool", nullptr},
      {"sheet", sheet != nullptr ? json::parse(core::nurbs::to_json(*sheet)) : json(nullptr)}};
  if (custom_tool != nullptr) {
    const glm::ivec3 t = custom_tool->density.dims();
    j["tool"] = {{"dims", {t.x, t.y, t.z}}, {"pivot", vec_json(custom_tool->pivot)}};
  }
  const std::string text = j.dump();
  // Write only what load_project() accepts back: a NaN in the settings or the
  // view (JSON writes it as null) would make this save, and the autosave
  // after it, a file that no longer opens.
  try {
    const json written = json::parse(text);
    (void)settings_of(written["settings"]);
    (void)view_of(written["view"]);
  } catch (const std::string& what) {
    return Error(path.string() + ": " + what + ", so it would not load back; nothing written");
  }

  std::vector<uint8_t> packed;
  {
    Deflater deflater(packed);
    const glm::ivec3 grid = volume.brick_grid();
    std::vector<uint8_t> le;
    for (int64_t i = 0; i < volume.brick_count(); ++i) {
      const glm::ivec3 b = core::grid_position(i, grid);
      const core::Brick& brick = volume.brick(b);
      if (brick.is_uniform()) {
        const uint8_t rec[2] = {kUniformBrick, brick.uniform_value()};
        deflater.add(rec, 2);
        continue;
      }
      const std::span<const int16_t> c = brick.pyramid()->coefficients();
      le.clear();
      le.push_back(kPyramidBrick);
      for (int16_t v : c)
        put(le, static_cast<uint16_t>(v));
      deflater.add(le.data(), le.size());
    }
    if (custom_tool != nullptr)
      deflater.add(custom_tool->density.data(), custom_tool->density.size());
    deflater.finish();
  }

  std::vector<uint8_t> out(kMagic.begin(), kMagic.end());
  put(out, kProjectVersion);
  put(out, static_cast<uint32_t>(text.size()));
  out.insert(out.end(), text.begin(), text.end());
  put(out, static_cast<uint64_t>(packed.size()));
  out.insert(out.end(), packed.begin(), packed.end());
  put(out, static_cast<uint32_t>(crc32(0, out.data(), static_cast<uInt>(out.size()))));

  AtomicFileWriter writer(path);
  if (!writer.ok()) return writer.error();
  writer.write(out.data(), out.size());
  return writer.commit();
}

namespace {

template <typename T>
T get(const uint8_t* p) {
  T v = 0;
  for (size_t i = 0; i < sizeof(T); ++i)
    v |= static_cast<T>(static_cast<T>(p[i]) << (8 * i));
  return v;
}

// Checked readers of the description's fields. A field of the wrong type or
// out of its range throws "PATH: what is wrong" (caught by parse_project):
// nlohmann's get<int>() of 1e300 is undefined behaviour, and a tool size of
// 1e30 would take all the machine's memory when the project opens.
[[noreturn]] void bad(const std::string& path, const std::string& what) {
  throw path + ": " + what;
}

std::string range_text(double lo, double hi) {
  char text[64];
  std::snprintf(text, sizeof text, "[%.9g, %.9g]", lo, hi);
  return text;
}

const json& field(const json& j, const char* key, const std::string& path) {
  if (!j.is_object()) bad(path, "expected an object");
  const auto it = j.find(key);
  if (it == j.end()) bad(path + "." + key, "missing");
  return *it;
}

int64_t whole_in(const json& j, int64_t lo, int64_t hi, const std::string& path) {
  if (!j.is_number_integer()) bad(path, "expected a whole number");
  // Unsigned values above INT64_MAX read as negative here and fail the range.
  const auto v = j.is_number_unsigned() && j.get<uint64_t>() > uint64_t(INT64_MAX)
                     ? int64_t{-1} - int64_t{INT64_MAX}
                     : j.get<int64_t>();
  if (v < lo || v > hi) bad(path, "not in " + range_text(double(lo), double(hi)));
  return v;
}

int int_in(const json& j, int lo, int hi, const std::string& path) {
  return static_cast<int>(whole_in(j, lo, hi, path));
}

double number_in(const json& j, double lo, double hi, const std::string& path) {
  if (!j.is_number()) bad(path, "expected a number");
  const double v = j.get<double>();
  if (!(v >= lo && v <= hi)) bad(path, "not in " + range_text(lo, hi));
  return v;
}

float float_in(const json& j, double lo, double hi, const std::string& path) {
  return static_cast<float>(number_in(j, lo, hi, path));
}

bool flag(const json& j, const std::string& path) {
  if (!j.is_boolean()) bad(path, "expected true or false");
  return j.get<bool>();
}

std::string text_of(const json& j, const std::string& path) {
  if (!j.is_string()) bad(path, "expected a string");
  return j.get<std::string>();
}

const json& array_of(const json& j, size_t n, const std::string& path) {
  if (!j.is_array() || j.size() != n) bad(path, "expected " + std::to_string(n) + " values");
  return j;
}

// Positions in the scene, voxels: the session's coordinate limit.
constexpr double kMaxCoordinate = sim::kMaxCoordinateVox;

glm::vec3 position_of(const json& j, const std::string& path) {
  const json& a = array_of(j, 3, path);
  return {float_in(a[0], -kMaxCoordinate, kMaxCoordinate, path + "[0]"),
          float_in(a[1], -kMaxCoordinate, kMaxCoordinate, path + "[1]"),
          float_in(a[2], -kMaxCoordinate, kMaxCoordinate, path + "[2]")};
}

glm::ivec3 dims_of(const json& j, int hi, const std::string& path) {
  const json& a = array_of(j, 3, path);
  return {int_in(a[0], 1, hi, path + "[0]"), int_in(a[1], 1, hi, path + "[1]"),
          int_in(a[2], 1, hi, path + "[2]")};
}

StationSettings settings_of(const json& j) {
  const std::string at = "settings";
  StationSettings s;
  const auto shape = sim::parse_tool_shape(text_of(field(j, "shape", at), at + ".shape"));
  if (!shape) bad(at + ".shape", "unknown tool shape");
  s.shape = *shape;
  const json& size = array_of(field(j, "size", at), 2, at + ".size");
  // Sizes as the sessions bound them (command_limits.h); 0 for an unused one.
  s.size_a_vox = float_in(size[0], 0.0, sim::kMaxToolSizeVox, at + ".size[0]");
  s.size_b_vox = float_in(size[1], 0.0, sim::kMaxToolSizeVox, at + ".size[1]");
  const auto mode = sim::parse_sculpt_mode_id(text_of(field(j, "mode", at), at + ".mode"));
  if (!mode) bad(at + ".mode", "unknown mode");
  if (const auto brush = ball_brush_of_choice(static_cast<uint8_t>(*mode))) {
    s.brush = brush;
  } else {
    s.mode = to_core(*mode);
  }
  s.strength = float_in(field(j, "strength", at), 0.0, 1.0, at + ".strength");
  // Projects saved before tools had a hardness have hard tools.
  if (j.contains("hardness")) s.hardness = float_in(j["hardness"], 0.0, 1.0, at + ".hardness");
  s.spacing = float_in(field(j, "spacing", at), 1e-3, sim::kMaxSpacing, at + ".spacing");
  // Projects saved before the option apply a stroke's strength once.
  if (j.contains("accumulate")) s.accumulate = flag(j["accumulate"], at + ".accumulate");
  s.custom_tool = flag(field(j, "custom_tool", at), at + ".custom_tool");
  // Projects saved before custom tools scaled hold them as made.
  if (j.contains("tool_scale"))
    s.tool_scale =
        float_in(j["tool_scale"], sim::kMinToolScale, sim::kMaxToolScale, at + ".tool_scale");
  const json& r = array_of(field(j, "custom_region", at), 6, at + ".custom_region");
  int corner[6];
  for (int i = 0; i < 6; ++i)
    corner[i] = int_in(r[size_t(i)], 0, int(kMaxCoordinate),
                       at + ".custom_region[" + std::to_string(i) + "]");
  s.custom_region = core::Box{{corner[0], corner[1], corner[2]}, {corner[3], corner[4], corner[5]}};
  const json& m = field(j, "mirror", at);
  if (!m.is_null()) {
    const int axis = int_in(field(m, "axis", at + ".mirror"), 0, 2, at + ".mirror.axis");
    s.mirror = core::MirrorPlane{axis, float_in(field(m, "at", at + ".mirror"), -kMaxCoordinate,
                                                kMaxCoordinate, at + ".mirror.at")};
  }
  // Projects written before the sheet existed have none of these.
  if (j.contains("sheet_editing"))
    s.sheet_editing = flag(j["sheet_editing"], at + ".sheet_editing");
  if (j.contains("sheet_influence"))
    s.sheet_drag.influence =
        static_cast<SheetInfluence>(int_in(j["sheet_influence"], 0, 2, at + ".sheet_influence"));
  if (j.contains("sheet_radius"))
    s.sheet_drag.radius = number_in(j["sheet_radius"], 0.0, 64.0, at + ".sheet_radius");
  return s;
}

ProjectView view_of(const json& j) {
  const std::string at = "view";
  ProjectView v;
  v.camera_target = position_of(field(j, "camera_target", at), at + ".camera_target");
  // Angles are radians, wrapped by the camera; any finite turn is a view.
  v.camera_yaw = float_in(field(j, "camera_yaw", at), -1e6, 1e6, at + ".camera_yaw");
  v.camera_pitch = float_in(field(j, "camera_pitch", at), -1e6, 1e6, at + ".camera_pitch");
  v.camera_distance =
      float_in(field(j, "camera_distance", at), 1e-3, kMaxCoordinate, at + ".camera_distance");
  const json& l = field(j, "lod", at);
  const std::string lod = at + ".lod";
  // Projects of the distance-only level of detail have "full_detail_distance"
  // instead: they open with the default error.
  if (l.contains("max_pixel_error"))
    v.lod.max_pixel_error = float_in(l["max_pixel_error"], 0.05, 64.0, lod + ".max_pixel_error");
  v.lod.max_level = int_in(field(l, "max_level", lod), 0, 16, lod + ".max_level");
  v.lod.frame_budget_ms =
      number_in(field(l, "frame_budget_ms", lod), 0.0, 1000.0, lod + ".frame_budget_ms");
  v.lod.fixed_level = int_in(field(l, "fixed_level", lod), -1, 16, lod + ".fixed_level");
  return v;
}

}  // namespace

Result<Project> load_project(const std::filesystem::path& path) {
  const std::string name = path.string();
  if (const Status s = check_input_file(path); !s) return s.error();
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error(name + ": cannot open: " + std::string(std::strerror(errno)));
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  if (in.bad()) return Error(name + ": read failed");
  return parse_project(bytes, name);
}

Result<Project> parse_project(std::span<const uint8_t> bytes, const std::string& name) {
  auto fail = [&](const std::string& what) { return Error(name + ": " + what); };
  const size_t fixed = kMagic.size() + 4 + 4;
  if (bytes.size() < fixed + 8 + 4 || !std::equal(kMagic.begin(), kMagic.end(), bytes.begin()))
    return fail("not a sculpt project file");
  const uint32_t version = get<uint32_t>(&bytes[8]);
  if (version != kProjectVersion)
    return fail("project version " + std::to_string(version) + " is not supported (this is " +
                std::to_string(kProjectVersion) + ")");
  const uint32_t stored_crc = get<uint32_t>(&bytes[bytes.size() - 4]);
  if (stored_crc != crc32(0, bytes.data(), static_cast<uInt>(bytes.size() - 4)))
    return fail("damaged (checksum mismatch)");
  const uint32_t n = get<uint32_t>(&bytes[12]);
  if (n > kMaxJsonBytes || fixed + n + 8 + 4 > bytes.size()) return fail("damaged (bad sizes)");
  const uint64_t m = get<uint64_t>(&bytes[fixed + n]);
  if (m != bytes.size() - (fixed + n + 8 + 4)) return fail("damaged (bad sizes)");

  Project project;
  glm::ivec3 dims, tool_dims{0};
  uint64_t content_hash = 0;
  core::VolumeOptions options;
  try {
    const json j = json::parse(bytes.begin() + fixed, bytes.begin() + fixed + n);
    const json& v = field(j, "volume", "description");
    dims = dims_of(field(v, "dims", "volume"), int(kMaxCoordinate), "volume.dims");
    options.brick_edge = int_in(field(v, "brick_edge", "volume"), 1, 1024, "volume.brick_edge");
    options.levels = int_in(field(v, "levels", "volume"), 0, 16, "volume.levels");
    const json& hash = field(v, "content_hash", "volume");
    if (!hash.is_number_unsigned()) bad("volume.content_hash", "expected a whole number");
    content_hash = hash.get<uint64_t>();
    project.settings = settings_of(field(j, "settings", "description"));
    project.view = view_of(field(j, "view", "description"));
    if (const json& t = field(j, "tool", "description"); !t.is_null()) {
      tool_dims = dims_of(field(t, "dims", "tool"), 1024, "tool.dims");
      core::Tool tool;
      tool.pivot = position_of(field(t, "pivot", "tool"), "tool.pivot");
      project.custom_tool = std::move(tool);
    }
    // Projects written before the sheet existed have no "sheet".
    if (const auto s = j.find("sheet"); s != j.end() && !s->is_null()) {
      auto sheet = core::nurbs::parse_surface_json(s->dump());
      if (!sheet) throw "sheet: " + sheet.error().message();
      project.sheet = std::move(sheet).value();
    }
  } catch (const std::string& what) {
    return fail(what);
  } catch (const std::exception& e) {
    return fail(std::string("bad project description: ") + e.what());
  }
  if (Status st = core::Volume::validate(dims, options); !st)
    return fail("volume: " + st.error().message());
  if (project.settings.custom_tool != project.custom_tool.has_value())
    return fail("settings.custom_tool does not match the stored tool");

  auto volume = std::make_unique<core::Volume>(dims, 0, options);
  Inflater inflater(&bytes[fixed + n + 8], static_cast<size_t>(m));
  const int e = options.brick_edge;
  const size_t cube = static_cast<size_t>(e) * e * e;
  std::vector<uint8_t> raw(2 * cube);
  std::vector<uint8_t> voxels(cube);
  core::WaveletPyramid pyramid(e, options.levels);
  const glm::ivec3 grid = volume->brick_grid();
  for (int64_t i = 0; i < volume->brick_count(); ++i) {
    const glm::ivec3 b = core::grid_position(i, grid);
    uint8_t tag;
    if (!inflater.read(&tag, 1)) return fail("damaged (volume data cut short)");
    if (tag == kUniformBrick) {
      uint8_t value;
      if (!inflater.read(&value, 1)) return fail("damaged (volume data cut short)");
      std::fill(voxels.begin(), voxels.end(), value);
    } else if (tag == kPyramidBrick) {
      if (!inflater.read(raw.data(), raw.size())) return fail("damaged (volume data cut short)");
      std::span<int16_t> c = pyramid.coefficients();
      for (size_t k = 0; k < cube; ++k)
        c[k] = static_cast<int16_t>(get<uint16_t>(&raw[2 * k]));
      pyramid.decode(voxels);
    } else {
      return fail("damaged (unknown brick record)");
    }
    volume->store_brick(b, voxels);
  }
  if (project.custom_tool) {
    project.custom_tool->density = core::DenseGrid<uint8_t>(tool_dims);
    core::DenseGrid<uint8_t>& d = project.custom_tool->density;
    if (!inflater.read(d.data(), d.size())) return fail("damaged (tool data cut short)");
  }
  if (!inflater.at_end()) return fail("damaged (data after the end)");
  // Coefficients out of their ranges would decode to other voxels: the hash
  // of what was rebuilt must be the hash of what was saved.
  if (volume->content_hash() != content_hash)
    return fail("damaged (the volume does not match its content hash)");
  volume->take_dirty_bricks();
  project.volume = std::move(volume);
  return project;
}

}  // namespace sculpt::station
