#pragma once
// A station command from its kind, choice and values (the controller's files).

#include <algorithm>
#include <cstdint>
#include <initializer_list>

#include "sculpt/sim/session/session.h"

namespace sculpt::station {

inline sim::Command make_command(sim::CommandKind kind, uint8_t choice = 0,
                                 std::initializer_list<float> values = {}) {
  sim::Command c{kind, choice, {}};
  std::copy(values.begin(), values.end(), c.values);
  return c;
}

}  // namespace sculpt::station
