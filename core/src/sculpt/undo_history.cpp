#include "sculpt/core/sculpt/undo_history.h"
#include "sculpt/core/grid/grid_index.h"

#include <vector>

namespace sculpt::core {

void UndoHistory::begin_stroke() {
  if (open_) end_stroke();
  open_ = true;
  current_ = Stroke{};
  current_bricks_.clear();
}

void UndoHistory::before_change(const Volume& volume, glm::ivec3 b) {
  if (!open_) return;
  const auto index = static_cast<int64_t>(grid_index(b, volume.brick_grid()));
  if (!current_bricks_.insert(index).second) return;
  const Brick& brick = volume.brick(b);
  current_.bytes += brick.memory_bytes();
  bytes_ += brick.memory_bytes();
  current_.bricks.emplace_back(b, brick);
}

void UndoHistory::end_stroke() {
  if (!open_) return;
  open_ = false;
  current_bricks_.clear();
  if (current_.bricks.empty()) return;
  for (const Stroke& s : redo_)
    bytes_ -= s.bytes;
  redo_.clear();
  undo_.push_back(std::move(current_));
  current_ = Stroke{};
  enforce_cap();
}

void UndoHistory::enforce_cap() {
  while (bytes_ > max_bytes_ && !undo_.empty()) {
    bytes_ -= undo_.front().bytes;
    undo_.pop_front();
    ++dropped_;
  }
}

void UndoHistory::swap_into(Volume& volume, Stroke& stroke) {
  // Restoring goes through store_brick, so the brick is re-encoded from its
  // exact voxels, re-padded and marked dirty for the mesher like any edit.
  std::vector<uint8_t> voxels(static_cast<size_t>(volume.brick_edge()) * volume.brick_edge() *
                              volume.brick_edge());
  size_t bytes = 0;
  for (auto& [b, saved] : stroke.bricks) {
    Brick current = volume.brick(b);
    saved.extract_level(0, voxels);
    volume.store_brick(b, voxels);
    saved = std::move(current);
    bytes += saved.memory_bytes();
  }
  stroke.bytes = bytes;
}

bool UndoHistory::undo(Volume& volume) {
  if (open_) end_stroke();
  if (undo_.empty()) return false;
  Stroke s = std::move(undo_.back());
  undo_.pop_back();
  bytes_ -= s.bytes;
  swap_into(volume, s);
  bytes_ += s.bytes;
  redo_.push_back(std::move(s));
  return true;
}

bool UndoHistory::redo(Volume& volume) {
  if (open_) end_stroke();
  if (redo_.empty()) return false;
  Stroke s = std::move(redo_.back());
  redo_.pop_back();
  bytes_ -= s.bytes;
  swap_into(volume, s);
  bytes_ += s.bytes;
  undo_.push_back(std::move(s));
  return true;
}

}  // namespace sculpt::core
