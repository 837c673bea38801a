#include "sculpt/core/volume/volume_io.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "sculpt/base/atomic_file.h"

namespace sculpt::core {

Result<Volume> read_volume_nrrd(const std::filesystem::path& path, const VolumeOptions& options,
                                const NrrdLimits& limits, const DensityWindow* window) {
  auto reader = NrrdReader::open(path, limits);
  if (!reader) return reader.error();
  const NrrdHeader& h = reader->header();
  if (h.type != NrrdType::kUInt8 && window == nullptr) {
    return Error(path.string() + ": holds " + nrrd_type_name(h.type) +
                 " voxels: map them to density with --window LO,HI or --data-iso V");
  }
  if (Status st = Volume::validate(h.dims, options); !st) return st.error().in(path.string());

  // One slab of brick_edge slices at a time: read it, then encode its bricks.
  const int e = options.brick_edge;
  const size_t slice = static_cast<size_t>(h.dims.x) * h.dims.y;
  std::vector<uint8_t> slab;
  Volume volume(h.dims, 0, options);
  for (int z0 = 0; z0 < h.dims.z; z0 += e) {
    const int n = std::min(e, h.dims.z - z0);
    slab.resize(slice * n);
    if (Status st = reader->read_density_slices(n, window, slab); !st) return st.error();
    DenseGrid<uint8_t> grid(glm::ivec3(h.dims.x, h.dims.y, n));
    grid.values().swap(slab);
    volume.write(glm::ivec3(0, 0, z0), grid);
    grid.values().swap(slab);
  }
  volume.take_dirty_bricks();  // a freshly loaded volume has nothing to re-mesh "again"
  return volume;
}

Status write_volume_nrrd(const std::filesystem::path& path, const Volume& volume, int level) {
  AtomicFileWriter out(path);
  if (!out.ok()) return out.error();
  const glm::ivec3 d = volume.level_dims(level);
  out.write(nrrd_header_text(d, NrrdType::kUInt8));
  const int m = volume.brick_edge() >> level;
  for (int z0 = 0; z0 < d.z; z0 += m) {
    const DenseGrid<uint8_t> slab =
        volume.read(Box{glm::ivec3(0, 0, z0), glm::ivec3(d.x, d.y, std::min(z0 + m, d.z))}, level);
    out.write(slab.data(), slab.size());
  }
  return out.commit();
}

}  // namespace sculpt::core
