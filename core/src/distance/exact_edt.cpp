// Felzenszwalb-Huttenlocher separable EDT. Cache: the z pass is two plain
// scans over contiguous rows; the y and x envelope passes run per z-slice
// (the slice stays in cache); the y pass gathers kBlock neighbouring columns
// at a time so every cache line read is used whole, runs the 1D envelope per
// column, and scatters back; the x pass runs on contiguous rows. Squared
// distances throughout; square roots once, at the end of the x pass.

#include "sculpt/core/distance/exact_edt.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kBlock = 16;

struct Scratch {
  std::vector<int> v;
  std::vector<float> z;
  std::vector<float> g_env;
  std::vector<float> f;    // kBlock columns of n values
  std::vector<float> d;    // kBlock columns of n values
  std::vector<int32_t> g;  // kBlock columns of features in
  std::vector<int32_t> h;  // kBlock columns of features out
  void size(int n) {
    if (static_cast<int>(v.size()) < n + 1) {
      v.resize(size_t(n) + 1);
      z.resize(size_t(n) + 2);
      g_env.resize(size_t(n) + 1);
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
// d[q] = its value at q, arg[q] = the winning i (-1 if none). v, z, g: the
// envelope's parabolas, their left ends and their f[v] + v^2 (kept so the
// intersection test reads one value, not f at a just-loaded index).
template <bool kFeatures>
void envelope_1d(const float* f, int n, float* d, int* arg, int* v, float* z, float* g) {
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == kInf) continue;
    const float fq = f[q] + float(q) * float(q);
    if (k < 0) {
      k = 0;
      v[0] = q;
      g[0] = fq;
      z[0] = -kInf;
      z[1] = kInf;
      continue;
    }
    float s;
    for (;;) {
      s = (fq - g[k]) / (2.0f * float(q - v[k]));
      if (s <= z[k] && k > 0) {
        --k;
        continue;
      }
      break;
    }
    if (s <= z[k]) {
      // k == 0 and the new parabola wins everywhere left of it too.
      v[0] = q;
      g[0] = fq;
      z[0] = -kInf;
      z[1] = kInf;
      continue;
    }
    ++k;
    v[k] = q;
    g[k] = fq;
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
    envelope_1d<kFeatures>(f + lo, hi - lo + 1, d + lo, arg, s.v.data(), s.z.data(),
                           s.g_env.data());
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

// The z pass over one row of x: run = distance along z to the last seed
// passed, kNoSeed before the first; forward sets d = run^2, backward keeps
// the smaller. Written with a 0/1 multiplier and min rather than a branch on
// the mask, so the loops vectorise (the branchy form does not).
constexpr float kNoSeed = 3.0e38f;  // finite, and its square overflows to +inf

void scan_forward(const uint8_t* __restrict m, float* __restrict run, float* __restrict d, int n,
                  uint8_t seed) {
  for (int x = 0; x < n; ++x) {
    const float keep = float(m[x] != seed);  // 0 at a seed
    const float r = std::min(run[x] + 1.0f, keep * kNoSeed);
    run[x] = r;
    d[x] = r * r;
  }
}

void scan_backward(const uint8_t* __restrict m, float* __restrict run, float* __restrict d, int n,
                   uint8_t seed) {
  for (int x = 0; x < n; ++x) {
    const float keep = float(m[x] != seed);
    const float r = std::min(run[x] + 1.0f, keep * kNoSeed);
    run[x] = r;
    d[x] = std::min(d[x], r * r);
  }
}

// First and last x of a row whose mask is not `seed` ({-1, -1}: none),
// eight bytes at a time (most rows of a volume are all seeds or all not).
std::pair<int, int> non_seed_range(const uint8_t* m, int n, uint8_t seed) {
  const uint64_t all_seed = 0x0101010101010101ull * seed;
  auto word_at = [&](int x) {
    uint64_t w;
    std::memcpy(&w, m + x, sizeof w);
    return w;
  };
  int lo = 0;
  while (lo + 8 <= n && word_at(lo) == all_seed)
    lo += 8;
  while (lo < n && m[lo] == seed)
    ++lo;
  if (lo == n) return {-1, -1};
  int hi = n - 1;
  while (hi - 7 > lo && word_at(hi - 7) == all_seed)
    hi -= 8;
  while (m[hi] == seed)
    --hi;
  return {lo, hi};
}

// Row [lo, hi] along x, contiguous, in place through the thread's scratch
// copy (the envelope reads f while it writes d). Outside [lo, hi] the row
// holds seeds (zeros), which hide everything beyond them.
template <bool kFeatures>
void envelope_row(float* dist, int32_t* feat, int lo, int hi, bool take_sqrt) {
  const int len = hi - lo + 1;
  Scratch& s = scratch(len);
  std::copy(dist + lo, dist + hi + 1, s.f.data());
  thread_local std::vector<int> args;
  int* arg = nullptr;
  if constexpr (kFeatures) {
    if (static_cast<int>(args.size()) < len) args.resize(size_t(len));
    arg = args.data();
    std::copy(feat + lo, feat + hi + 1, s.g.data());
  }
  envelope_1d<kFeatures>(s.f.data(), len, dist + lo, arg, s.v.data(), s.z.data(), s.g_env.data());
  if constexpr (kFeatures) {
    for (int i = 0; i < len; ++i)
      feat[lo + i] = arg[i] < 0 ? -1 : s.g[size_t(arg[i])];
  }
  if (take_sqrt) {
    for (int i = lo; i <= hi; ++i)
      dist[i] = std::sqrt(dist[i]);
  }
}

// Pass order z, y, x. The z pass is only the nearest seed on each z-column,
// two scans that run over contiguous rows for all x at once (branch-free, so
// they vectorise); the y and x envelope passes then run per z-slice while it
// is in cache, x on contiguous rows. The z pass also records, per row, the
// x-range of the non-seed voxels: seeds stay 0 through every pass, so the
// envelopes only visit those ranges (the bounding region of the object, not
// the whole grid) and never scan for them.
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
  // Per row (y, z), index y + dims.y * z: first and last non-seed x (-1: none).
  std::vector<int> row_lo(size_t(dims.y) * dims.z), row_hi(size_t(dims.y) * dims.z);
  // z: per y, the nearest seed up and down each z-column, all x at once.
  parallel_for(
      dims.y,
      [&](int64_t y) {
        thread_local std::vector<float> run_buf;
        thread_local std::vector<int> seed_buf;
        run_buf.assign(size_t(dims.x), kNoSeed);
        float* run = run_buf.data();
        int* sz = nullptr;  // features: z of the last seed passed, -1: none
        if constexpr (kFeatures) {
          seed_buf.assign(size_t(dims.x), -1);
          sz = seed_buf.data();
        }
        const size_t base = size_t(y) * dims.x;
        for (int z = 0; z < dims.z; ++z) {
          const size_t r = base + size_t(z) * slice;
          const uint8_t* m = mask.data() + r;
          float* d = D + r;
          const auto [lo, hi] = non_seed_range(m, dims.x, seed_value);
          row_lo[size_t(y) + size_t(dims.y) * z] = lo;
          row_hi[size_t(y) + size_t(dims.y) * z] = hi;
          scan_forward(m, run, d, dims.x, seed_value);
          if constexpr (kFeatures) {
            for (int x = 0; x < dims.x; ++x) {
              if (m[x] == seed_value) sz[x] = z;
              F[r + x] = sz[x] < 0 ? -1 : int32_t(base + size_t(sz[x]) * slice + size_t(x));
            }
          }
        }
        run_buf.assign(size_t(dims.x), kNoSeed);
        if constexpr (kFeatures) seed_buf.assign(size_t(dims.x), -1);
        for (int z = dims.z - 1; z >= 0; --z) {
          const size_t r = base + size_t(z) * slice;
          const uint8_t* m = mask.data() + r;
          float* d = D + r;
          if constexpr (kFeatures) {
            for (int x = 0; x < dims.x; ++x) {
              if (m[x] == seed_value) sz[x] = z;
              run[x] = m[x] == seed_value ? 0.0f : run[x] + 1.0f;
              // Strictly nearer only: ties keep the seed below.
              if (run[x] * run[x] < d[x]) {
                d[x] = run[x] * run[x];
                F[r + x] = int32_t(base + size_t(sz[x]) * slice + size_t(x));
              }
            }
          } else {
            scan_backward(m, run, d, dims.x, seed_value);
          }
        }
      },
      threads);
  // y then x, per z-slice, inside the box of the slice's non-seed voxels.
  parallel_for(
      dims.z,
      [&](int64_t z) {
        const int* lo = row_lo.data() + size_t(dims.y) * z;
        const int* hi = row_hi.data() + size_t(dims.y) * z;
        int y0 = dims.y, y1 = -1, x0 = dims.x, x1 = -1;
        for (int y = 0; y < dims.y; ++y) {
          if (hi[y] < 0) continue;
          y0 = std::min(y0, y);
          y1 = y;
          x0 = std::min(x0, lo[y]);
          x1 = std::max(x1, hi[y]);
        }
        if (y1 < 0) return;  // all seeds
        // One seed row beyond each end of the box hides the rest.
        y0 = std::max(0, y0 - 1);
        y1 = std::min(dims.y - 1, y1 + 1);
        for (int x = x0; x <= x1; x += kBlock) {
          const int w = std::min(kBlock, x1 + 1 - x);
          envelope_block<kFeatures>(D, F, size_t(z) * slice + size_t(y0) * dims.x + x, w,
                                    y1 - y0 + 1, size_t(dims.x), false);
        }
        for (int y = y0; y <= y1; ++y) {
          if (hi[y] < 0) continue;
          const size_t r = size_t(z) * slice + size_t(y) * dims.x;
          envelope_row<kFeatures>(D + r, kFeatures ? F + r : nullptr, std::max(0, lo[y] - 1),
                                  std::min(dims.x - 1, hi[y] + 1), take_sqrt);
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
