#pragma once
// Internal to core/distance: loops over a mesh's triangles or vertices in
// fixed chunks, and counting-sort groups, for parallel work whose results
// must not depend on the number of threads (mesh_distance.cpp,
// narrow_band.cpp).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core::detail {

// Fixed chunks of a mesh's triangles or vertices for parallel loops whose
// results must not depend on the number of threads.
constexpr int kChunks = 16;

template <class Body>
void for_chunks(int64_t n, Body&& body, int threads = 0) {
  parallel_for(
      kChunks,
      [&](int64_t c) {
        for (int64_t i = n * c / kChunks; i < n * (c + 1) / kChunks; ++i)
          body(i);
      },
      threads);
}

// Items grouped by a key in [0, keys), each group in the order the items
// were added: start[k] .. start[k + 1] index `items` (a counting sort).
struct Groups {
  std::vector<uint32_t> start;
  std::vector<uint32_t> items;
};

template <class KeyOf>
Groups group_by(size_t keys, size_t n, KeyOf&& key_of) {
  Groups g;
  g.start.assign(keys + 1, 0);
  for (size_t i = 0; i < n; ++i)
    ++g.start[key_of(i) + 1];
  for (size_t k = 0; k < keys; ++k)
    g.start[k + 1] += g.start[k];
  g.items.resize(n);
  std::vector<uint32_t> next(g.start.begin(), g.start.end() - 1);
  for (size_t i = 0; i < n; ++i)
    g.items[next[key_of(i)]++] = uint32_t(i);
  return g;
}

}  // namespace sculpt::core::detail
