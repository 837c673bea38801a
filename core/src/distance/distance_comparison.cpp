#include "sculpt/core/distance/distance_comparison.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

ComparisonInput comparison_input(ComparisonShape shape, int n) {
  ComparisonInput in;
  const glm::vec3 mid(float(n - 1) * 0.5f);
  in.density = DenseGrid<uint8_t>(glm::ivec3(n));
  in.truth = DenseGrid<float>(glm::ivec3(n));
  const glm::vec3 c = mid + (shape == ComparisonShape::kSphere ? glm::vec3(0.31f, -0.17f, 0.23f)
                                                               : glm::vec3(0.19f, 0.27f, -0.11f));
  in.name = shape == ComparisonShape::kSphere ? "sphere" : "torus";
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const glm::vec3 q = glm::vec3(float(x), float(y), float(z)) - c;
        float d;
        if (shape == ComparisonShape::kSphere) {
          d = glm::length(q) - 0.3f * float(n);
        } else {
          const float ring = std::sqrt(q.x * q.x + q.y * q.y) - 0.25f * float(n);
          d = std::sqrt(ring * ring + q.z * q.z) - 0.1f * float(n);
        }
        in.truth.at(x, y, z) = d;
        in.density.at(x, y, z) = density_from_distance(d);
      }
  return in;
}

std::vector<ComparisonCase> default_comparison_cases() {
  std::vector<ComparisonCase> cases;
  for (DistanceMethod m :
       {DistanceMethod::kExact, DistanceMethod::kOctree, DistanceMethod::kChamferCity,
        DistanceMethod::kChamfer345, DistanceMethod::kChamfer5x5x5, DistanceMethod::kEvdt,
        DistanceMethod::kVcvdt})
    for (DistanceInit i : {DistanceInit::kBinary, DistanceInit::kShell})
      cases.push_back({m, i});
  return cases;
}

std::vector<ComparisonRow> compare_distance_methods(const ComparisonInput& input,
                                                    const std::vector<ComparisonCase>& cases,
                                                    int threads) {
  std::vector<ComparisonRow> rows;
  const DenseGrid<float> phi = level_function(input.density);
  for (DistanceInit init : {DistanceInit::kBinary, DistanceInit::kShell}) {
    bool wanted = false;
    for (const auto& c : cases)
      wanted |= c.init == init;
    if (!wanted) continue;
    auto t0 = std::chrono::steady_clock::now();
    const DistanceInput prepared = prepare_distance_input(phi, init, threads);
    const double prepare = seconds_since(t0);
    for (const auto& c : cases) {
      if (c.init != init) continue;
      t0 = std::chrono::steady_clock::now();
      const DenseGrid<float> d = compute_signed_distance(prepared, c.method, init, threads);
      ComparisonRow r;
      r.seconds = seconds_since(t0);
      r.prepare_seconds = prepare;
      r.shape = input.name;
      r.n = input.density.dims().x;
      r.c = c;
      r.min_error = r.max_error = d[0] - input.truth[0];
      double sum = 0;
      for (size_t i = 0; i < d.size(); ++i) {
        const float e = d[i] - input.truth[i];
        r.min_error = std::min(r.min_error, e);
        r.max_error = std::max(r.max_error, e);
        sum += std::abs(double(e));
      }
      r.mean_error = sum / double(d.size());
      rows.push_back(r);
    }
  }
  return rows;
}

std::string comparison_markdown(const std::vector<ComparisonRow>& rows) {
  std::string out =
      "| shape | size | method | init | time | error range (voxels) | mean abs error |\n"
      "|---|---:|---|---|---:|---|---:|\n";
  char line[256];
  for (const ComparisonRow& r : rows) {
    std::snprintf(
        line, sizeof line, "| %s | %d^3 | %s | %s | %.3f s + %.3f s | %+.4f -> %+.4f | %.4f |\n",
        r.shape.c_str(), r.n, distance_method_name(r.c.method), distance_init_name(r.c.init),
        r.seconds, r.prepare_seconds, double(r.min_error), double(r.max_error), r.mean_error);
    out += line;
  }
  return out;
}

}  // namespace sculpt::core
