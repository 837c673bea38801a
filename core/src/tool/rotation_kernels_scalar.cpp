// The portable kernels of tool rotation (rotation_kernels.h): the reference
// the AVX2 kernels must match bit for bit, and the path on CPUs without
// AVX2 or with the vector kernel switched off.
//
// Their own file, beside rotation_kernels_avx2.cpp, so that each kernel's
// two versions can be read side by side and RotationFrame (tool_rotation.cpp)
// keeps only the map and the batching.

#include <algorithm>
#include <cmath>
#include <cstring>

#include "tool/rotation_kernels.h"

namespace sculpt::core::rotation {
namespace {

// The scalar kernel skips equal-cornered cells (PreparedTool::cells()), so
// its cost follows the tool's surface rather than its rotated box.
void sample_lines_scalar(const PreparedTool& tool, Sampling sampling, const int32_t step_i[3],
                         const Lines& lines, const uint8_t* /*end*/) {
  const glm::ivec3 pd = tool.padded_dims();
  const bool nearest = sampling == Sampling::kNearest;
  const size_t px = pd.x, pxy = px * pd.y;
  const uint8_t* padded = tool.padded();
  const uint16_t* cells = tool.cells();
  const int32_t st[3] = {step_i[0], step_i[1], step_i[2]};
  for (int l = 0; l < lines.count; ++l) {
    int32_t s[3] = {lines.s0[l], lines.s1[l], lines.s2[l]};
    uint8_t* out = lines.out[l];
    const int n1 = lines.n[l];
    if (nearest) {
      for (int n = 0; n < n1; ++n) {
        out[n] = padded[cell_index(s, pd)];
        s[0] += st[0];
        s[1] += st[1];
        s[2] += st[2];
      }
      continue;
    }
    for (int n = 0; n < n1; ++n) {
      const size_t i = cell_index(s, pd);
      const uint16_t c = cells[i];
      out[n] = c != 0 ? static_cast<uint8_t>(c) : trilinear_at(padded, i, s, px, pxy);
      s[0] += st[0];
      s[1] += st[1];
      s[2] += st[2];
    }
  }
}

// One row's span from its squared distance to the balls' axis, in the same
// float operations as the AVX2 kernel's eight rows, so both give the same
// spans: ceil and floor by truncation, as the baseline x86-64 has no
// rounding instruction.
inline float trunc_ceil(float v) {
  const auto t = static_cast<float>(static_cast<int32_t>(v));
  return t < v ? t + 1.0f : t;
}
inline float trunc_floor(float v) {
  const auto t = static_cast<float>(static_cast<int32_t>(v));
  return t > v ? t - 1.0f : t;
}

void spans_scalar(const float centre[3], float reach2, float core2, float width,
                  const SpanRun* runs, int count, Spans& out) {
  const float cx = centre[0];
  for (int r = 0; r < count; ++r) {
    const SpanRun& run = runs[r];
    const float dz = static_cast<float>(run.z) - centre[2];
    const float dz2 = dz * dz;
    for (int i = 0; i < run.n; ++i) {
      const int at = run.at + i;
      const float dy = static_cast<float>(run.y0 + i) - centre[1];
      const float r2 = dy * dy + dz2;
      const float h2 = reach2 - r2;
      const float h = std::sqrt(std::max(h2, 0.0f));
      float x0 = std::max(0.0f, trunc_ceil(cx - h));
      float x1 = std::min(width, trunc_floor(cx + h) + 1.0f);
      if (!(h2 >= 0.0f && x0 < x1)) x0 = x1 = 0.0f;
      const float k2 = core2 - r2;
      const float k = std::sqrt(std::max(k2, 0.0f));
      float c0 = x1, c1 = x1;
      if (core2 > 0.0f && k2 > 0.0f) {
        c0 = std::min(std::max(trunc_ceil(cx - k), x0), x1);
        c1 = std::min(std::max(trunc_floor(cx + k) + 1.0f, c0), x1);
      }
      out.x0[at] = static_cast<int32_t>(x0);
      out.x1[at] = static_cast<int32_t>(x1);
      out.c0[at] = static_cast<int32_t>(c0);
      out.c1[at] = static_cast<int32_t>(c1);
    }
  }
}

void plan_rows_scalar(const int32_t row_s[3], const int32_t step_i[3], const int32_t step_j[3],
                      int width, uint8_t core_value, const Spans& sp, int i, int m, uint8_t* out,
                      Lines& lines) {
  int32_t s[3] = {row_s[0], row_s[1], row_s[2]};
  for (int r = 0; r < m; ++r, out += width) {
    plan_row(s, step_i, 0, width, sp.row(i + r), core_value, out, lines);
    for (int a = 0; a < 3; ++a)
      s[a] += step_j[a];
  }
}

}  // namespace

void plan_row(const int32_t row_s[3], const int32_t step_i[3], int x0, int x1, Span span,
              uint8_t core_value, uint8_t* out, Lines& lines) {
  const int first = x0;
  // The stretch within reach, and the core stretch [c0, c1) in it, which
  // needs no sampling.
  x0 = std::max(x0, span.x0);
  x1 = std::min(x1, span.x1);
  if (x0 >= x1) return;
  const int c0 = std::clamp(span.c0, x0, x1);
  const int c1 = std::clamp(span.c1, c0, x1);
  auto add_line = [&](int a, int b) {
    Line line;
    for (int i = 0; i < 3; ++i)
      line.s[i] = row_s[i] + a * step_i[i];
    line.n = b - a;
    line.out = out + (a - first);
    lines.add(line);
  };
  // A short core is sampled with the rest (its samples are the core value
  // anyway).
  if (c1 - c0 < kMinCoreRun) {
    add_line(x0, x1);
    return;
  }
  if (core_value != 0) std::memset(out + (c0 - first), core_value, c1 - c0);
  if (x0 < c0) add_line(x0, c0);
  if (c1 < x1) add_line(c1, x1);
}

const Kernels kScalarKernels = {sample_lines_scalar, spans_scalar, plan_rows_scalar};

}  // namespace sculpt::core::rotation
