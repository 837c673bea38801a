#include "sculpt/core/distance/contours.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "sculpt/core/distance/polygon_distance.h"
#include "sculpt/core/distance/signed_distance.h"

namespace sculpt::core {
namespace {

constexpr int kMaxDim = 2048;
// The grid's voxels: the level function and the 3D transform hold a few
// float grids of this size (2 GB at the limit).
constexpr int64_t kMaxVoxels = int64_t{1} << 27;

Error at_line(int line, const std::string& what) {
  return Error("line " + std::to_string(line) + ": " + what);
}

}  // namespace

Result<ContourStack> parse_contours(const std::string& text) {
  ContourStack s;
  std::istringstream in(text);
  std::string line;
  int n = 0;
  bool header = false, have_dims = false;
  Contour* open = nullptr;
  while (std::getline(in, line)) {
    ++n;
    if (const size_t h = line.find('#'); h != std::string::npos) line.resize(h);
    std::istringstream ls(line);
    std::string tag;
    if (!(ls >> tag)) continue;
    if (!header) {
      int version = 0;
      if (tag != "sculpt-contours" || !(ls >> version) || version != 1)
        return at_line(n, "expected 'sculpt-contours 1' as the first record");
      header = true;
      continue;
    }
    if (tag == "dims") {
      if (!(ls >> s.dims.x >> s.dims.y >> s.dims.z) ||
          glm::any(glm::lessThan(s.dims, glm::ivec3(2))) ||
          glm::any(glm::greaterThan(s.dims, glm::ivec3(kMaxDim))))
        return at_line(n, "dims needs three integers in 2.." + std::to_string(kMaxDim));
      if (int64_t{s.dims.x} * s.dims.y * s.dims.z > kMaxVoxels)
        return at_line(n, "dims: more than " + std::to_string(kMaxVoxels) + " voxels (512^3)");
      have_dims = true;
    } else if (tag == "contour") {
      if (!have_dims) return at_line(n, "contour before dims");
      if (open) return at_line(n, "contour inside a contour (missing 'end')");
      Contour c;
      if (!(ls >> c.slice) || c.slice < 0 || c.slice >= s.dims.z)
        return at_line(n, "contour needs a slice number in 0.." + std::to_string(s.dims.z - 1));
      s.contours.push_back(c);
      open = &s.contours.back();
    } else if (tag == "end") {
      if (!open) return at_line(n, "'end' without a contour");
      if (open->points.size() < 3) return at_line(n, "contour has fewer than 3 points");
      open = nullptr;
    } else {
      if (!open) return at_line(n, "unknown record '" + tag + "'");
      glm::vec2 p;
      std::istringstream ps(line);
      if (!(ps >> p.x >> p.y) || !std::isfinite(p.x) || !std::isfinite(p.y))
        return at_line(n, "expected a point 'X Y'");
      // Inside the slice: the distance is then linear in the contour's size
      // (polygon_distance.h), and a contour outside the grid draws nothing.
      if (p.x < 0.0f || p.y < 0.0f || p.x > float(s.dims.x - 1) || p.y > float(s.dims.y - 1))
        return at_line(n, "point outside the slice (0..dims-1)");
      open->points.push_back(p);
    }
  }
  if (!header) return Error("empty file (expected 'sculpt-contours 1')");
  if (open) return Error("contour at the end of the file has no 'end'");
  if (s.contours.empty()) return Error("no contours");
  return s;
}

Result<ContourStack> read_contours(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error(path.string() + ": cannot open file");
  std::stringstream text;
  text << in.rdbuf();
  auto s = parse_contours(text.str());
  if (!s) return s.error().in(path.string());
  return s;
}

DenseGrid<float> contour_level_function(const ContourStack& stack) {
  const glm::ivec3 d = stack.dims;
  std::map<int, std::vector<const Contour*>> by_slice;
  for (const Contour& c : stack.contours)
    by_slice[c.slice].push_back(&c);
  std::map<int, std::vector<float>> fields;
  for (const auto& [z, contours] : by_slice) {
    std::vector<const std::vector<glm::vec2>*> polygons;
    for (const Contour* c : contours)
      polygons.push_back(&c->points);
    fields[z] = polygon_signed_distance({d.x, d.y}, polygons);
  }
  DenseGrid<float> phi(d);
  const size_t slice = size_t(d.x) * d.y;
  const int first = fields.begin()->first, last = fields.rbegin()->first;
  for (int z = 0; z < d.z; ++z) {
    float* out = phi.data() + size_t(z) * slice;
    if (z < first || z > last) {
      // Flat cap: outside by the distance to the end slice.
      const std::vector<float>& f = fields[z < first ? first : last];
      const float gap = float(z < first ? first - z : z - last);
      for (size_t i = 0; i < slice; ++i)
        out[i] = std::max(f[i], gap);
      continue;
    }
    auto hi = fields.lower_bound(z);
    if (hi->first == z) {
      std::copy(hi->second.begin(), hi->second.end(), out);
      continue;
    }
    auto lo = std::prev(hi);
    const float t = float(z - lo->first) / float(hi->first - lo->first);
    for (size_t i = 0; i < slice; ++i)
      out[i] = (1 - t) * lo->second[i] + t * hi->second[i];
  }
  return phi;
}

DenseGrid<float> contour_distance_field(const ContourStack& stack, int threads) {
  return signed_distance(contour_level_function(stack), DistanceMethod::kExact,
                         DistanceInit::kShell, threads);
}

}  // namespace sculpt::core
