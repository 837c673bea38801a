#pragma once
// Internal to StationLoop: an offset or closing's inputs and result, and its
// worker when it computes in the background (station_loop_morphology.cpp).

#include <atomic>
#include <cstdint>
#include <thread>

#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/distance/morphology.h"
#include "sculpt/core/grid/box.h"
#include "sculpt/station/app/station_loop.h"

namespace sculpt::station {

struct StationLoop::MorphologyJob {
  core::Box box;
  bool close = false;
  float by = 0.0f;
  int64_t inside_before = 0;
  core::DenseGrid<float> phi;        // the box's level function
  core::DenseGrid<uint8_t> density;  // what the box becomes
  int64_t inside_after = 0;
  std::atomic<bool> done{false};
  std::thread worker;  // in the background only

  void compute() {
    // The distance transforms' result does not depend on the thread count,
    // so a replay on another machine makes the same voxels.
    const core::DenseGrid<float> moved =
        close ? core::close_distance(phi, by)
              : core::offset_distance(core::surface_distance(phi), by);
    density = core::density_from_distance_field(moved);
    for (size_t i = 0; i < moved.size(); ++i)
      inside_after += moved[i] < 0.0f;
    phi = {};
    done.store(true, std::memory_order_release);
  }
  ~MorphologyJob() {
    if (worker.joinable()) worker.join();
  }
};

}  // namespace sculpt::station
