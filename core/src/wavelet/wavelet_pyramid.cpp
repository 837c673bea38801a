#include "sculpt/core/wavelet/wavelet_pyramid.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cstring>

#include "sculpt/core/wavelet/haar_1d.h"

namespace sculpt::core {
namespace {

// A strided view of a cube inside a larger array: element (x, y, z) is at
// data[z * slice + y * row + x].
template <class T>
struct CubeView {
  T* data;
  ptrdiff_t row;
  ptrdiff_t slice;
  T* row_ptr(int y, int z) const { return data + z * slice + y * row; }
};

template <class T>
CubeView<T> compact(T* data, int n) {
  return {data, n, ptrdiff_t{n} * n};
}

// The 2x2x2 blocks of one level a step works on: [i0, i1) x [j0, j1) x
// [k0, k1) in block (output) coordinates.
struct BlockRange {
  int i0, i1, j0, j1, k0, k1;
  static BlockRange all(int h) { return {0, h, 0, h, 0, h}; }
};

// Lifting on int16 values: every intermediate fits (see the header's ranges),
// and 16-bit lanes let the compiler put twice as many voxels in a vector.
inline int16_t low_of(int16_t a, int16_t b) {
  return static_cast<int16_t>(b + (static_cast<int16_t>(a - b) >> 1));
}
inline int16_t high_of(int16_t a, int16_t b) {
  return static_cast<int16_t>(a - b);
}
inline int16_t even_of(int16_t low, int16_t high) {
  return static_cast<int16_t>(low - (high >> 1) + high);
}
inline int16_t odd_of(int16_t low, int16_t high) {
  return static_cast<int16_t>(low - (high >> 1));
}

// Row kernels. Each works on whole rows of h values so that the compiler
// vectorises it (16 int16 lanes per AVX2 register); __restrict promises the
// rows never overlap, which they do not: temporaries live on the stack.
constexpr int kMaxHalf = WaveletPyramid::kMaxEdge / 2;

// The level kernels are compiled twice, for AVX2 and for the x86-64 baseline,
// and the loader picks the one the CPU runs: twice the lanes where available,
// one portable binary.
// Not under sanitizers: their runtimes start after ifunc resolvers run, and
// ThreadSanitizer crashes in one before main().
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_THREAD__) && !defined(__SANITIZE_ADDRESS__)
#define SCULPT_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SCULPT_VECTOR_CLONES
#endif

// x step: the pairs (s[2i], s[2i+1]) of one row become low[i], high[i].
template <class Src>
inline void split_row(const Src* __restrict s, int h, int16_t* __restrict low,
                      int16_t* __restrict high) {
  for (int i = 0; i < h; ++i) {
    const auto a = static_cast<int16_t>(s[2 * i]);
    const auto b = static_cast<int16_t>(s[2 * i + 1]);
    high[i] = high_of(a, b);
    low[i] = low_of(a, b);
  }
}

// y or z step: the pairs (a[i], b[i]) of two rows become low[i], high[i].
inline void split_rows(const int16_t* __restrict a, const int16_t* __restrict b, int h,
                       int16_t* __restrict low, int16_t* __restrict high) {
  for (int i = 0; i < h; ++i) {
    high[i] = high_of(a[i], b[i]);
    low[i] = low_of(a[i], b[i]);
  }
}

// Inverse of split_rows.
inline void merge_rows(const int16_t* __restrict low, const int16_t* __restrict high, int h,
                       int16_t* __restrict a, int16_t* __restrict b) {
  for (int i = 0; i < h; ++i) {
    a[i] = even_of(low[i], high[i]);
    b[i] = odd_of(low[i], high[i]);
  }
}

// Inverse of split_row: interleaves the reconstructed pairs into one row.
template <class Dst>
inline void merge_row(const int16_t* __restrict low, const int16_t* __restrict high, int h,
                      Dst* __restrict d) {
  for (int i = 0; i < h; ++i) {
    d[2 * i] = static_cast<Dst>(even_of(low[i], high[i]));
    d[2 * i + 1] = static_cast<Dst>(odd_of(low[i], high[i]));
  }
}

// One level of the forward transform of the n^3 cube `src`. The Haar supports
// of one level do not overlap, so the separable x, y, z steps reduce to an
// independent transform of each 2x2x2 block; here a row of h blocks at a time.
// The low-pass block goes to `low` (h^3, h = n/2); the seven detail bands go
// to `bands`, octant (bx,by,bz) at offset (bx,by,bz)*h. Row names: <x><y><z>
// band (L = 0, H = 1) or, before a step, the input row's (dy, dz).
template <class Src>
SCULPT_VECTOR_CLONES void forward_level(CubeView<const Src> src, int n, CubeView<int16_t> low,
                                        CubeView<int16_t> bands, BlockRange r) {
  const int h = n / 2;
  const int w = r.i1 - r.i0, i0 = r.i0;
  alignas(64) int16_t lx[4][kMaxHalf], hx[4][kMaxHalf];  // x step of rows (dy,dz) = 00,10,01,11
  alignas(64) int16_t ll[2][kMaxHalf], lh[2][kMaxHalf], hl[2][kMaxHalf], hh[2][kMaxHalf];  // [dz]
  for (int k = r.k0; k < r.k1; ++k) {
    for (int j = r.j0; j < r.j1; ++j) {
      for (int q = 0; q < 4; ++q)
        split_row(src.row_ptr(2 * j + (q & 1), 2 * k + (q >> 1)) + 2 * i0, w, lx[q], hx[q]);
      for (int dz = 0; dz < 2; ++dz) {
        split_rows(lx[2 * dz], lx[2 * dz + 1], w, ll[dz], lh[dz]);
        split_rows(hx[2 * dz], hx[2 * dz + 1], w, hl[dz], hh[dz]);
      }
      split_rows(ll[0], ll[1], w, low.row_ptr(j, k) + i0, bands.row_ptr(j, k + h) + i0);
      split_rows(hl[0], hl[1], w, bands.row_ptr(j, k) + h + i0, bands.row_ptr(j, k + h) + h + i0);
      split_rows(lh[0], lh[1], w, bands.row_ptr(j + h, k) + i0, bands.row_ptr(j + h, k + h) + i0);
      split_rows(hh[0], hh[1], w, bands.row_ptr(j + h, k) + h + i0,
                 bands.row_ptr(j + h, k + h) + h + i0);
    }
  }
}

// The exact inverse of forward_level: the z, y, x steps undone in that order.
template <class Dst>
SCULPT_VECTOR_CLONES void inverse_level(CubeView<const int16_t> low, CubeView<const int16_t> bands,
                                        int n, CubeView<Dst> dst, BlockRange r) {
  const int h = n / 2;
  const int w = r.i1 - r.i0, i0 = r.i0;
  alignas(64) int16_t ll[2][kMaxHalf], lh[2][kMaxHalf], hl[2][kMaxHalf], hh[2][kMaxHalf];
  alignas(64) int16_t lx[4][kMaxHalf], hx[4][kMaxHalf];
  for (int k = r.k0; k < r.k1; ++k) {
    for (int j = r.j0; j < r.j1; ++j) {
      merge_rows(low.row_ptr(j, k) + i0, bands.row_ptr(j, k + h) + i0, w, ll[0], ll[1]);
      merge_rows(bands.row_ptr(j, k) + h + i0, bands.row_ptr(j, k + h) + h + i0, w, hl[0], hl[1]);
      merge_rows(bands.row_ptr(j + h, k) + i0, bands.row_ptr(j + h, k + h) + i0, w, lh[0], lh[1]);
      merge_rows(bands.row_ptr(j + h, k) + h + i0, bands.row_ptr(j + h, k + h) + h + i0, w, hh[0],
                 hh[1]);
      for (int dz = 0; dz < 2; ++dz) {
        merge_rows(ll[dz], lh[dz], w, lx[2 * dz], lx[2 * dz + 1]);
        merge_rows(hl[dz], hh[dz], w, hx[2 * dz], hx[2 * dz + 1]);
      }
      for (int q = 0; q < 4; ++q)
        merge_row(lx[q], hx[q], w, dst.row_ptr(2 * j + (q & 1), 2 * k + (q >> 1)) + 2 * i0);
    }
  }
}

// Scratch for the intermediate low-pass cubes; per thread so that bricks can be
// encoded concurrently without allocation in the loop.
struct Scratch {
  std::vector<int16_t> a, b;
  void reserve(int edge) {
    const size_t half = static_cast<size_t>(edge / 2) * (edge / 2) * (edge / 2);
    if (a.size() < half) {
      a.resize(half);
      b.resize(half);
    }
  }
};
thread_local Scratch tls_scratch;

}  // namespace

int log2_exact(int power_of_two) {
  assert(is_power_of_two(power_of_two));
  int l = 0;
  while ((1 << l) < power_of_two)
    ++l;
  return l;
}

WaveletPyramid::WaveletPyramid(int edge, int levels)
    : edge_(edge), levels_(levels), coefficients_(static_cast<size_t>(edge) * edge * edge) {
  assert(is_power_of_two(edge) && edge <= kMaxEdge);
  assert(levels >= 0 && levels <= log2_exact(edge));
}

void WaveletPyramid::encode(std::span<const uint8_t> voxels) {
  assert(voxels.size() == coefficients_.size());
  const int e = edge_;
  const CubeView<int16_t> all{coefficients_.data(), e, ptrdiff_t{e} * e};
  if (levels_ == 0) {
    std::copy(voxels.begin(), voxels.end(), coefficients_.begin());
    return;
  }
  Scratch& s = tls_scratch;
  s.reserve(e);
  int16_t* cur = s.a.data();
  int16_t* next = s.b.data();
  forward_level<uint8_t>({voxels.data(), e, ptrdiff_t{e} * e}, e, compact(cur, e / 2), all,
                         BlockRange::all(e / 2));
  for (int l = 2, n = e / 2; l <= levels_; ++l, n /= 2) {
    forward_level<int16_t>(compact<const int16_t>(cur, n), n, compact(next, n / 2), all,
                           BlockRange::all(n / 2));
    std::swap(cur, next);
  }
  // The coarsest low-pass block goes to the corner of the layout.
  const int m = e >> levels_;
  for (int z = 0; z < m; ++z)
    for (int y = 0; y < m; ++y)
      std::memcpy(all.row_ptr(y, z), cur + (z * m + y) * m, m * sizeof(int16_t));
}

void WaveletPyramid::encode_region(std::span<const uint8_t> voxels, std::array<int, 3> lo,
                                   std::array<int, 3> hi) {
  assert(voxels.size() == coefficients_.size());
  const int e = edge_;
  const CubeView<int16_t> all{coefficients_.data(), e, ptrdiff_t{e} * e};
  for (int a = 0; a < 3; ++a)
    assert(0 <= lo[a] && lo[a] < hi[a] && hi[a] <= e);
  if (levels_ == 0) {
    for (int z = lo[2]; z < hi[2]; ++z)
      for (int y = lo[1]; y < hi[1]; ++y)
        for (int x = lo[0]; x < hi[0]; ++x)
          all.row_ptr(y, z)[x] = voxels[(static_cast<size_t>(z) * e + y) * e + x];
    return;
  }
  // The level-l blocks holding a changed voxel, widened to whole rows along
  // x: the row kernels are vectorised along x, and a part of a row (a dab
  // changes about half a brick's width) would run in their scalar remainder
  // loops. Recomputing unchanged blocks from valid values gives the same
  // coefficients.
  auto blocks = [&](int l) {
    return BlockRange{
        0, e >> l, lo[1] >> l, ((hi[1] - 1) >> l) + 1, lo[2] >> l, ((hi[2] - 1) >> l) + 1};
  };
  // Low-pass cubes of levels 1..L (lows[l], (e >> l)^3), filled only where
  // needed.
  thread_local std::vector<int16_t> lows[8];
  for (int l = 1; l <= levels_; ++l) {
    const size_t n = static_cast<size_t>(e >> l);
    if (lows[l].size() < n * n * n) lows[l].resize(n * n * n);
  }
  // Top down: the old level l-1 low-pass values of the changed level-l
  // blocks, by the inverse step from the stored pyramid. Outside the
  // changed level-(l-1) blocks they are still valid (Haar supports of one
  // level never overlap), and the forward step of level l needs them.
  const int m = e >> levels_;
  for (int z = 0; z < m; ++z)
    for (int y = 0; y < m; ++y)
      std::memcpy(&lows[levels_][(static_cast<size_t>(z) * m + y) * m], all.row_ptr(y, z),
                  static_cast<size_t>(m) * sizeof(int16_t));
  for (int l = levels_; l >= 2; --l) {
    const int n = e >> (l - 1);
    inverse_level<int16_t>(compact<const int16_t>(lows[l].data(), n / 2),
                           {all.data, all.row, all.slice}, n, compact(lows[l - 1].data(), n),
                           blocks(l));
  }
  // Bottom up: the forward steps over the changed blocks only, each level
  // reading the new low-pass values below it where they changed and the old
  // ones around them.
  forward_level<uint8_t>({voxels.data(), e, ptrdiff_t{e} * e}, e, compact(lows[1].data(), e / 2),
                         all, blocks(1));
  for (int l = 2; l <= levels_; ++l) {
    const int n = e >> (l - 1);
    forward_level<int16_t>(compact<const int16_t>(lows[l - 1].data(), n), n,
                           compact(lows[l].data(), n / 2), all, blocks(l));
  }
  for (int z = 0; z < m; ++z)
    for (int y = 0; y < m; ++y)
      std::memcpy(all.row_ptr(y, z), &lows[levels_][(static_cast<size_t>(z) * m + y) * m],
                  static_cast<size_t>(m) * sizeof(int16_t));
}

void WaveletPyramid::extract_level(int level, std::span<uint8_t> out) const {
  assert(level >= 0 && level <= levels_);
  const int e = edge_;
  const int m = e >> level;
  assert(out.size() == static_cast<size_t>(m) * m * m);
  const CubeView<const int16_t> all{coefficients_.data(), e, ptrdiff_t{e} * e};
  if (level == levels_) {
    for (int z = 0; z < m; ++z)
      for (int y = 0; y < m; ++y)
        for (int x = 0; x < m; ++x)
          out[(z * m + y) * m + x] = static_cast<uint8_t>(all.row_ptr(y, z)[x]);
    return;
  }
  Scratch& s = tls_scratch;
  s.reserve(e);
  // Undo levels L .. level+1; the coarsest low-pass block is read in place.
  CubeView<const int16_t> low = all;
  int16_t* cur = s.a.data();
  int16_t* next = s.b.data();
  for (int l = levels_, n = e >> (levels_ - 1); l > level + 1; --l, n *= 2) {
    inverse_level<int16_t>(low, all, n, compact(cur, n), BlockRange::all(n / 2));
    low = compact<const int16_t>(cur, n);
    std::swap(cur, next);
  }
  inverse_level<uint8_t>(low, all, m, compact(out.data(), m), BlockRange::all(m / 2));
}

void WaveletPyramid::decode(std::span<uint8_t> voxels) const {
  extract_level(0, voxels);
}

uint8_t WaveletPyramid::voxel(int x, int y, int z) const {
  assert(x >= 0 && y >= 0 && z >= 0 && x < edge_ && y < edge_ && z < edge_);
  const int e = edge_;
  auto c = [&](int cx, int cy, int cz) {
    return coefficients_[(static_cast<size_t>(cz) * e + cy) * e + cx];
  };
  // Walk from the coarsest block down: at each level only the child on the
  // path to (x, y, z) is reconstructed, from its parent and 7 details.
  int16_t value = c(x >> levels_, y >> levels_, z >> levels_);
  for (int l = levels_; l >= 1; --l) {
    const int h = e >> l;
    const int px = x >> l, py = y >> l, pz = z >> l;
    const int dx = (x >> (l - 1)) & 1, dy = (y >> (l - 1)) & 1, dz = (z >> (l - 1)) & 1;
    auto undo_z = [&](int16_t lo, int bx, int by) {
      const int16_t hi = c(px + bx * h, py + by * h, pz + h);
      return dz == 0 ? even_of(lo, hi) : odd_of(lo, hi);
    };
    const int16_t ll = undo_z(value, 0, 0);
    const int16_t hl = undo_z(c(px + h, py, pz), 1, 0);
    const int16_t lh = undo_z(c(px, py + h, pz), 0, 1);
    const int16_t hh = undo_z(c(px + h, py + h, pz), 1, 1);
    const int16_t lx = dy == 0 ? even_of(ll, lh) : odd_of(ll, lh);
    const int16_t hx = dy == 0 ? even_of(hl, hh) : odd_of(hl, hh);
    value = dx == 0 ? even_of(lx, hx) : odd_of(lx, hx);
  }
  return static_cast<uint8_t>(value);
}

int64_t WaveletPyramid::detail_count() const {
  const int64_t m = edge_ >> levels_;
  return static_cast<int64_t>(coefficients_.size()) - m * m * m;
}

int64_t WaveletPyramid::zero_detail_count() const {
  const int e = edge_;
  const int m = e >> levels_;
  int64_t zeros = std::count(coefficients_.begin(), coefficients_.end(), int16_t{0});
  for (int z = 0; z < m; ++z)
    for (int y = 0; y < m; ++y)
      for (int x = 0; x < m; ++x)
        zeros -= coefficients_[(static_cast<size_t>(z) * e + y) * e + x] == 0;
  return zeros;
}

}  // namespace sculpt::core
