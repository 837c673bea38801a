#pragma once
// The evdev 6-axis backend over any evdev edge: make_evdev_backend() gives
// it the real one; the tests give it a fake tree and event stream.

#include <functional>
#include <memory>

#include "backends/evdev_input/evdev_input_device.h"

namespace sculpt::hal::evdev_input {

/// Makes a fresh evdev edge: one for listing, one per opened device.
using EvdevIoFactory = std::function<std::unique_ptr<evdev_ff::EvdevIo>()>;

std::unique_ptr<Backend> make_evdev_input_backend(EvdevIoFactory factory,
                                                  EvdevInputOptions options = {});

}  // namespace sculpt::hal::evdev_input
