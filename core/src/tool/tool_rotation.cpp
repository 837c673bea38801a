// Discrete tool rotation, "Discrete tools for virtual sculpture" §3.1-3.2.
//
// Departures from the paper's text, all for speed without changing what is
// computed: the map runs in 16.16 fixed point (exact integer stepping, so
// brute force and Algorithm 1 agree bit for bit); each row is clipped to the
// stretch whose samples can be non-zero (the reach ball); the stretch inside
// the tool's core (a ball round the pivot where every sample reads one
// value, 255 inside a solid tool) is filled without sampling; and the scalar
// kernel skips equal-cornered cells (PreparedTool's cell table), so the cost
// follows the tool's surface rather than its rotated box. Rows are planned
// first and sampled in batches. Memory is x fastest, so the innermost step
// is along x (the paper steps along z). RotationClipping::kNone turns the
// reach clipping and the core fill off, to measure Algorithm 1 alone.
//
// This file holds the map (RotationFrame) and its batching; the inner loops
// are in rotation_kernels*.cpp, chosen by kernels() below, PreparedTool in
// prepared_tool.cpp.

#include "sculpt/core/tool/tool_rotation.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "tool/rotation_kernels.h"

namespace sculpt::core {
namespace {

using rotation::kFracBits;
using rotation::kSpanRows;
using rotation::Lines;
using rotation::Span;
using rotation::SpanRun;
using rotation::Spans;

std::atomic<bool> g_vector_kernel{true};

constexpr double kOne = 1 << kFracBits;
constexpr int kPad = PreparedTool::kPad;

int32_t to_fixed(double v) {
  return static_cast<int32_t>(std::llround(v * kOne));
}

// Sample coordinates are padded tool voxels; nearest rounds by flooring
// s + 0.5, folded into the coordinate so both samplers floor.
double sample_shift(Sampling sampling) {
  return kPad + (sampling == Sampling::kNearest ? 0.5 : 0.0);
}

// floor and ceil of doubles well inside the int range, inline: the baseline
// x86-64 target has no rounding instruction, and the libm calls cost more
// than a row's samples.
inline double fast_floor(double x) {
  const double t = static_cast<double>(static_cast<int64_t>(x));
  return t > x ? t - 1.0 : t;
}
inline double fast_ceil(double x) {
  const double t = static_cast<double>(static_cast<int64_t>(x));
  return t < x ? t + 1.0 : t;
}

}  // namespace

// The kernels' one dispatch (rotation_kernels.h), beside use_vector_kernel(),
// whose switch it reads.
namespace rotation {

const Kernels& kernels() {
#ifdef SCULPT_ROTATION_AVX2
  // The CPU is asked once, the switch on every call.
  static const bool cpu_has_avx2 = __builtin_cpu_supports("avx2");
  if (g_vector_kernel.load(std::memory_order_relaxed) && cpu_has_avx2) return kAvx2Kernels;
#endif
  return kScalarKernels;
}

}  // namespace rotation

glm::mat3 euler_xyz_deg(glm::vec3 degrees) {
  const glm::vec3 r = glm::radians(degrees);
  const glm::mat4 rx = glm::rotate(glm::mat4(1.0f), r.x, glm::vec3(1, 0, 0));
  const glm::mat4 ry = glm::rotate(glm::mat4(1.0f), r.y, glm::vec3(0, 1, 0));
  const glm::mat4 rz = glm::rotate(glm::mat4(1.0f), r.z, glm::vec3(0, 0, 1));
  glm::mat3 m(rz * ry * rx);
  // Quarter turns must be exact: snap float noise (cos 90 deg = -4e-8) to 0.
  for (int c = 0; c < 3; ++c)
    for (int r2 = 0; r2 < 3; ++r2)
      if (std::abs(m[c][r2]) < 1e-6f) m[c][r2] = 0.0f;
  return m;
}

bool use_vector_kernel(bool enabled) {
  g_vector_kernel.store(enabled, std::memory_order_relaxed);
  // kernels() is the only place that asks the CPU.
  return enabled && &rotation::kernels() != &rotation::kScalarKernels;
}

RotationFrame::RotationFrame(const PreparedTool& tool, const glm::mat3& rotation,
                             glm::vec3 position, Sampling sampling, RotationClipping clipping)
    : sampling_(sampling) {
  const glm::dvec3 pivot(tool.pivot());
  const glm::dvec3 pos(position);
  const glm::dmat3 r(rotation);
  const glm::dvec3 d(tool.dims());
  // The support of the samples in tool coordinates: trilinear reaches one
  // voxel beyond the outer centres, nearest half a voxel.
  const double margin = sampling == Sampling::kNearest ? 0.5 : 1.0;
  glm::dvec3 lo(1e300), hi(-1e300);
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 corner((c & 1) ? d.x - 1 + margin : -margin,
                            (c & 2) ? d.y - 1 + margin : -margin,
                            (c & 4) ? d.z - 1 + margin : -margin);
    const glm::dvec3 k = r * (corner - pivot) + pos;
    lo = glm::min(lo, k);
    hi = glm::max(hi, k);
  }
  // Target voxels strictly inside the support (trilinear: samples on its
  // border weigh 0) or on its low border (nearest: t = -0.5 rounds to voxel
  // 0). The 1e-9 absorbs rounding of exact quarter turns, so their box is
  // exactly the tool's.
  constexpr double kEps = 1e-9;
  const glm::dvec3 box_lo =
      sampling == Sampling::kNearest ? glm::ceil(lo - kEps) : glm::floor(lo + kEps) + 1.0;
  box_ = Box{glm::ivec3(box_lo), glm::ivec3(glm::ceil(hi - kEps))};

  const glm::dmat3 inv = glm::transpose(r);
  const glm::dvec3 s0 = inv * (glm::dvec3(box_.lo) - pos) + pivot + sample_shift(sampling);
  for (int i = 0; i < 3; ++i) {
    origin_[i] = to_fixed(s0[i]);
    // Voxels 0 .. d-1 sit at padded kPad .. d-1+kPad; a cell reaching any of
    // them starts at kPad - 1 .. d - 1 + kPad.
    support_hi_[i] = tool.dims()[i] + kPad;
  }
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i)
      step_[a][i] = to_fixed(inv[a][i]);  // component i of inv * e_a
  for (int i = 0; i < 3; ++i)
    inv_step_x_[i] = step_[0][i] != 0 ? 1.0 / step_[0][i] : 0.0;
  for (int i = 0; i < 3; ++i)
    centre_[i] = static_cast<float>(pos[i] - box_.lo[i]);

  // The balls are tested at exact target positions, the samples taken at
  // fixed-point ones: each of the box's steps is off by at most 2^-17 per
  // component (and a float rotation is orthonormal to about 1e-7), so a
  // sample is within (1 + steps) * 2^-17 * sqrt 3 + 1e-6 * distance of where
  // the balls assume. `error` is more than 7 times that bound.
  const glm::ivec3 size = box_.size();
  const double error = 0.01 + 1e-4 * (size.x + size.y + size.z);
  // spans() works in float, eight rows per instruction, so the balls absorb
  // its rounding too: the squared distances and chords are off by a few
  // 2^-24 of the squared radius (hence the relative widening of the
  // squares, which also covers the centre's rounding), the chord ends by a
  // few 2^-24 of the box size (float_error).
  const double float_error = 1e-3 + 1e-5 * (size.x + size.y + size.z);
  constexpr double kSquareError = 4e-6;
  const double reach = tool.reach_vox(sampling) + error + float_error;
  reach2_ = static_cast<float>(reach * reach * (1.0 + kSquareError) + 1e-3);
  const double core = static_cast<double>(tool.core_radius_vox(sampling)) - error - float_error;
  const double core2 = core * core * (1.0 - kSquareError) - 1e-3;
  core2_ = core > 0.0 && core2 > 0.0 ? static_cast<float>(core2) : -1.0f;
  core_value_ = tool.core_value();
  // Samples whose cell floor(s) lies in [0, dims + kPad] per axis read inside
  // the padded grid (both kernels, both samplings): tool coordinates in
  // [-kPad, dims + 1).
  // Only the axes along which the reach ball leaves the grid can cut a line
  // (a ring's axis, say): the others are not tested.
  for (int i = 0; i < 3; ++i)
    clip_axis_[i] = pivot[i] - reach < -kPad || pivot[i] + reach >= d[i] + 1.0;
  clip_support_ = clip_axis_[0] || clip_axis_[1] || clip_axis_[2];
  if (clipping == RotationClipping::kNone) {
    // A reach ball holding the whole box (a voxel to spare for the float
    // spans), no core, and lines cut to the tool's grid: every voxel of the
    // box sampled, as brute force samples it, but by Algorithm 1's steps.
    double far2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double c = centre_[i];
      const double e = std::max(std::abs(c), std::abs(size[i] - 1 - c)) + 1.0;
      far2 += e * e;
    }
    reach2_ = static_cast<float>(far2);
    core2_ = -1.0f;
    clip_axis_[0] = clip_axis_[1] = clip_axis_[2] = true;
    clip_support_ = true;
  }
}

uint8_t RotationFrame::sample_voxel(const PreparedTool& tool, glm::ivec3 k) const {
  const glm::ivec3 n = k - box_.lo;
  int32_t s[3];
  for (int i = 0; i < 3; ++i)
    s[i] = origin_[i] + n.x * step_[0][i] + n.y * step_[1][i] + n.z * step_[2][i];
  for (int i = 0; i < 3; ++i) {
    const int32_t c = s[i] >> kFracBits;
    if (c < kPad - 1 || c >= support_hi_[i]) return 0;
  }
  const glm::ivec3 pd = tool.padded_dims();
  const size_t i = rotation::cell_index(s, pd);
  if (sampling_ == Sampling::kNearest) return tool.padded()[i];
  return rotation::trilinear_at(tool.padded(), i, s, pd.x, static_cast<size_t>(pd.x) * pd.y);
}

bool RotationFrame::clip_to_support(const int32_t s[3], int count, int& n0, int& n1) const {
  // Widened by half a voxel so rounding of the (double) bounds can only add
  // samples that read zero padding; the padding keeps every sample inside
  // the grid.
  double lo = 0.0, hi = count;
  for (int i = 0; i < 3; ++i) {
    if (!clip_axis_[i]) continue;
    const double a = ((kPad - 1 - 0.5) * kOne - s[i]);
    const double b = ((support_hi_[i] + 0.5) * kOne - s[i]);
    if (step_[0][i] == 0) {
      if (a > 0.0 || b <= 0.0) return false;
      continue;
    }
    double e0 = a * inv_step_x_[i], e1 = b * inv_step_x_[i];
    if (e0 > e1) std::swap(e0, e1);
    lo = std::max(lo, fast_ceil(e0));
    hi = std::min(hi, fast_floor(e1) + 1.0);
  }
  if (lo >= hi) return false;
  n0 = static_cast<int>(lo);
  n1 = static_cast<int>(hi);
  return true;
}

void RotationFrame::clip_lines(Lines& lines, int from) const {
  // Lines with no sample in the support are dropped, the rest keep their
  // order.
  int kept = from;
  for (int l = from; l < lines.count; ++l) {
    rotation::Line line = lines.at(l);
    int n0 = 0, n1 = 0;
    if (!clip_to_support(line.s, line.n, n0, n1)) continue;
    for (int i = 0; i < 3; ++i)
      line.s[i] += n0 * step_[0][i];
    line.out += n0;
    line.n = n1 - n0;
    lines.put(kept++, line);
  }
  lines.count = kept;
}

void RotationFrame::spans(const SpanRun* runs, int count, Spans& out) const {
  assert(count == 0 || runs[count - 1].at + runs[count - 1].n <= kSpanRows);
  // A single row (the cache asks row by row) costs less one lane wide.
  const bool one_row = count == 1 && runs[0].n == 1;
  const rotation::Kernels& k = one_row ? rotation::kScalarKernels : rotation::kernels();
  k.spans(centre_, reach2_, core2_, static_cast<float>(box_.size().x), runs, count, out);
}

void RotationFrame::row_start(int y, int z, int32_t s[3]) const {
  for (int i = 0; i < 3; ++i)
    s[i] = origin_[i] + y * step_[1][i] + z * step_[2][i];
}

bool RotationFrame::reach_span(int y, int z, int& x0, int& x1) const {
  Spans sp;
  const SpanRun run{y, z, 1, 0};
  spans(&run, 1, sp);
  x0 = std::max(x0, sp.x0[0]);
  x1 = std::min(x1, sp.x1[0]);
  return x0 < x1;
}

void RotationFrame::row_plans(int z, RowPlan* plans) const {
  const glm::ivec3 size = box_.size();
  Spans sp;
  for (int ya = 0; ya < size.y; ya += kSpanRows) {
    const int n = std::min(kSpanRows, size.y - ya);
    const SpanRun run{ya, z, n, 0};
    spans(&run, 1, sp);
    for (int i = 0; i < n; ++i) {
      int x0 = sp.x0[i], x1 = sp.x1[i];
      if (clip_support_ && x0 < x1) {
        // The reach stretch cut to the support, as clip_lines() cuts each
        // line of it: a sample it drops reads zero padding either way.
        int32_t s[3];
        row_start(ya + i, z, s);
        for (int a = 0; a < 3; ++a)
          s[a] += x0 * step_[0][a];
        int n0 = 0, n1 = 0;
        if (clip_to_support(s, x1 - x0, n0, n1)) {
          x1 = x0 + n1;
          x0 += n0;
        } else {
          x0 = x1 = 0;
        }
      }
      // The core lies inside the support (the tool is solid there).
      const int c0 = x0 < x1 ? std::clamp(sp.c0[i], x0, x1) : 0;
      const int c1 = x0 < x1 ? std::clamp(sp.c1[i], c0, x1) : 0;
      plans[ya + i] = RowPlan{static_cast<int16_t>(x0), static_cast<int16_t>(x1),
                              static_cast<int16_t>(c0), static_cast<int16_t>(c1)};
    }
  }
}

void RotationFrame::plan_row(const int32_t row_s[3], int x0, int x1, Span span, uint8_t* out,
                             Lines& lines) const {
  const int from = lines.count;
  rotation::plan_row(row_s, step_[0], x0, x1, span, core_value_, out, lines);
  if (clip_support_) clip_lines(lines, from);
}

void RotationFrame::plan_rows(const int32_t row_s[3], const Spans& sp, int i, int m, uint8_t* out,
                              Lines& lines) const {
  assert(m <= 8 && i + 8 <= kSpanRows && lines.count + 16 <= Lines::kCapacity);
  // The vector planner is for the common case of unclipped rows; lines that
  // must be clipped are planned row by row by the scalar one, then clipped.
  const int from = lines.count;
  const rotation::Kernels& k = clip_support_ ? rotation::kScalarKernels : rotation::kernels();
  k.plan_rows(row_s, step_[0], step_[1], box_.size().x, core_value_, sp, i, m, out, lines);
  if (clip_support_) clip_lines(lines, from);
}

void RotationFrame::sample_row(const PreparedTool& tool, int y, int z, int x0, int x1,
                               uint8_t* out) const {
  assert(x0 <= x1);
  const int ry = y - box_.lo.y, rz = z - box_.lo.z;
  Spans sp;
  const SpanRun run{ry, rz, 1, 0};
  spans(&run, 1, sp);
  int32_t row_s[3];
  row_start(ry, rz, row_s);
  Lines lines;
  plan_row(row_s, x0 - box_.lo.x, x1 - box_.lo.x, sp.row(0), out, lines);
  rotation::kernels().sample_lines(tool, sampling_, step_[0], lines, out + (x1 - x0));
}

void RotationFrame::sample_row(const PreparedTool& tool, int y, int z, int x0, int x1, RowPlan plan,
                               uint8_t* out) const {
  assert(x0 <= x1);
  int32_t row_s[3];
  row_start(y - box_.lo.y, z - box_.lo.z, row_s);
  Lines lines;
  // The plan's stretch is within the support already: no clipping.
  rotation::plan_row(row_s, step_[0], x0 - box_.lo.x, x1 - box_.lo.x,
                     Span{plan.x0, plan.x1, plan.c0, plan.c1}, core_value_, out, lines);
  rotation::kernels().sample_lines(tool, sampling_, step_[0], lines, out + (x1 - x0));
}

void RotationFrame::sample_box(const PreparedTool& tool, uint8_t* out) const {
  const glm::ivec3 size = box_.size();
  const uint8_t* end = out + static_cast<size_t>(size.x) * size.y * size.z;
  // The rows of several planes are given their spans together, then
  // planned eight at a time into a batch of lines, which is sampled when
  // full: each stage's set-up is paid per batch rather than per row.
  Spans sp;
  constexpr int kRuns = kSpanRows / 8;
  SpanRun runs[kRuns];
  int count = 0, used = 0;
  Lines lines;
  auto plan = [&] {
    if (count == 0) return;
    spans(runs, count, sp);
    for (int r = 0; r < count; ++r) {
      const SpanRun& run = runs[r];
      uint8_t* dst = out + (static_cast<size_t>(run.z) * size.y + run.y0) * size.x;
      // Algorithm 1: each row's first sample one J step from the previous.
      int32_t row_s[3];
      for (int i = 0; i < 3; ++i)
        row_s[i] = origin_[i] + run.y0 * step_[1][i] + run.z * step_[2][i];
      for (int i = 0; i < run.n; i += 8) {
        if (lines.count + 16 > Lines::kCapacity) {
          rotation::kernels().sample_lines(tool, sampling_, step_[0], lines, end);
          lines.count = 0;
        }
        const int m = std::min(8, run.n - i);
        plan_rows(row_s, sp, run.at + i, m, dst, lines);
        dst += static_cast<size_t>(m) * size.x;
        for (int a = 0; a < 3; ++a)
          row_s[a] += m * step_[1][a];
      }
    }
    count = used = 0;
  };
  for (int z = 0; z < size.z; ++z) {
    // Only the rows of this plane that cross the reach ball.
    const double dz = z - static_cast<double>(centre_[2]);
    const double h2 = static_cast<double>(reach2_) - dz * dz;
    if (h2 < 0.0) continue;
    const double h = std::sqrt(h2);
    const int y0 = std::max(0, static_cast<int>(fast_ceil(centre_[1] - h)));
    const int y1 = std::min(size.y, static_cast<int>(fast_floor(centre_[1] + h)) + 1);
    for (int ya = y0; ya < y1; ya += kSpanRows) {
      const int n = std::min(kSpanRows, y1 - ya);
      const int slots = (n + 7) & ~7;
      if (used + slots > kSpanRows) plan();
      runs[count++] = SpanRun{ya, z, n, used};
      used += slots;
    }
  }
  plan();
  rotation::kernels().sample_lines(tool, sampling_, step_[0], lines, end);
}

RotatedTool rotate_tool(const PreparedTool& tool, const glm::mat3& rotation, glm::vec3 position,
                        RotationMethod method, Sampling sampling, RotationClipping clipping) {
  const RotationFrame frame(tool, rotation, position, sampling, clipping);
  const Box& box = frame.box();
  RotatedTool out{DenseGrid<uint8_t>(box.size()), box.lo};
  uint8_t* dst = out.density.data();
  if (method == RotationMethod::kBrute) {
    // Every target voxel: a full matrix product and a bounds test.
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        for (int x = box.lo.x; x < box.hi.x; ++x)
          *dst++ = frame.sample_voxel(tool, {x, y, z});
    return out;
  }
  frame.sample_box(tool, dst);
  return out;
}

RotatedTool rotate_tool_about_pivot(const PreparedTool& tool, const glm::mat3& rotation,
                                    RotationMethod method, Sampling sampling,
                                    RotationClipping clipping) {
  return rotate_tool(tool, rotation, tool.pivot(), method, sampling, clipping);
}

RotatedTool rotate_tool_direct(const PreparedTool& tool, const glm::mat3& rotation,
                               glm::vec3 position) {
  const RotationFrame frame(tool, rotation, position, Sampling::kNearest);
  const Box& box = frame.box();
  RotatedTool out{DenseGrid<uint8_t>(box.size()), box.lo};
  const DenseGrid<uint8_t>& src = tool.tool().density;
  const glm::ivec3 d = src.dims();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const glm::vec3 w = rotation * (glm::vec3(x, y, z) - tool.pivot()) + position;
        const glm::ivec3 k(glm::floor(w + 0.5f));
        if (!box.contains(k)) continue;
        const glm::ivec3 n = k - box.lo;
        out.density.at(n.x, n.y, n.z) = src.at(x, y, z);
      }
  return out;
}

}  // namespace sculpt::core
