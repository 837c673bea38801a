#pragma once
// Internal to the mesh module: values grouped by a vertex index, for the
// topology check (mesh.cpp) and the simplifier's triangles around each
// vertex (brick_simplify.cpp).

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

namespace sculpt::core::detail {

// Values grouped by a vertex index, each group sorted: a counting sort over
// the indices (dense: below the vertex count), so grouping is linear in the
// values and each sort is over a vertex's few. Sorting all of a mesh's
// edges as tuples instead took the window's simplifier half its time.
// `each(put)` calls put(vertex, value) for every value, the same ones each
// time: it is called twice, to count and to fill.
template <class Value>
class ByVertex {
 public:
  template <class Each>
  ByVertex(size_t vertex_count, Each each) : start_(vertex_count + 1, 0) {
    each([&](uint32_t v, const Value&) {
      assert(v < vertex_count);
      ++start_[v + 1];
    });
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    values_.resize(start_.back());
    std::vector<uint32_t> end(start_.begin(), start_.end() - 1);
    each([&](uint32_t v, const Value& value) { values_[end[v]++] = value; });
    for (size_t v = 0; v < vertex_count; ++v)
      std::sort(values_.begin() + start_[v], values_.begin() + start_[v + 1]);
  }
  std::span<const Value> of(size_t v) const {
    return std::span(values_).subspan(start_[v], start_[v + 1] - start_[v]);
  }

 private:
  std::vector<uint32_t> start_;
  std::vector<Value> values_;
};

}  // namespace sculpt::core::detail
