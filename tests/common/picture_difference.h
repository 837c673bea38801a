#pragma once
// How two pictures of the same size differ, as a viewer would notice: the
// mean over pixels of the largest channel difference, the share of pixels
// where it is over 24 (a step the eye sees at once), and over 8 (faint
// alone, but seen where such pixels line up: a streak on smooth clay).

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace sculpt::test {

struct PictureDifference {
  double mean = 0;
  double visible_share = 0;
  double faint_share = 0;
};

/// `a` and `b`: RGB bytes, the same size.
inline PictureDifference picture_difference(const std::vector<uint8_t>& a,
                                            const std::vector<uint8_t>& b) {
  double sum = 0;
  int64_t visible = 0, faint = 0;
  for (size_t i = 0; i + 2 < a.size() && i + 2 < b.size(); i += 3) {
    int worst = 0;
    for (size_t k = 0; k < 3; ++k)
      worst = std::max(worst, std::abs(int{a[i + k]} - int{b[i + k]}));
    sum += worst;
    visible += worst > 24;
    faint += worst > 8;
  }
  const double pixels = static_cast<double>(std::max<size_t>(1, a.size() / 3));
  return {sum / pixels, static_cast<double>(visible) / pixels, static_cast<double>(faint) / pixels};
}

}  // namespace sculpt::test
