// Patch-wise tessellation with cached basis functions. A step of the path
// constraint moves hundreds of control points of a refined sheet rigidly, so
// re-evaluating every vertex they reach would cost a 100-step path tens of
// milliseconds; moving the vertices whose whole support moved by the same
// rigid motion, and evaluating only the rim, keeps it to a few. The rim is
// what costs (about 2000 vertices a step of the Figure 14 path at 4 cells
// per refined span): update() decides per patch rather than per vertex and
// contracts only the control columns the rim's patches use; a step
// allocates nothing. What remains is the evaluation itself (one rational
// point, two derivatives and a normalised normal per rim vertex), which a
// batched, vectorisable version did not make faster without AVX.

#include "sculpt/core/nurbs/surface_tessellator.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>

namespace sculpt::core::nurbs {

SurfaceTessellator::SurfaceTessellator(const NurbsSurface& surface, int samples_per_span)
    : per_span_(std::max(1, samples_per_span)) {
  rebuild(surface);
}

SurfaceTessellator SurfaceTessellator::with_cells(const NurbsSurface& surface, int cells_u,
                                                  int cells_v) {
  SurfaceTessellator t;
  t.per_span_ = 0;
  t.cells_u_ = std::max(1, cells_u);
  t.cells_v_ = std::max(1, cells_v);
  t.rebuild(surface);
  return t;
}

void SurfaceTessellator::build_axis(const std::vector<double>& knots, int degree, int count,
                                    int cells, std::vector<AxisSample>& axis,
                                    std::vector<int>& spans, std::vector<int>& first) {
  axis.clear();
  spans.clear();
  first.clear();
  for (int s = degree; s < count; ++s) {
    if (knots[static_cast<size_t>(s)] < knots[static_cast<size_t>(s + 1)]) spans.push_back(s);
  }
  const size_t w = static_cast<size_t>(degree + 1);
  std::array<double, 2 * (kMaxDegree + 1)> nd{};
  auto add = [&](double t, int span) {
    basis_derivatives(knots, degree, span, t, 1, nd.data());
    AxisSample a;
    a.t = t;
    a.span = span;
    std::copy(nd.begin(), nd.begin() + static_cast<ptrdiff_t>(w), a.n.begin());
    std::copy(nd.begin() + static_cast<ptrdiff_t>(w), nd.begin() + static_cast<ptrdiff_t>(2 * w),
              a.dn.begin());
    axis.push_back(a);
  };
  const double domain = knots[static_cast<size_t>(count)] - knots[static_cast<size_t>(degree)];
  for (int s : spans) {
    const double lo = knots[static_cast<size_t>(s)];
    const double hi = knots[static_cast<size_t>(s + 1)];
    const int n = cells > 0 ? std::max(1, static_cast<int>(std::lround(cells * (hi - lo) / domain)))
                            : per_span_;
    first.push_back(static_cast<int>(axis.size()));
    for (int k = 0; k < n; ++k) {
      add(lo + (hi - lo) * k / n, s);
    }
  }
  // The domain's end is evaluated in the last span (one-sided limit).
  add(knots[static_cast<size_t>(spans.back() + 1)], spans.back());
  first.push_back(static_cast<int>(axis.size()));
}

void SurfaceTessellator::rebuild(const NurbsSurface& s) {
  degree_u_ = s.degree_u;
  degree_v_ = s.degree_v;
  count_u_ = s.count_u;
  count_v_ = s.count_v;
  knots_u_ = s.knots_u;
  knots_v_ = s.knots_v;
  pw_.resize(static_cast<size_t>(s.point_count()));
  for (int k = 0; k < s.point_count(); ++k)
    pw_[static_cast<size_t>(k)] = homogeneous(s, k);
  build_axis(knots_u_, degree_u_, count_u_, cells_u_, axis_u_, spans_u_, first_u_);
  build_axis(knots_v_, degree_v_, count_v_, cells_v_, axis_v_, spans_v_, first_v_);
  const int nu = vertices_u();
  const int nv = vertices_v();
  const size_t n = static_cast<size_t>(nu) * static_cast<size_t>(nv);
  positions_.assign(n, glm::dvec3(0.0));
  normals_.assign(n, glm::dvec3(0.0, 0.0, 1.0));
  mesh_.positions.assign(n, glm::vec3(0.0f));
  mesh_.normals.assign(n, glm::vec3(0.0f, 0.0f, 1.0f));
  mesh_.triangles.clear();
  mesh_.triangles.reserve(static_cast<size_t>(2 * (nu - 1) * (nv - 1)));
  for (int b = 0; b + 1 < nv; ++b) {
    for (int a = 0; a + 1 < nu; ++a) {
      const auto i00 = static_cast<uint32_t>(a + nu * b);
      const auto i10 = i00 + 1;
      const auto i01 = i00 + static_cast<uint32_t>(nu);
      const auto i11 = i01 + 1;
      mesh_.triangles.emplace_back(i00, i10, i11);
      mesh_.triangles.emplace_back(i00, i11, i01);
    }
  }
  for (int b = 0; b < nv; ++b) {
    prepare_row(b, 0, count_u_ - 1);
    for (size_t pu = 0; pu < spans_u_.size(); ++pu)
      for (int a = first_u_[pu]; a < first_u_[pu + 1]; ++a)
        evaluate_vertex(a, b);
  }
  moved_sum_.assign(static_cast<size_t>((count_u_ + 1) * (count_v_ + 1)), 0);
  moved_flag_.assign(static_cast<size_t>(count_u_ * count_v_), 0);
  patch_moved_.assign(spans_u_.size(), 0);
  column_stamp_.assign(static_cast<size_t>(count_u_), 0);
  row_stamp_ = 0;
}

void SurfaceTessellator::contract_column(int b, int i) {
  const AxisSample& sv = axis_v_[static_cast<size_t>(b)];
  const int j0 = sv.span - degree_v_;
  glm::dvec4 q(0.0), dq(0.0);
  for (int y = 0; y <= degree_v_; ++y) {
    const glm::dvec4& pw = pw_[static_cast<size_t>(i + count_u_ * (j0 + y))];
    q += sv.n[static_cast<size_t>(y)] * pw;
    dq += sv.dn[static_cast<size_t>(y)] * pw;
  }
  row_q_[static_cast<size_t>(i)] = q;
  row_dq_[static_cast<size_t>(i)] = dq;
}

void SurfaceTessellator::prepare_row(int b, int first, int last) {
  row_q_.resize(static_cast<size_t>(count_u_));
  row_dq_.resize(static_cast<size_t>(count_u_));
  for (int i = first; i <= last; ++i)
    contract_column(b, i);
}

void SurfaceTessellator::prepare_columns(int b, int first, int last) {
  for (int i = first; i <= last; ++i) {
    uint32_t& stamp = column_stamp_[static_cast<size_t>(i)];
    if (stamp == row_stamp_) continue;
    stamp = row_stamp_;
    contract_column(b, i);
  }
}

void SurfaceTessellator::evaluate_vertex(int a, int b) {
  // Homogeneous S, dS/du, dS/dv from the contracted row (prepare_row).
  const AxisSample& su = axis_u_[static_cast<size_t>(a)];
  const int i0 = su.span - degree_u_;
  glm::dvec4 s(0.0), du(0.0), dv(0.0);
  for (int x = 0; x <= degree_u_; ++x) {
    const glm::dvec4& q = row_q_[static_cast<size_t>(i0 + x)];
    s += su.n[static_cast<size_t>(x)] * q;
    du += su.dn[static_cast<size_t>(x)] * q;
    dv += su.n[static_cast<size_t>(x)] * row_dq_[static_cast<size_t>(i0 + x)];
  }
  // One division and one square root per vertex: they dominated the cost.
  const double inv_w = 1.0 / s.w;
  const glm::dvec3 p = glm::dvec3(s) * inv_w;
  const glm::dvec3 pu = (glm::dvec3(du) - du.w * p) * inv_w;
  const glm::dvec3 pv = (glm::dvec3(dv) - dv.w * p) * inv_w;
  glm::dvec3 n = glm::cross(pu, pv);
  const double len2 = glm::dot(n, n);
  if (len2 > 1e-24 * glm::dot(pu, pu) * glm::dot(pv, pv) && len2 > 0.0) {
    n *= 1.0 / std::sqrt(len2);
  } else {
    // A collapsed edge: fall back to the nudged evaluation of normal().
    NurbsSurface view;
    view.degree_u = degree_u_;
    view.degree_v = degree_v_;
    view.count_u = count_u_;
    view.count_v = count_v_;
    view.knots_u = knots_u_;
    view.knots_v = knots_v_;
    view.points.resize(pw_.size());
    view.weights.resize(pw_.size());
    for (size_t k = 0; k < pw_.size(); ++k) {
      view.points[k] = glm::dvec3(pw_[k]) / pw_[k].w;
      view.weights[k] = pw_[k].w;
    }
    n = normal(view, su.t, axis_v_[static_cast<size_t>(b)].t);
  }
  const size_t v = static_cast<size_t>(a + vertices_u() * b);
  positions_[v] = p;
  normals_[v] = n;
  mesh_.positions[v] = glm::vec3(p);
  mesh_.normals[v] = glm::vec3(n);
  ++vertices_evaluated_;
}

int SurfaceTessellator::moved_in_support(int su, int sv) const {
  // Support of span (su, sv): control points [su-p, su] x [sv-q, sv].
  const int w = count_u_ + 1;
  const int i0 = su - degree_u_, i1 = su + 1;
  const int j0 = sv - degree_v_, j1 = sv + 1;
  auto at = [&](int i, int j) { return moved_sum_[static_cast<size_t>(i + w * j)]; };
  return at(i1, j1) - at(i0, j1) - at(i1, j0) + at(i0, j0);
}

int SurfaceTessellator::update(const NurbsSurface& s, std::span<const int> moved,
                               const RigidMotion* motion) {
  if (s.degree_u != degree_u_ || s.degree_v != degree_v_ || s.count_u != count_u_ ||
      s.count_v != count_v_ || s.knots_u != knots_u_ || s.knots_v != knots_v_) {
    rebuild(s);
    return patch_count();
  }
  if (moved.empty()) return 0;
  // Moved flags as 2D prefix sums, and the index box of the moved points.
  int lo_i = count_u_, hi_i = -1, lo_j = count_v_, hi_j = -1;
  for (int k : moved) {
    pw_[static_cast<size_t>(k)] = homogeneous(s, k);
    moved_flag_[static_cast<size_t>(k)] = 1;
    const int i = k % count_u_, j = k / count_u_;
    lo_i = std::min(lo_i, i);
    hi_i = std::max(hi_i, i);
    lo_j = std::min(lo_j, j);
    hi_j = std::max(hi_j, j);
  }
  const int w = count_u_ + 1;
  for (int j = 0; j < count_v_; ++j) {
    int row = 0;
    for (int i = 0; i < count_u_; ++i) {
      row += moved_flag_[static_cast<size_t>(i + count_u_ * j)];
      moved_sum_[static_cast<size_t>(i + 1 + w * (j + 1))] =
          moved_sum_[static_cast<size_t>(i + 1 + w * j)] + row;
    }
  }
  for (int k : moved)
    moved_flag_[static_cast<size_t>(k)] = 0;
  const int full = (degree_u_ + 1) * (degree_v_ + 1);
  // Patches whose span lies in [lo, hi + degree] can see a moved point.
  auto patch_range = [](const std::vector<int>& spans, int first_span, int last_span) {
    const auto lo = std::lower_bound(spans.begin(), spans.end(), first_span);
    const auto hi = std::upper_bound(spans.begin(), spans.end(), last_span);
    return std::pair<int, int>(static_cast<int>(lo - spans.begin()),
                               static_cast<int>(hi - spans.begin()));
  };
  const auto [pu0, pu1] = patch_range(spans_u_, lo_i, hi_i + degree_u_);
  const auto [pv0, pv1] = patch_range(spans_v_, lo_j, hi_j + degree_v_);
  const int nu = vertices_u();
  int patches = 0;
  // Patch by patch: the vertices of a patch share one support, so one count
  // decides for all of them whether they are untouched, move rigidly, or
  // are evaluated.
  for (int pv = pv0; pv < pv1; ++pv) {
    const int sv = spans_v_[static_cast<size_t>(pv)];
    bool any = false;
    for (int pu = pu0; pu < pu1; ++pu) {
      const int count = moved_in_support(spans_u_[static_cast<size_t>(pu)], sv);
      patch_moved_[static_cast<size_t>(pu)] = count;
      patches += count > 0;
      any = any || count > 0;
    }
    if (!any) continue;
    for (int b = first_v_[static_cast<size_t>(pv)]; b < first_v_[static_cast<size_t>(pv + 1)];
         ++b) {
      ++row_stamp_;  // a new row: no column contracted yet
      for (int pu = pu0; pu < pu1; ++pu) {
        const int count = patch_moved_[static_cast<size_t>(pu)];
        if (count == 0) continue;
        const int a0 = first_u_[static_cast<size_t>(pu)];
        const int a1 = first_u_[static_cast<size_t>(pu + 1)];
        if (count == full && motion != nullptr) {
          for (int a = a0; a < a1; ++a) {
            const size_t v = static_cast<size_t>(a + nu * b);
            positions_[v] = motion->apply(positions_[v]);
            normals_[v] = motion->rotation * normals_[v];
            mesh_.positions[v] = glm::vec3(positions_[v]);
            mesh_.normals[v] = glm::vec3(normals_[v]);
          }
          vertices_moved_rigidly_ += a1 - a0;
        } else {
          const int su = spans_u_[static_cast<size_t>(pu)];
          prepare_columns(b, su - degree_u_, su);
          for (int a = a0; a < a1; ++a)
            evaluate_vertex(a, b);
        }
      }
    }
  }
  return patches;
}

Mesh tessellate(const NurbsSurface& surface, int samples_per_span) {
  return SurfaceTessellator(surface, samples_per_span).mesh();
}

}  // namespace sculpt::core::nurbs
