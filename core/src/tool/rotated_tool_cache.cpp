#include "sculpt/core/tool/rotated_tool_cache.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <thread>

namespace sculpt::core {

RotatedToolCacheStats& RotatedToolCacheStats::operator+=(const RotatedToolCacheStats& o) {
  placements += o.placements;
  placement_hits += o.placement_hits;
  voxels_requested += o.voxels_requested;
  voxels_reused += o.voxels_reused;
  voxels_rotated += o.voxels_rotated;
  evictions += o.evictions;
  bytes += o.bytes;
  entries += o.entries;
  return *this;
}
glm::quat bin_orientation(const glm::quat& orientation, double step, int32_t key[4]) {
  const glm::quat q = glm::normalize(orientation);
  const float comps[4] = {q.w, q.x, q.y, q.z};
  float sign = 1.0f;
  for (float c : comps) {
    if (c != 0.0f) {
      sign = c < 0.0f ? -1.0f : 1.0f;
      break;
    }
  }
  for (int i = 0; i < 4; ++i)
    key[i] = static_cast<int32_t>(std::lround(sign * comps[i] / step));
  return glm::normalize(
      glm::quat(static_cast<float>(key[0] * step), static_cast<float>(key[1] * step),
                static_cast<float>(key[2] * step), static_cast<float>(key[3] * step)));
}

RotatedToolEntry::RotatedToolEntry(const PreparedTool& tool, const glm::mat3& rotation,
                                   glm::vec3 offset, Sampling sampling,
                                   RotatedToolCacheStats* stats)
    : tool_(&tool),
      rotation_(rotation),
      offset_(offset),
      frame_(tool, rotation, offset, sampling),
      stats_(stats),
      stride_(static_cast<size_t>(frame_.box().size().x) + kRowSlack),
      values_size_(static_cast<size_t>(frame_.box().size().y) * frame_.box().size().z * stride_),
      values_(std::make_unique_for_overwrite<uint8_t[]>(values_size_)) {
  const glm::ivec3 s = frame_.box().size();
  const size_t rows = static_cast<size_t>(s.y) * s.z;
  done_ = std::make_unique<std::atomic<uint32_t>[]>(rows);  // value-initialised: empty
  filling_ = std::make_unique<std::atomic<bool>[]>(rows);
  plans_.resize(rows);
  for (int z = 0; z < s.z; ++z)
    frame_.row_plans(z, &plans_[static_cast<size_t>(z) * s.y]);
}

const uint8_t* RotatedToolEntry::rotate_row(int y, int z, int x0, int x1,
                                            RotatedToolCacheStats& stats) {
  const Box& b = frame_.box();
  assert(x0 >= b.lo.x && x1 <= b.hi.x && x0 <= x1 && y >= b.lo.y && y < b.hi.y && z >= b.lo.z &&
         z < b.hi.z);
  const int ly = y - b.lo.y, lz = z - b.lo.z;
  const size_t r = static_cast<size_t>(lz) * b.size().y + ly;
  // Rows are short (a tool's width): a thread finding this one taken waits
  // the few microseconds its filling takes.
  std::atomic<bool>& filling = filling_[r];
  while (filling.exchange(true, std::memory_order_acquire))
    std::this_thread::yield();
  uint8_t* values = &values_[r * stride_];
  const uint32_t done = done_[r].load(std::memory_order_relaxed);  // ordered by the lock
  int lo = done_lo(done), hi = done_hi(done);
  if (lo >= hi) std::memset(values, 0, stride_);
  const int a = x0 - b.lo.x, e = x1 - b.lo.x;
  stats.voxels_requested += e - a;
  stats.voxels_reused += std::max(0, std::min(e, hi) - std::max(a, lo));
  // The tool is sampled at integer steps from the row's start (Algorithm 1
  // in fixed point), so a voxel's value does not depend on which stretch,
  // or which thread, rotated it.
  const RotationFrame::RowPlan plan = plans_[r];
  if (lo >= hi) {
    frame_.sample_row(*tool_, y, z, x0, x1, plan, values + a);
    stats.voxels_rotated += e - a;
    lo = a;
    hi = e;
  } else {
    // Keep one computed stretch per row: fill the gap on either side.
    if (a < lo) {
      frame_.sample_row(*tool_, y, z, x0, b.lo.x + lo, plan, values + a);
      stats.voxels_rotated += lo - a;
      lo = a;
    }
    if (e > hi) {
      frame_.sample_row(*tool_, y, z, b.lo.x + hi, x1, plan, values + hi);
      stats.voxels_rotated += e - hi;
      hi = e;
    }
  }
  done_[r].store(static_cast<uint32_t>(lo) | (static_cast<uint32_t>(hi) << 16),
                 std::memory_order_release);
  filling.store(false, std::memory_order_release);
  return values + a;
}

size_t RotatedToolEntry::memory_bytes() const {
  return sizeof(*this) + values_size_ +
         plans_.size() * (sizeof(std::atomic<uint32_t>) + sizeof(std::atomic<bool>) +
                          sizeof(RotationFrame::RowPlan));
}

RotatedToolCache::RotatedToolCache(std::shared_ptr<const PreparedTool> tool, Sampling sampling,
                                   size_t max_bytes, int subvoxel_steps)
    : tool_(std::move(tool)),
      sampling_(sampling),
      max_bytes_(max_bytes),
      subvoxel_steps_(subvoxel_steps),
      bin_step_(orientation_bin_step(tool_->reach_vox(sampling))) {
  assert(subvoxel_steps >= 1 && subvoxel_steps <= 4096);
  // Row stretches are int16 offsets.
  assert(glm::length(glm::vec3(tool_->dims())) < 16000.0f);
}

size_t RotatedToolCache::KeyHash::operator()(const Key& k) const {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](uint64_t v) { h = (h ^ v) * 1099511628211ull; };
  for (int32_t q : k.q)
    mix(static_cast<uint32_t>(q));
  for (int16_t f : k.f)
    mix(static_cast<uint16_t>(f));
  return static_cast<size_t>(h ^ (h >> 29));
}

RotatedToolCache::Placement RotatedToolCache::acquire(const glm::quat& orientation,
                                                      glm::vec3 position) {
  ++stats_.placements;
  Key key{};
  const glm::quat binned = bin_orientation(orientation, bin_step_, key.q);
  glm::ivec3 anchor(glm::floor(position));
  const glm::vec3 frac = position - glm::vec3(anchor);
  for (int i = 0; i < 3; ++i) {
    int f = static_cast<int>(std::lround(frac[i] * static_cast<float>(subvoxel_steps_)));
    if (f >= subvoxel_steps_) {
      f -= subvoxel_steps_;
      ++anchor[i];
    }
    key.f[i] = static_cast<int16_t>(f);
  }

  if (auto it = slots_.find(key); it != slots_.end()) {
    ++stats_.placement_hits;
    lru_.splice(lru_.begin(), lru_, it->second.lru);
    return {it->second.entry, anchor};
  }
  const glm::vec3 offset(key.f[0] / static_cast<float>(subvoxel_steps_),
                         key.f[1] / static_cast<float>(subvoxel_steps_),
                         key.f[2] / static_cast<float>(subvoxel_steps_));
  auto entry = std::make_shared<RotatedToolEntry>(*tool_, glm::mat3_cast(binned), offset, sampling_,
                                                  &stats_);
  const size_t bytes = entry->memory_bytes();
  if (bytes <= max_bytes_) {
    evict_to(max_bytes_ - bytes);
    lru_.push_front(key);
    slots_.emplace(key, Slot{entry, lru_.begin()});
    stats_.bytes += bytes;
    stats_.entries = slots_.size();
  }
  return {entry, anchor};
}

void RotatedToolCache::evict_to(size_t budget) {
  while (stats_.bytes > budget && !lru_.empty()) {
    auto it = slots_.find(lru_.back());
    stats_.bytes -= it->second.entry->memory_bytes();
    slots_.erase(it);
    lru_.pop_back();
    ++stats_.evictions;
  }
  stats_.entries = slots_.size();
}

void RotatedToolCache::clear() {
  slots_.clear();
  lru_.clear();
  stats_.bytes = 0;
  stats_.entries = 0;
}

}  // namespace sculpt::core
