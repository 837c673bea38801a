#include "sculpt/core/haptics/patch_exchange.h"

namespace sculpt::core {

PatchExchange::PatchExchange(int edge) {
  for (PatchSnapshot& s : buffers_)
    s.phi.reserve(size_t(edge) * size_t(edge) * size_t(edge));
}

void PatchExchange::publish() {
  // Release: the reader that takes this slot sees everything written to it.
  back_ = ready_.exchange(back_ | kFresh, std::memory_order_acq_rel) & 3u;
}

const PatchSnapshot& PatchExchange::acquire() {
  if (ready_.load(std::memory_order_relaxed) & kFresh)
    front_ = ready_.exchange(front_, std::memory_order_acq_rel) & 3u;
  return buffers_[front_];
}

void copy_snapshot(const PatchSnapshot& from, PatchSnapshot& to) {
  to.origin = from.origin;
  to.edge = from.edge;
  to.band_vox = from.band_vox;
  to.clamp_vox = from.clamp_vox;
  to.version = from.version;
  to.phi.assign(from.phi.begin(), from.phi.end());
}

}  // namespace sculpt::core
