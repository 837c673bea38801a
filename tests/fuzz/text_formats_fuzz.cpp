// libFuzzer target: the small text formats users write by hand: NURBS
// surface, curve and zone JSON, contour stacks, and the normaliser settings
// (input.conf), and the simulated arm's hand scripts. The first byte picks
// the reader. Seeds: corpus/text_formats.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "sculpt/core/distance/contours.h"
#include "sculpt/core/nurbs/nurbs_json.h"
#include "sculpt/hal/force/hand_script.h"
#include "sculpt/hal/normalizer/normalizer_config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  switch (data[0] % 6) {
    case 0:
      (void)sculpt::core::nurbs::parse_surface_json(text);
      break;
    case 1:
      (void)sculpt::core::nurbs::parse_curve_json(text);
      break;
    case 2:
      (void)sculpt::core::nurbs::parse_zone_json(text);
      break;
    case 3:
      (void)sculpt::core::parse_contours(text);
      break;
    case 5: {
      // What parses has its path in time order, every target finite.
      auto hand = sculpt::hal::parse_hand_script(text, "hand");
      if (hand.ok()) {
        for (size_t i = 1; i < hand->path.size(); ++i)
          if (hand->path[i].t_s < hand->path[i - 1].t_s) __builtin_trap();
        const glm::vec3 at = hand->target_at(hand->end_s() * 0.5);
        if (!std::isfinite(at.x + at.y + at.z)) __builtin_trap();
      }
      break;
    }
    default: {
      // What parses must print and parse back equal.
      auto config = sculpt::hal::parse_normalizer_config(text, "input.conf");
      if (config.ok()) {
        auto again = sculpt::hal::parse_normalizer_config(sculpt::hal::to_text(*config), "again");
        if (!again.ok()) __builtin_trap();
      }
    }
  }
  return 0;
}
