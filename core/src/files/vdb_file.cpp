#include "sculpt/core/files/vdb_file.h"

// The one translation unit that includes OpenVDB (docs/design.md: its headers
// cost about 20 s of compile each, and CI builds the project four times).
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/SignedFloodFill.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <mutex>
#include <sstream>

#include "sculpt/base/atomic_file.h"

namespace sculpt::core {
namespace {

constexpr const char* kDensityName = "density";
constexpr const char* kSurfaceName = "surface";
constexpr const char* kDimsKey = "sculpt_dims";
constexpr const char* kPivotKey = "sculpt_pivot";

void initialize_once() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

std::string voxel_text(int x, int y, int z) {
  return "(" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) + ")";
}

// Voxel (x, y, z) at world (x, y, z): the exported meshes' coordinates.
openvdb::math::Transform::Ptr voxel_unit_transform() {
  return openvdb::math::Transform::createLinearTransform(1.0);
}

void set_dims_meta(openvdb::GridBase& grid, glm::ivec3 dims) {
  grid.insertMeta(kDimsKey, openvdb::Vec3IMetadata(openvdb::Vec3i(dims.x, dims.y, dims.z)));
}

openvdb::FloatGrid::Ptr density_grid(const DenseGrid<uint8_t>& density) {
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName(kDensityName);
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setTransform(voxel_unit_transform());
  set_dims_meta(*grid, density.dims());
  auto acc = grid->getAccessor();
  const glm::ivec3 d = density.dims();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x)
        if (const uint8_t v = density.at(x, y, z); v != 0)
          acc.setValue(openvdb::Coord(x, y, z), static_cast<float>(v) / 255.0f);
  // Full regions (1.0 throughout) become tiles: a solid block costs no leaves.
  grid->tree().prune();
  return grid;
}

Result<openvdb::FloatGrid::Ptr> surface_grid(const DenseGrid<float>& surface) {
  auto grid = openvdb::FloatGrid::create(kVdbHalfWidth);
  grid->setName(kSurfaceName);
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  grid->setTransform(voxel_unit_transform());
  set_dims_meta(*grid, surface.dims());
  auto acc = grid->getAccessor();
  const glm::ivec3 d = surface.dims();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const float v = surface.at(x, y, z);
        if (std::isnan(v)) return Error("voxel " + voxel_text(x, y, z) + " is NaN");
        if (std::abs(v) < kVdbHalfWidth) acc.setValue(openvdb::Coord(x, y, z), v);
      }
  // Inactive space inside the surface reads -half width, as a level set's must.
  openvdb::tools::signedFloodFill(grid->tree());
  return grid;
}

// A uniform scale plus a translation, nothing else: the project's voxels are
// cubes on axis-aligned rows. Returns the voxel size or an error.
Result<double> uniform_voxel_size(const openvdb::GridBase& grid) {
  const openvdb::math::Transform& t = grid.transform();
  if (!t.isLinear()) return Error("its transform is not linear (" + t.mapType() + ")");
  const openvdb::math::Mat4d m = t.baseMap()->getAffineMap()->getMat4();
  double largest = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      largest = std::max(largest, std::abs(m(i, j)));
  if (!std::isfinite(largest) || largest == 0.0) {
    return Error("its transform is not a finite, invertible scale");
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (i != j && std::abs(m(i, j)) > 1e-9 * largest) {
        return Error("its transform rotates or shears the grid");
      }
  const double s = m(0, 0);
  if (!(s > 0.0) || !(m(1, 1) > 0.0) || !(m(2, 2) > 0.0)) {
    return Error("its transform mirrors the grid");
  }
  if (std::abs(m(1, 1) - s) > 1e-9 * s || std::abs(m(2, 2) - s) > 1e-9 * s) {
    return Error("its voxels are not cubes (voxel size " + t.voxelSize().str() + ")");
  }
  return s;
}

struct GridBox {
  openvdb::Coord origin;
  glm::ivec3 dims{0};
};

// Which voxels to read: [0, sculpt_dims) when the file says so (ours), else
// the active bounding box. Checked against the limits before anything is
// allocated.
Result<GridBox> grid_box(const openvdb::GridBase& grid, const VdbLimits& limits) {
  const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
  int64_t lo[3] = {0, 0, 0};
  int64_t size[3] = {0, 0, 0};
  if (auto meta = grid.getMetadata<openvdb::Vec3IMetadata>(kDimsKey)) {
    const openvdb::Vec3i v = meta->value();
    for (int i = 0; i < 3; ++i)
      size[i] = v[i];
    if (size[0] < 1 || size[1] < 1 || size[2] < 1) {
      return Error(std::string(kDimsKey) + " " + v.str() + " is not a size");
    }
    if (!active.empty()) {
      for (int i = 0; i < 3; ++i)
        if (active.min()[i] < 0 || active.max()[i] >= size[i]) {
          return Error("active voxels outside its " + std::string(kDimsKey) + " " + v.str());
        }
    }
  } else {
    if (active.empty()) return Error("it has no active voxels");
    for (int i = 0; i < 3; ++i) {
      lo[i] = active.min()[i];
      size[i] = int64_t{active.max()[i]} - active.min()[i] + 1;
    }
  }
  int64_t voxels = 1;
  for (int i = 0; i < 3; ++i) {
    if (size[i] > limits.max_edge) {
      return Error(std::to_string(size[0]) + " x " + std::to_string(size[1]) + " x " +
                   std::to_string(size[2]) + " voxels: more than " +
                   std::to_string(limits.max_edge) + " on an edge");
    }
    voxels *= size[i];
  }
  if (voxels > limits.max_voxels) {
    return Error(std::to_string(size[0]) + " x " + std::to_string(size[1]) + " x " +
                 std::to_string(size[2]) + " voxels: more than the limit of " +
                 std::to_string(limits.max_voxels));
  }
  GridBox box;
  box.origin = openvdb::Coord(static_cast<int32_t>(lo[0]), static_cast<int32_t>(lo[1]),
                              static_cast<int32_t>(lo[2]));
  box.dims =
      glm::ivec3(static_cast<int>(size[0]), static_cast<int>(size[1]), static_cast<int>(size[2]));
  return box;
}

// The box's voxels, each through `convert`; an error at the first value that
// is not a finite number.
template <class T, class Convert>
Result<DenseGrid<T>> read_values(const openvdb::FloatGrid& grid, const GridBox& box,
                                 Convert convert) {
  DenseGrid<T> out(box.dims);
  auto acc = grid.getConstAccessor();
  for (int z = 0; z < box.dims.z; ++z)
    for (int y = 0; y < box.dims.y; ++y)
      for (int x = 0; x < box.dims.x; ++x) {
        const float v = acc.getValue(box.origin.offsetBy(x, y, z));
        if (!std::isfinite(v)) {
          return Error("voxel " + voxel_text(x, y, z) + " of '" + grid.getName() +
                       "' is not a finite number");
        }
        out.at(x, y, z) = convert(v);
      }
  return out;
}

Result<VdbGridsIn> read_grids(std::istream& in, const VdbLimits& limits) {
  initialize_once();
  openvdb::io::Stream stream(in, /*delayLoad=*/false);
  const openvdb::GridPtrVecPtr grids = stream.getGrids();
  openvdb::GridBase::Ptr chosen;
  std::string found;
  for (const auto& g : *grids) {
    if (!g) continue;
    found += (found.empty() ? "" : ", ") + ("'" + g->getName() + "' (" + g->valueType() + ")");
    if (g->getName() == kDensityName) chosen = g;
  }
  if (!chosen) {
    for (const auto& g : *grids)
      if (g && g->getName() == kSurfaceName) chosen = g;
  }
  if (!chosen) {
    for (const auto& g : *grids)
      if (g && g->isType<openvdb::FloatGrid>() && g->getGridClass() == openvdb::GRID_LEVEL_SET) {
        chosen = g;
        break;
      }
  }
  if (!chosen) {
    return Error("no float grid named 'density' and no level set (grids: " +
                 (found.empty() ? std::string("none") : found) + ")");
  }
  const std::string name = chosen->getName();
  if (!chosen->isType<openvdb::FloatGrid>()) {
    return Error("grid '" + name + "' holds " + chosen->valueType() + " values, not float");
  }
  auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(chosen);
  auto voxel_size = uniform_voxel_size(*grid);
  if (!voxel_size) return voxel_size.error().in("grid '" + name + "'");
  auto box = grid_box(*grid, limits);
  if (!box) return box.error().in("grid '" + name + "'");

  VdbGridsIn out;
  out.grid_name = name;
  if (name == kDensityName) {
    // Fog volumes from other tools may exceed 1 (Houdini's do): full.
    auto density = read_values<uint8_t>(*grid, *box, [](float v) {
      return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    });
    if (!density) return density.error();
    out.density = std::move(*density);
  } else {
    const double scale = *voxel_size;
    auto surface =
        read_values<float>(*grid, *box, [scale](float v) { return static_cast<float>(v / scale); });
    if (!surface) return surface.error();
    out.surface = std::move(*surface);
  }
  if (auto meta = grid->getMetadata<openvdb::Vec3SMetadata>(kPivotKey)) {
    const openvdb::Vec3s p = meta->value();
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      return Error(std::string(kPivotKey) + " is not 3 finite numbers");
    }
    out.pivot = glm::vec3(p[0], p[1], p[2]);
  }
  return out;
}

}  // namespace

bool is_vdb_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".vdb";
}

Status write_vdb(const std::filesystem::path& path, const VdbGridsOut& grids) {
  initialize_once();
  std::string bytes;
  try {
    openvdb::GridCPtrVec out;
    if (grids.density != nullptr) {
      auto grid = density_grid(*grids.density);
      if (grids.pivot) {
        const glm::vec3 p = *grids.pivot;
        grid->insertMeta(kPivotKey, openvdb::Vec3SMetadata(openvdb::Vec3s(p.x, p.y, p.z)));
      }
      out.push_back(grid);
    }
    if (grids.surface != nullptr) {
      auto grid = surface_grid(*grids.surface);
      if (!grid) return grid.error().in(path.string());
      out.push_back(*grid);
    }
    if (out.empty()) return Error(path.string() + ": no grid to write");
    openvdb::MetaMap file_meta;
    file_meta.insertMeta("creator", openvdb::StringMetadata("sculpt"));
    std::ostringstream stream(std::ios::binary);
    openvdb::io::Stream(stream).write(out, file_meta);
    bytes = std::move(stream).str();
  } catch (const std::exception& e) {
    return Error(path.string() + ": OpenVDB could not write it: " + e.what());
  }
  AtomicFileWriter file(path);
  if (!file.ok()) return file.error();
  file.write(bytes);
  return file.commit();
}

Result<VdbGridsIn> read_vdb(std::istream& in, const std::string& name, const VdbLimits& limits) {
  try {
    auto grids = read_grids(in, limits);
    if (!grids) return grids.error().in(name);
    return grids;
  } catch (const std::bad_alloc&) {
    return Error(name + ": not a readable OpenVDB file (it asks for more memory than there is)");
  } catch (const std::exception& e) {
    // openvdb::Exception's what() already names its kind ("IoError: ...").
    return Error(name + ": not a readable OpenVDB file: " + e.what());
  }
}

Result<VdbGridsIn> read_vdb(const std::filesystem::path& path, const VdbLimits& limits) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Error(path.string() + ": is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error(path.string() + ": cannot open");
  return read_vdb(in, path.string(), limits);
}

}  // namespace sculpt::core
