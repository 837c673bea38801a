#include "sculpt/core/wavelet/wavelet_pyramid.h"

#include <algorithm>
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

// Lifting on int16 values: every intermediate fits (see the header's ranges),
// and 16-bit lanes let the compiler put twice as many voxels in a vector.
inline int16_t low_of(int16_t a, int16_t b) {
  return static_cast<int16_t>(b + (static_cast<int16_t>(a - b) >> 1));
}
inline int16_t high_of(int16_t a, int16_t b) { return static_cast<int16_t>(a - b); }
inline int16_t even_of(int16_t low, int16_t high) {
  return static_cast<int16_t>(low - (high >> 1) + high);
}
inline int16_t odd_of(int16_t low, int16_t high) { return static_cast<int16_t>(low - (high >> 1)); }

// One level of the forward transform of the n^3 cube `src`. The Haar supports
// of one level do not overlap, so the separable x, y, z steps reduce to an
// independent transform of each 2x2x2 block: one pass, eight outputs per block.
// The low-pass block goes to `low` (h^3, h = n/2); the seven detail bands go to
// `bands`, octant (bx,by,bz) at offset (bx,by,bz)*h.
template <class Src>
void forward_level(CubeView<const Src> src, int n, CubeView<int16_t> low, CubeView<int16_t> bands) {
  const int h = n / 2;
  for (int k = 0; k < h; ++k) {
    for (int j = 0; j < h; ++j) {
      const Src* s00 = src.row_ptr(2 * j, 2 * k);  // s<dy><dz>
      const Src* s10 = src.row_ptr(2 * j + 1, 2 * k);
      const Src* s01 = src.row_ptr(2 * j, 2 * k + 1);
      const Src* s11 = src.row_ptr(2 * j + 1, 2 * k + 1);
      int16_t* o000 = low.row_ptr(j, k);  // o<bx><by><bz>, bx handled by +h
      int16_t* o100 = bands.row_ptr(j, k) + h;
      int16_t* o010 = bands.row_ptr(j + h, k);
      int16_t* o110 = bands.row_ptr(j + h, k) + h;
      int16_t* o001 = bands.row_ptr(j, k + h);
      int16_t* o101 = bands.row_ptr(j, k + h) + h;
      int16_t* o011 = bands.row_ptr(j + h, k + h);
      int16_t* o111 = bands.row_ptr(j + h, k + h) + h;
      for (int i = 0; i < h; ++i) {
        // x step, for each of the four (y, z) rows of the block
        const auto a00 = static_cast<int16_t>(s00[2 * i]), b00 = static_cast<int16_t>(s00[2 * i + 1]);
        const auto a10 = static_cast<int16_t>(s10[2 * i]), b10 = static_cast<int16_t>(s10[2 * i + 1]);
        const auto a01 = static_cast<int16_t>(s01[2 * i]), b01 = static_cast<int16_t>(s01[2 * i + 1]);
        const auto a11 = static_cast<int16_t>(s11[2 * i]), b11 = static_cast<int16_t>(s11[2 * i + 1]);
        const int16_t lx00 = low_of(a00, b00), hx00 = high_of(a00, b00);
        const int16_t lx10 = low_of(a10, b10), hx10 = high_of(a10, b10);
        const int16_t lx01 = low_of(a01, b01), hx01 = high_of(a01, b01);
        const int16_t lx11 = low_of(a11, b11), hx11 = high_of(a11, b11);
        // y step on the L and H halves, for z = 0 and z = 1
        const int16_t ll0 = low_of(lx00, lx10), lh0 = high_of(lx00, lx10);
        const int16_t hl0 = low_of(hx00, hx10), hh0 = high_of(hx00, hx10);
        const int16_t ll1 = low_of(lx01, lx11), lh1 = high_of(lx01, lx11);
        const int16_t hl1 = low_of(hx01, hx11), hh1 = high_of(hx01, hx11);
        // z step; names: <x band><y band>, L = 0, H = 1
        o000[i] = low_of(ll0, ll1);
        o001[i] = high_of(ll0, ll1);
        o100[i] = low_of(hl0, hl1);
        o101[i] = high_of(hl0, hl1);
        o010[i] = low_of(lh0, lh1);
        o011[i] = high_of(lh0, lh1);
        o110[i] = low_of(hh0, hh1);
        o111[i] = high_of(hh0, hh1);
      }
    }
  }
}

// The exact inverse of forward_level: the z, y, x steps undone in that order.
template <class Dst>
void inverse_level(CubeView<const int16_t> low, CubeView<const int16_t> bands, int n,
                   CubeView<Dst> dst) {
  const int h = n / 2;
  for (int k = 0; k < h; ++k) {
    for (int j = 0; j < h; ++j) {
      const int16_t* c000 = low.row_ptr(j, k);
      const int16_t* c100 = bands.row_ptr(j, k) + h;
      const int16_t* c010 = bands.row_ptr(j + h, k);
      const int16_t* c110 = bands.row_ptr(j + h, k) + h;
      const int16_t* c001 = bands.row_ptr(j, k + h);
      const int16_t* c101 = bands.row_ptr(j, k + h) + h;
      const int16_t* c011 = bands.row_ptr(j + h, k + h);
      const int16_t* c111 = bands.row_ptr(j + h, k + h) + h;
      Dst* d00 = dst.row_ptr(2 * j, 2 * k);
      Dst* d10 = dst.row_ptr(2 * j + 1, 2 * k);
      Dst* d01 = dst.row_ptr(2 * j, 2 * k + 1);
      Dst* d11 = dst.row_ptr(2 * j + 1, 2 * k + 1);
      for (int i = 0; i < h; ++i) {
        // z
        const int16_t ll0 = even_of(c000[i], c001[i]), ll1 = odd_of(c000[i], c001[i]);
        const int16_t hl0 = even_of(c100[i], c101[i]), hl1 = odd_of(c100[i], c101[i]);
        const int16_t lh0 = even_of(c010[i], c011[i]), lh1 = odd_of(c010[i], c011[i]);
        const int16_t hh0 = even_of(c110[i], c111[i]), hh1 = odd_of(c110[i], c111[i]);
        // y
        const int16_t lx00 = even_of(ll0, lh0), lx10 = odd_of(ll0, lh0);
        const int16_t hx00 = even_of(hl0, hh0), hx10 = odd_of(hl0, hh0);
        const int16_t lx01 = even_of(ll1, lh1), lx11 = odd_of(ll1, lh1);
        const int16_t hx01 = even_of(hl1, hh1), hx11 = odd_of(hl1, hh1);
        // x
        d00[2 * i] = static_cast<Dst>(even_of(lx00, hx00));
        d00[2 * i + 1] = static_cast<Dst>(odd_of(lx00, hx00));
        d10[2 * i] = static_cast<Dst>(even_of(lx10, hx10));
        d10[2 * i + 1] = static_cast<Dst>(odd_of(lx10, hx10));
        d01[2 * i] = static_cast<Dst>(even_of(lx01, hx01));
        d01[2 * i + 1] = static_cast<Dst>(odd_of(lx01, hx01));
        d11[2 * i] = static_cast<Dst>(even_of(lx11, hx11));
        d11[2 * i + 1] = static_cast<Dst>(odd_of(lx11, hx11));
      }
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
  while ((1 << l) < power_of_two) ++l;
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
  forward_level<uint8_t>({voxels.data(), e, ptrdiff_t{e} * e}, e, compact(cur, e / 2), all);
  for (int l = 2, n = e / 2; l <= levels_; ++l, n /= 2) {
    forward_level<int16_t>(compact<const int16_t>(cur, n), n, compact(next, n / 2), all);
    std::swap(cur, next);
  }
  // The coarsest low-pass block goes to the corner of the layout.
  const int m = e >> levels_;
  for (int z = 0; z < m; ++z)
    for (int y = 0; y < m; ++y) std::memcpy(all.row_ptr(y, z), cur + (z * m + y) * m, m * sizeof(int16_t));
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
        for (int x = 0; x < m; ++x) out[(z * m + y) * m + x] = static_cast<uint8_t>(all.row_ptr(y, z)[x]);
    return;
  }
  Scratch& s = tls_scratch;
  s.reserve(e);
  // Undo levels L .. level+1; the coarsest low-pass block is read in place.
  CubeView<const int16_t> low = all;
  int16_t* cur = s.a.data();
  int16_t* next = s.b.data();
  for (int l = levels_, n = e >> (levels_ - 1); l > level + 1; --l, n *= 2) {
    inverse_level<int16_t>(low, all, n, compact(cur, n));
    low = compact<const int16_t>(cur, n);
    std::swap(cur, next);
  }
  inverse_level<uint8_t>(low, all, m, compact(out.data(), m));
}

void WaveletPyramid::decode(std::span<uint8_t> voxels) const { extract_level(0, voxels); }

uint8_t WaveletPyramid::voxel(int x, int y, int z) const {
  assert(x >= 0 && y >= 0 && z >= 0 && x < edge_ && y < edge_ && z < edge_);
  const int e = edge_;
  auto c = [&](int cx, int cy, int cz) { return coefficients_[(static_cast<size_t>(cz) * e + cy) * e + cx]; };
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
      for (int x = 0; x < m; ++x) zeros -= coefficients_[(static_cast<size_t>(z) * e + y) * e + x] == 0;
  return zeros;
}

}  // namespace sculpt::core
