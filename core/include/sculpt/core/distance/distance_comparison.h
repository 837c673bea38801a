#pragma once
// The comparison of Jones & Satherley §3.7 (their Table 1) on shapes whose
// true distance is known: per method and initialisation, the time, the error
// range (most negative, most positive) and the mean absolute error against
// the analytic signed distance at every voxel centre.

#include <string>
#include <vector>

#include "sculpt/core/distance/signed_distance.h"
#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

enum class ComparisonShape {
  /// Radius 0.3 n, centre (n-1)/2 + (0.31, -0.17, 0.23): off the grid.
  kSphere,
  /// Around z, major radius 0.25 n, minor 0.1 n, centre (n-1)/2 + (0.19, 0.27, -0.11).
  kTorus,
};

struct ComparisonInput {
  std::string name;
  /// uint8 density (analytic_shapes.h ramp), n^3.
  DenseGrid<uint8_t> density;
  /// Analytic signed distance at every voxel centre, voxel units.
  DenseGrid<float> truth;
};

ComparisonInput comparison_input(ComparisonShape shape, int n);

struct ComparisonCase {
  DistanceMethod method;
  DistanceInit init;
};

struct ComparisonRow {
  std::string shape;
  int n = 0;
  ComparisonCase c{};
  /// Computing B or the shell (the paper's "+ 124s"), seconds.
  double prepare_seconds = 0;
  /// The transform itself, seconds.
  double seconds = 0;
  /// Most negative and most positive (computed - true), voxels.
  float min_error = 0, max_error = 0;
  /// Mean |computed - true| over all voxels.
  double mean_error = 0;
};

/// The cases of the table: every method but brute (O(n m)) with both
/// initialisations.
std::vector<ComparisonCase> default_comparison_cases();

/// Runs `cases` on `input` (n = its size) with `threads`.
std::vector<ComparisonRow> compare_distance_methods(const ComparisonInput& input,
                                                    const std::vector<ComparisonCase>& cases,
                                                    int threads = 0);

/// Markdown table of rows: shape, size, method, init, time, error range, mean.
std::string comparison_markdown(const std::vector<ComparisonRow>& rows);

}  // namespace sculpt::core
