#include "sculpt/station/project/project_file.h"

#include <zlib.h>

#include <array>
#include <cstring>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "sculpt/base/atomic_file.h"
#include "sculpt/core/grid/grid_index.h"
#include "sculpt/core/nurbs/nurbs_json.h"
#include "sculpt/core/wavelet/wavelet_pyramid.h"

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
            {"mode", sim::sculpt_mode_name(static_cast<sim::SculptModeId>(s.mode))},
            {"strength", s.strength},
            {"spacing", s.spacing},
            {"custom_tool", s.custom_tool},
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
           {{"full_detail_distance", v.lod.full_detail_distance},
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

}  // namespace

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

glm::vec3 vec_of(const json& j) {
  if (!j.is_array() || j.size() != 3) throw std::string("expected three numbers");
  return {j[0].get<float>(), j[1].get<float>(), j[2].get<float>()};
}

StationSettings settings_of(const json& j) {
  StationSettings s;
  const auto shape = sim::parse_tool_shape(j.at("shape").get<std::string>());
  if (!shape) throw std::string("settings.shape: unknown tool shape");
  s.shape = *shape;
  s.size_a_vox = j.at("size").at(0).get<float>();
  s.size_b_vox = j.at("size").at(1).get<float>();
  const auto mode = sim::parse_sculpt_mode_id(j.at("mode").get<std::string>());
  if (!mode) throw std::string("settings.mode: unknown mode");
  s.mode = static_cast<core::SculptMode>(*mode);
  s.strength = j.at("strength").get<float>();
  s.spacing = j.at("spacing").get<float>();
  s.custom_tool = j.at("custom_tool").get<bool>();
  const json& r = j.at("custom_region");
  s.custom_region = core::Box{{r.at(0).get<int>(), r.at(1).get<int>(), r.at(2).get<int>()},
                              {r.at(3).get<int>(), r.at(4).get<int>(), r.at(5).get<int>()}};
  const json& m = j.at("mirror");
  if (!m.is_null()) {
    const int axis = m.at("axis").get<int>();
    if (axis < 0 || axis > 2) throw std::string("settings.mirror.axis: not 0, 1 or 2");
    s.mirror = core::MirrorPlane{axis, m.at("at").get<float>()};
  }
  s.sheet_editing = j.value("sheet_editing", false);
  const int influence = j.value("sheet_influence", static_cast<int>(s.sheet_drag.influence));
  if (influence < 0 || influence > 2) throw std::string("settings.sheet_influence: not 0, 1 or 2");
  s.sheet_drag.influence = static_cast<SheetInfluence>(influence);
  s.sheet_drag.radius = j.value("sheet_radius", s.sheet_drag.radius);
  if (!(s.sheet_drag.radius >= 0 && s.sheet_drag.radius <= 64))
    throw std::string("settings.sheet_radius: out of range");
  if (!(s.spacing > 0) || !(s.strength >= 0 && s.strength <= 1))
    throw std::string("settings: strength or spacing out of range");
  return s;
}

ProjectView view_of(const json& j) {
  ProjectView v;
  v.camera_target = vec_of(j.at("camera_target"));
  v.camera_yaw = j.at("camera_yaw").get<float>();
  v.camera_pitch = j.at("camera_pitch").get<float>();
  v.camera_distance = j.at("camera_distance").get<float>();
  const json& l = j.at("lod");
  v.lod.full_detail_distance = l.at("full_detail_distance").get<float>();
  v.lod.max_level = l.at("max_level").get<int>();
  v.lod.frame_budget_ms = l.at("frame_budget_ms").get<double>();
  v.lod.fixed_level = l.at("fixed_level").get<int>();
  return v;
}

}  // namespace

Result<Project> load_project(const std::filesystem::path& path) {
  const std::string name = path.string();
  auto fail = [&](const std::string& what) { return Error(name + ": " + what); };
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail("cannot open: " + std::string(std::strerror(errno)));
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
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
    const json& v = j.at("volume");
    dims = glm::ivec3(v.at("dims").at(0).get<int>(), v.at("dims").at(1).get<int>(),
                      v.at("dims").at(2).get<int>());
    options.brick_edge = v.at("brick_edge").get<int>();
    options.levels = v.at("levels").get<int>();
    content_hash = v.at("content_hash").get<uint64_t>();
    project.settings = settings_of(j.at("settings"));
    project.view = view_of(j.at("view"));
    if (const json& t = j.at("tool"); !t.is_null()) {
      tool_dims = glm::ivec3(t.at("dims").at(0).get<int>(), t.at("dims").at(1).get<int>(),
                             t.at("dims").at(2).get<int>());
      if (glm::any(glm::lessThan(tool_dims, glm::ivec3(1))) ||
          glm::any(glm::greaterThan(tool_dims, glm::ivec3(1024))))
        throw std::string("tool.dims out of range");
      core::Tool tool;
      tool.pivot = vec_of(t.at("pivot"));
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
