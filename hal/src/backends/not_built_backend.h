#pragma once
// The stand-in for a transport compiled out (GLFW's null platform, but never
// chosen): it exists so that `sculpt devices` can say which option and
// package would bring it, and it enumerates and opens nothing.

#include <memory>
#include <string>

#include "sculpt/hal/types/device.h"

namespace sculpt::hal::detail {

/// name: "hidapi"; option: "SCULPT_WITH_HIDAPI"; package: "libhidapi-dev".
std::unique_ptr<Backend> make_not_built_backend(std::string name, const std::string& option,
                                                const std::string& package);

}  // namespace sculpt::hal::detail
