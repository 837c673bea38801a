// Patch-wise tessellation with cached basis functions: a deformation step of
// the path constraint moves a handful of control points, so re-evaluating only
// the patches they reach keeps a 100-step path well inside a frame.

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

void SurfaceTessellator::build_axis(const std::vector<double>& knots, int degree, int count,
                                    std::vector<AxisSample>& axis, std::vector<int>& spans) {
  axis.clear();
  spans.clear();
  for (int s = degree; s < count; ++s) {
    if (knots[static_cast<size_t>(s)] < knots[static_cast<size_t>(s + 1)]) spans.push_back(s);
  }
  const size_t w = static_cast<size_t>(degree + 1);
  std::vector<double> nd(2 * w);
  auto add = [&](double t, int span) {
    basis_derivatives(knots, degree, span, t, 1, nd.data());
    AxisSample a;
    a.t = t;
    a.span = span;
    a.n.assign(nd.begin(), nd.begin() + static_cast<ptrdiff_t>(w));
    a.dn.assign(nd.begin() + static_cast<ptrdiff_t>(w), nd.end());
    axis.push_back(std::move(a));
  };
  for (int s : spans) {
    const double lo = knots[static_cast<size_t>(s)];
    const double hi = knots[static_cast<size_t>(s + 1)];
    for (int k = 0; k < per_span_; ++k)
      add(lo + (hi - lo) * k / per_span_, s);
  }
  // The domain's end is evaluated in the last span (one-sided limit).
  add(knots[static_cast<size_t>(spans.back() + 1)], spans.back());
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
  build_axis(knots_u_, degree_u_, count_u_, axis_u_, spans_u_);
  build_axis(knots_v_, degree_v_, count_v_, axis_v_, spans_v_);
  const int nu = vertices_u();
  const int nv = vertices_v();
  mesh_.positions.assign(static_cast<size_t>(nu * nv), glm::vec3(0.0f));
  mesh_.normals.assign(static_cast<size_t>(nu * nv), glm::vec3(0.0f, 0.0f, 1.0f));
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
    for (int a = 0; a < nu; ++a)
      evaluate_vertex(a, b);
  }
  dirty_.assign(static_cast<size_t>(patch_count()), 0);
  patches_evaluated_ += patch_count();
}

void SurfaceTessellator::evaluate_vertex(int a, int b) {
  const AxisSample& su = axis_u_[static_cast<size_t>(a)];
  const AxisSample& sv = axis_v_[static_cast<size_t>(b)];
  glm::dvec4 s(0.0), du(0.0), dv(0.0);
  const int i0 = su.span - degree_u_;
  const int j0 = sv.span - degree_v_;
  for (int y = 0; y <= degree_v_; ++y) {
    const glm::dvec4* row = &pw_[static_cast<size_t>(i0 + count_u_ * (j0 + y))];
    glm::dvec4 r0(0.0), r1(0.0);
    for (int x = 0; x <= degree_u_; ++x) {
      r0 += su.n[static_cast<size_t>(x)] * row[x];
      r1 += su.dn[static_cast<size_t>(x)] * row[x];
    }
    s += sv.n[static_cast<size_t>(y)] * r0;
    du += sv.n[static_cast<size_t>(y)] * r1;
    dv += sv.dn[static_cast<size_t>(y)] * r0;
  }
  const glm::dvec3 p = glm::dvec3(s) / s.w;
  const glm::dvec3 pu = (glm::dvec3(du) - du.w * p) / s.w;
  const glm::dvec3 pv = (glm::dvec3(dv) - dv.w * p) / s.w;
  glm::dvec3 n = glm::cross(pu, pv);
  const double len = glm::length(n);
  if (len > 1e-12 * glm::length(pu) * glm::length(pv) && len > 0.0) {
    n /= len;
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
    n = normal(view, su.t, sv.t);
  }
  const size_t v = static_cast<size_t>(a + vertices_u() * b);
  mesh_.positions[v] = glm::vec3(p);
  mesh_.normals[v] = glm::vec3(n);
}

void SurfaceTessellator::evaluate_patch(int pu, int pv) {
  for (int b = pv * per_span_; b <= (pv + 1) * per_span_; ++b) {
    for (int a = pu * per_span_; a <= (pu + 1) * per_span_; ++a)
      evaluate_vertex(a, b);
  }
}

int SurfaceTessellator::update(const NurbsSurface& s, std::span<const int> moved) {
  if (s.degree_u != degree_u_ || s.degree_v != degree_v_ || s.count_u != count_u_ ||
      s.count_v != count_v_ || s.knots_u != knots_u_ || s.knots_v != knots_v_) {
    rebuild(s);
    return patch_count();
  }
  if (moved.empty()) return 0;
  // Knot span -> patch column / row (spans of zero length have no patch).
  auto patch_range = [](const std::vector<int>& spans, int first_span, int last_span) {
    const auto lo = std::lower_bound(spans.begin(), spans.end(), first_span);
    const auto hi = std::upper_bound(spans.begin(), spans.end(), last_span);
    return std::pair<int, int>(static_cast<int>(lo - spans.begin()),
                               static_cast<int>(hi - spans.begin()));
  };
  const int pu_count = patches_u();
  for (int k : moved) {
    pw_[static_cast<size_t>(k)] = homogeneous(s, k);
    const int i = k % count_u_;
    const int j = k / count_u_;
    const auto [u0, u1] = patch_range(spans_u_, i, i + degree_u_);
    const auto [v0, v1] = patch_range(spans_v_, j, j + degree_v_);
    for (int pv = v0; pv < v1; ++pv) {
      for (int pu = u0; pu < u1; ++pu)
        dirty_[static_cast<size_t>(pu + pu_count * pv)] = 1;
    }
  }
  int count = 0;
  for (int pv = 0; pv < patches_v(); ++pv) {
    for (int pu = 0; pu < pu_count; ++pu) {
      uint8_t& d = dirty_[static_cast<size_t>(pu + pu_count * pv)];
      if (d == 0) continue;
      d = 0;
      evaluate_patch(pu, pv);
      ++count;
    }
  }
  patches_evaluated_ += count;
  return count;
}

Mesh tessellate(const NurbsSurface& surface, int samples_per_span) {
  return SurfaceTessellator(surface, samples_per_span).mesh();
}

}  // namespace sculpt::core::nurbs
