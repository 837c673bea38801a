// Felzenszwalb-Huttenlocher separable EDT. Cache: the x pass and the y pass
// run per z-slice (the slice stays in cache); the y and z passes gather
// kBlock neighbouring columns at a time so every cache line read is used
// whole, run the 1D envelope per column, and scatter back.

#include "sculpt/core/distance/exact_edt.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kBlock = 16;

struct Scratch {
  std::vector<int> v;
  std::vector<float> z;
  std::vector<float> f;    // kBlock columns of n values
  std::vector<float> d;    // kBlock columns of n values
  std::vector<int32_t> g;  // kBlock columns of features in
  std::vector<int32_t> h;  // kBlock columns of features out
  void size(int n) {
    if (static_cast<int>(v.size()) < n + 1) {
      v.resize(n + 1);
      z.resize(n + 2);
      f.resize(size_t(n) * kBlock);
      d.resize(size_t(n) * kBlock);
      g.resize(size_t(n) * kBlock);
      h.resize(size_t(n) * kBlock);
    }
  }
};

Scratch& scratch(int n) {
  thread_local Scratch s;
  s.size(n);
  return s;
}

// Lower envelope of the parabolas (q - i)^2 + f[i] over finite f[i];
// d[q] = its value at q, arg[q] = the winning i (-1 if none).
template <bool kFeatures>
void envelope_1d(const float* f, int n, float* d, int* arg, int* v, float* z) {
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == kInf) continue;
    const float fq = f[q] + float(q) * float(q);
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -kInf;
      z[1] = kInf;
      continue;
    }
    float s;
    for (;;) {
      const int p = v[k];
      s = (fq - (f[p] + float(p) * float(p))) / (2.0f * float(q - p));
      if (s <= z[k] && k > 0) {
        --k;
        continue;
      }
      break;
    }
    if (s <= z[k]) {
      // k == 0 and the new parabola wins everywhere left of it too.
      v[0] = q;
      z[0] = -kInf;
      z[1] = kInf;
      continue;
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInf;
  }
  if (k < 0) {
    for (int q = 0; q < n; ++q) {
      d[q] = kInf;
      if constexpr (kFeatures) arg[q] = -1;
    }
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[j + 1] < float(q))
      ++j;
    const float t = float(q - v[j]);
    d[q] = t * t + f[v[j]];
    if constexpr (kFeatures) arg[q] = v[j];
  }
}

// One axis of a block of up to kBlock columns: column j starts at base + j
// (neighbouring x), consecutive elements `stride` apart.
template <bool kFeatures>
void envelope_block(float* dist, int32_t* feat, size_t base, int width, int n, size_t stride,
                    bool take_sqrt) {
  Scratch& s = scratch(n);
  // Zeros (seeds) at both ends of a column hide everything beyond them: a
  // voxel between two zeros is nearer to one of them than to any zero
  // farther out. So only the span from the zero before the first non-zero
  // value to the zero after the last one runs the envelope; the ends stay
  // zero. Columns all zero (most columns outside an object) skip it.
  int first[kBlock], last[kBlock];
  for (int j = 0; j < width; ++j)
    first[j] = n, last[j] = -1;
  for (int i = 0; i < n; ++i) {
    const size_t row = base + size_t(i) * stride;
    for (int j = 0; j < width; ++j) {
      const float v = dist[row + j];
      s.f[size_t(j) * n + i] = v;
      if (v != 0.0f) {
        first[j] = std::min(first[j], i);
        last[j] = i;
      }
      if constexpr (kFeatures) s.g[size_t(j) * n + i] = feat[row + j];
    }
  }
  bool any = false;
  for (int j = 0; j < width; ++j)
    any = any || last[j] >= 0;
  if (!any) return;  // zeros stay zeros (and their square roots), features stay
  int* arg = nullptr;
  thread_local std::vector<int> args;
  if constexpr (kFeatures) {
    if (static_cast<int>(args.size()) < n) args.resize(n);
    arg = args.data();
  }
  for (int j = 0; j < width; ++j) {
    float* d = &s.d[size_t(j) * n];
    const float* f = &s.f[size_t(j) * n];
    std::copy(f, f + n, d);  // zeros (and, for all-zero columns, everything)
    if constexpr (kFeatures)
      std::copy(&s.g[size_t(j) * n], &s.g[size_t(j) * n] + n, &s.h[size_t(j) * n]);
    if (last[j] < 0) continue;
    const int lo = std::max(0, first[j] - 1), hi = std::min(n - 1, last[j] + 1);
    envelope_1d<kFeatures>(f + lo, hi - lo + 1, d + lo, arg, s.v.data(), s.z.data());
    if constexpr (kFeatures) {
      const int32_t* g = &s.g[size_t(j) * n];
      int32_t* h = &s.h[size_t(j) * n];
      for (int i = 0; i <= hi - lo; ++i)
        h[lo + i] = arg[i] < 0 ? -1 : g[lo + arg[i]];
    }
  }
  for (int i = 0; i < n; ++i) {
    const size_t row = base + size_t(i) * stride;
    for (int j = 0; j < width; ++j) {
      const float v = s.d[size_t(j) * n + i];
      dist[row + j] = take_sqrt ? std::sqrt(v) : v;
      if constexpr (kFeatures) feat[row + j] = s.h[size_t(j) * n + i];
    }
  }
}

template <bool kFeatures>
void transform(const DenseGrid<uint8_t>& mask, uint8_t seed_value, int threads, bool take_sqrt,
               DenseGrid<float>& dist, DenseGrid<int32_t>* nearest) {
  const glm::ivec3 dims = mask.dims();
  dist = DenseGrid<float>(dims);
  if constexpr (kFeatures) *nearest = DenseGrid<int32_t>(dims);
  if (dims.x == 0 || dims.y == 0 || dims.z == 0) return;
  float* D = dist.data();
  int32_t* F = kFeatures ? nearest->data() : nullptr;
  const size_t slice = size_t(dims.x) * dims.y;
  // x then y, per z-slice.
  parallel_for(
      dims.z,
      [&](int64_t z) {
        const uint8_t* m = mask.data() + size_t(z) * slice;
        float* d = D + size_t(z) * slice;
        int32_t* f = kFeatures ? F + size_t(z) * slice : nullptr;
        for (int y = 0; y < dims.y; ++y) {
          const size_t r = size_t(y) * dims.x;
          // Forward then backward scan: nearest seed on the row.
          int last = -1;
          for (int x = 0; x < dims.x; ++x) {
            if (m[r + x] == seed_value) last = x;
            d[r + x] = last < 0 ? kInf : float(x - last) * float(x - last);
            if constexpr (kFeatures)
              f[r + x] = last < 0 ? -1 : int32_t(size_t(z) * slice + r + last);
          }
          last = -1;
          for (int x = dims.x - 1; x >= 0; --x) {
            if (m[r + x] == seed_value) last = x;
            if (last < 0) continue;
            const float t = float(last - x) * float(last - x);
            if (t < d[r + x]) {
              d[r + x] = t;
              if constexpr (kFeatures) f[r + x] = int32_t(size_t(z) * slice + r + last);
            }
          }
        }
        for (int x0 = 0; x0 < dims.x; x0 += kBlock) {
          const int w = std::min(kBlock, dims.x - x0);
          envelope_block<kFeatures>(D, F, size_t(z) * slice + x0, w, dims.y, size_t(dims.x), false);
        }
      },
      threads);
  // z, per y-row of columns.
  parallel_for(
      dims.y,
      [&](int64_t y) {
        for (int x0 = 0; x0 < dims.x; x0 += kBlock) {
          const int w = std::min(kBlock, dims.x - x0);
          envelope_block<kFeatures>(D, F, size_t(y) * dims.x + x0, w, dims.z, slice, take_sqrt);
        }
      },
      threads);
}

}  // namespace

DenseGrid<float> squared_edt(const DenseGrid<uint8_t>& mask, uint8_t seed_value, int threads) {
  DenseGrid<float> d;
  transform<false>(mask, seed_value, threads, false, d, nullptr);
  return d;
}

DenseGrid<float> exact_edt(const DenseGrid<uint8_t>& mask, uint8_t seed_value, int threads) {
  DenseGrid<float> d;
  transform<false>(mask, seed_value, threads, true, d, nullptr);
  return d;
}

FeatureTransform feature_transform(const DenseGrid<uint8_t>& mask, uint8_t seed_value,
                                   int threads) {
  FeatureTransform ft;
  transform<true>(mask, seed_value, threads, false, ft.distance_squared, &ft.nearest);
  return ft;
}

}  // namespace sculpt::core
