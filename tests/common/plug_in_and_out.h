#pragma once
// A device plugged in and pulled out again `times` times through a fake
// transport, each reader retired before the next plug. Device ids are never
// reused, so the device plugged in after this gets an id of `times` or more.
// Call it inside ASSERT_NO_FATAL_FAILURE.

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "sculpt/hal/backends/feed_backend.h"
#include "sculpt/hal/registry/device_registry.h"

namespace sculpt::test {

inline void plug_in_and_out(hal::FeedBackend& transport, hal::DeviceRegistry& registry,
                            const hal::DeviceInfo& device, int times) {
  for (int plug = 0; plug < times; ++plug) {
    auto feed = transport.attach(device);
    ASSERT_EQ(registry.scan().opened.size(), 1u);
    transport.detach(device.path, plug);
    for (int i = 0; i < 5000 && registry.open_count() > 0; ++i) {
      hal::InputFrame drained;
      registry.poll(drained, 0);  // retires the reader once it has finished
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ASSERT_EQ(registry.open_count(), 0u) << "the reader of plug " << plug << " did not finish";
  }
}

}  // namespace sculpt::test
