#include "sculpt/core/files/vdb_file.h"

// The one translation unit that includes OpenVDB (docs/design.md: its headers
// cost about 20 s of compile each, and CI builds the project four times).
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/SignedFloodFill.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <vector>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sculpt/base/atomic_file.h"
#include "sculpt/base/input_file.h"

// Under a sanitizer the child process keeps its report but not the address
// space limit (see run_reader_child()).
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__) || defined(__SANITIZE_MEMORY__)
#define SCULPT_VDB_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#define SCULPT_VDB_SANITIZED 1
#endif
#endif
#ifdef SCULPT_VDB_SANITIZED
#include <sanitizer/common_interface_defs.h>
#endif

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

// The grid read_vdb() takes, checked, before any voxel is read.
struct Chosen {
  openvdb::FloatGrid::Ptr grid;
  std::string name;
  GridBox box;
  double voxel_size = 1.0;
  std::optional<glm::vec3> pivot;
};

Result<Chosen> choose_grid(std::istream& in, const VdbLimits& limits) {
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
  Chosen out;
  out.name = chosen->getName();
  if (!chosen->isType<openvdb::FloatGrid>()) {
    return Error("grid '" + out.name + "' holds " + chosen->valueType() + " values, not float");
  }
  out.grid = openvdb::gridPtrCast<openvdb::FloatGrid>(chosen);
  auto voxel_size = uniform_voxel_size(*out.grid);
  if (!voxel_size) return voxel_size.error().in("grid '" + out.name + "'");
  out.voxel_size = *voxel_size;
  auto box = grid_box(*out.grid, limits);
  if (!box) return box.error().in("grid '" + out.name + "'");
  out.box = *box;
  if (auto meta = out.grid->getMetadata<openvdb::Vec3SMetadata>(kPivotKey)) {
    const openvdb::Vec3s p = meta->value();
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      return Error(std::string(kPivotKey) + " is not 3 finite numbers");
    }
    out.pivot = glm::vec3(p[0], p[1], p[2]);
  }
  return out;
}

// ---------------------------------------------------------------------------
// Reading in a child process.
//
// Debian's OpenVDB 10.0.1 writes past a heap buffer in io::bloscFromStream()
// on a crafted .vdb (a stored chunk longer than the leaf it fills; found by
// tests/fuzz/vdb_file_fuzz.cpp, tests/data/vdb/crafted_blosc_heap_overflow.vdb),
// loads an uninitialised bool in RootNode.h on others, and allocates what a
// length in the file says before it reads the bytes (a damaged file asks for
// gigabytes). None of that can be caught in-process, so read_vdb() forks: the
// child parses with OpenVDB under an address-space limit (RLIMIT_AS) and
// streams the dense result through a pipe; the parent checks every length
// against the limits it enforces anyway before it allocates, and a child that
// crashes or dies becomes one error line naming the file. Writing stays
// in-process: the grids written are our own.
//
// The pipe carries records: a tag byte, a uint32 length, that many bytes.
//   'H' header: uint8 kind (0 density, 1 surface), int32 dims[3], uint8 has
//       pivot, float pivot[3], then the grid's name;
//   'D' voxel bytes (density uint8 or surface float, x fastest), in order;
//   'K' the end (all voxels sent); 'E' an error message (the whole answer).

constexpr size_t kHeaderFixed = 1 + 3 * 4 + 1 + 3 * 4;
constexpr size_t kMaxNameBytes = 4096;
constexpr size_t kMaxMessageBytes = 4096;
constexpr size_t kChunkBytes = size_t{1} << 20;

// Every byte, through EINTR and partial writes; false when the parent is gone.
bool write_all(int fd, const void* data, size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

bool send_record(int fd, char tag, const void* data, size_t size) {
  char head[5];
  head[0] = tag;
  const auto length = static_cast<uint32_t>(size);
  std::memcpy(head + 1, &length, 4);
  return write_all(fd, head, sizeof(head)) && write_all(fd, data, size);
}

// Bytes until `size` are read (true), or end of file / an error (false).
bool read_all(int fd, void* data, size_t size) {
  char* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t n = ::read(fd, p, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    if (n == 0) return false;
    p += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

// The chosen grid's voxels in the header's order, each through `convert`, in
// chunks of kChunkBytes; an error at the first value that is not a finite
// number (some voxels may have gone out: the parent drops them).
template <class T, class Convert>
Status send_values(int fd, const Chosen& c, Convert convert) {
  std::vector<T> chunk;
  chunk.reserve(kChunkBytes / sizeof(T));
  auto acc = c.grid->getConstAccessor();
  const glm::ivec3 d = c.box.dims;
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const float v = acc.getValue(c.box.origin.offsetBy(x, y, z));
        if (!std::isfinite(v)) {
          return Error("voxel " + voxel_text(x, y, z) + " of '" + c.name +
                       "' is not a finite number");
        }
        chunk.push_back(convert(v));
        if (chunk.size() == chunk.capacity()) {
          if (!send_record(fd, 'D', chunk.data(), chunk.size() * sizeof(T))) {
            return Error("the reading process lost its pipe");
          }
          chunk.clear();
        }
      }
  if (!chunk.empty() && !send_record(fd, 'D', chunk.data(), chunk.size() * sizeof(T))) {
    return Error("the reading process lost its pipe");
  }
  return {};
}

Status send_grid(int fd, std::istream& in, const VdbLimits& limits) {
  auto c = choose_grid(in, limits);
  if (!c) return c.error();
  const bool density = c->name == kDensityName;
  std::string header(kHeaderFixed, '\0');
  header[0] = density ? 0 : 1;
  const int32_t dims[3] = {c->box.dims.x, c->box.dims.y, c->box.dims.z};
  std::memcpy(&header[1], dims, sizeof(dims));
  header[13] = c->pivot ? 1 : 0;
  const glm::vec3 pivot = c->pivot.value_or(glm::vec3(0.0f));
  const float p[3] = {pivot.x, pivot.y, pivot.z};
  std::memcpy(&header[14], p, sizeof(p));
  header += c->name.substr(0, kMaxNameBytes);
  if (!send_record(fd, 'H', header.data(), header.size())) {
    return Error("the reading process lost its pipe");
  }
  Status sent;
  if (density) {
    // Fog volumes from other tools may exceed 1 (Houdini's do): full.
    sent = send_values<uint8_t>(fd, *c, [](float v) {
      return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
    });
  } else {
    const double scale = c->voxel_size;
    sent = send_values<float>(fd, *c, [scale](float v) { return static_cast<float>(v / scale); });
  }
  if (!sent.ok()) return sent;
  if (!send_record(fd, 'K', nullptr, 0)) return Error("the reading process lost its pipe");
  return {};
}

[[noreturn]] void run_reader_child(int fd, std::istream& in, const std::string& name,
                                   const VdbLimits& limits) {
  // A crash here is the answer the parent looks for: the default actions, not
  // the handlers of the program (or of libFuzzer, which would record the
  // child's crash as its own).
  for (int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL})
    std::signal(sig, SIG_DFL);
  std::signal(SIGPIPE, SIG_IGN);
#ifdef SCULPT_VDB_SANITIZED
  __sanitizer_set_death_callback(nullptr);
#else
  // The sanitizers reserve terabytes of address space for their shadow
  // memory, so the limit is set only in ordinary builds.
  const auto bytes = static_cast<rlim_t>(limits.reader_address_space);
  const rlimit limit{bytes, bytes};
  setrlimit(RLIMIT_AS, &limit);
#endif
  const auto cpu = static_cast<rlim_t>(std::max(1, limits.reader_cpu_seconds));
  const rlimit cpu_limit{cpu, cpu + 1};  // SIGXCPU, a second later SIGKILL
  setrlimit(RLIMIT_CPU, &cpu_limit);
  std::signal(SIGXCPU, SIG_DFL);
  if (limits.reader_stderr_to_null) {
    ::setenv("LIBC_FATAL_STDERR_", "1", 1);  // glibc's abort messages: stderr, not the tty
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null >= 0) ::dup2(null, STDERR_FILENO);
  }
  Status status;
  try {
    status = send_grid(fd, in, limits);
    if (!status.ok()) status = status.error().in(name);
  } catch (const std::bad_alloc&) {
    status = Error(name + ": not a readable OpenVDB file (it asks for more memory than there is)");
  } catch (const std::exception& e) {
    // openvdb::Exception's what() already names its kind ("IoError: ...").
    status = Error(name + ": not a readable OpenVDB file: " + e.what());
  }
  if (status.ok()) ::_exit(0);
  const std::string message = status.error().message().substr(0, kMaxMessageBytes);
  ::_exit(send_record(fd, 'E', message.data(), message.size()) ? 0 : 1);
}

// What came through the pipe: `answered` when the child finished its answer
// (a result or its own error), else `grids` holds what was wrong with it.
struct Received {
  bool answered = false;
  Result<VdbGridsIn> grids = Error("");
};

Received receive(int fd, const std::string& name, const VdbLimits& limits) {
  Received r;
  const auto fail = [&](const std::string& why) {
    r.grids = Error(name + ": OpenVDB could not read it (" + why + ")");
    return r;
  };
  const auto record = [&](char* tag, uint32_t* length) {
    char head[5];
    if (!read_all(fd, head, sizeof(head))) return false;
    *tag = head[0];
    std::memcpy(length, head + 1, 4);
    return true;
  };
  char tag = 0;
  uint32_t length = 0;
  if (!record(&tag, &length)) return fail("its reader stopped without an answer");
  if (tag == 'E') {
    if (length == 0 || length > kMaxMessageBytes) return fail("its reader sent a bad answer");
    std::string message(length, '\0');
    if (!read_all(fd, message.data(), length)) return fail("its reader's answer was cut off");
    r.answered = true;
    r.grids = Error(std::move(message));
    return r;
  }
  if (tag != 'H' || length < kHeaderFixed || length > kHeaderFixed + kMaxNameBytes) {
    return fail("its reader sent a bad answer");
  }
  std::string header(length, '\0');
  if (!read_all(fd, header.data(), length)) return fail("its reader's answer was cut off");
  int32_t dims[3];
  std::memcpy(dims, &header[1], sizeof(dims));
  int64_t voxels = 1;
  for (const int32_t d : dims) {
    if (d < 1 || d > limits.max_edge) return fail("its reader sent a bad size");
    voxels *= d;
  }
  if (voxels > limits.max_voxels) return fail("its reader sent a bad size");
  float p[3];
  std::memcpy(p, &header[14], sizeof(p));
  VdbGridsIn out;
  out.grid_name = header.substr(kHeaderFixed);
  if (header[13] != 0) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      return fail("its reader sent a bad pivot");
    }
    out.pivot = glm::vec3(p[0], p[1], p[2]);
  }
  const glm::ivec3 size(dims[0], dims[1], dims[2]);
  char* bytes = nullptr;
  size_t expected = 0;
  if (header[0] == 0) {
    out.density.emplace(size);
    bytes = reinterpret_cast<char*>(out.density->data());
    expected = out.density->size();
  } else {
    out.surface.emplace(size);
    bytes = reinterpret_cast<char*>(out.surface->data());
    expected = out.surface->size() * sizeof(float);
  }
  size_t got = 0;
  while (true) {
    if (!record(&tag, &length)) return fail("its reader's answer was cut off");
    if (tag == 'D' && length > 0 && length <= expected - got) {
      if (!read_all(fd, bytes + got, length)) return fail("its reader's answer was cut off");
      got += length;
    } else if (tag == 'E' && length > 0 && length <= kMaxMessageBytes) {
      std::string message(length, '\0');
      if (!read_all(fd, message.data(), length)) return fail("its reader's answer was cut off");
      r.answered = true;
      r.grids = Error(std::move(message));
      return r;
    } else if (tag == 'K' && length == 0 && got == expected) {
      r.answered = true;
      r.grids = std::move(out);
      return r;
    } else {
      return fail("its reader sent a bad answer");
    }
  }
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
  // Registered once here, so that each child does not pay for it again.
  initialize_once();
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    return Error(name + ": cannot start the OpenVDB reader: " + std::strerror(errno));
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    return Error(name + ": cannot start the OpenVDB reader: " + std::strerror(err));
  }
  if (pid == 0) {
    ::close(fds[0]);
    run_reader_child(fds[1], in, name, limits);
  }
  ::close(fds[1]);
  Received r = receive(fds[0], name, limits);
  ::close(fds[0]);
  int status = 0;
  bool killed = false;
  pid_t waited = 0;
  // An answer that broke off: unless the child has already ended (crashed),
  // it may still be writing, or hung.
  if (!r.answered) {
    while ((waited = ::waitpid(pid, &status, WNOHANG)) < 0 && errno == EINTR) {
    }
    if (waited == 0) {
      ::kill(pid, SIGKILL);
      killed = true;
    }
  }
  if (waited != pid) {
    while (::waitpid(pid, &status, 0) < 0) {
      if (errno != EINTR) return Error(name + ": lost the OpenVDB reader: " + std::strerror(errno));
    }
  }
  if (r.answered && WIFEXITED(status) && WEXITSTATUS(status) == 0) return std::move(r.grids);
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGXCPU) {
    return Error(name + ": OpenVDB could not read it in " +
                 std::to_string(limits.reader_cpu_seconds) + " s of CPU time (a damaged file?)");
  }
  if (WIFSIGNALED(status) && !(killed && WTERMSIG(status) == SIGKILL)) {
    return Error(name + ": OpenVDB could not read it (crashed: signal " +
                 std::to_string(WTERMSIG(status)) + ")");
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
    return Error(name + ": OpenVDB could not read it (its reader exited with status " +
                 std::to_string(WEXITSTATUS(status)) + ")");
  }
  return std::move(r.grids);
}

Result<VdbGridsIn> read_vdb(const std::filesystem::path& path, const VdbLimits& limits) {
  if (const Status s = check_input_file(path); !s) return s.error();
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error(path.string() + ": cannot open");
  return read_vdb(in, path.string(), limits);
}

}  // namespace sculpt::core
