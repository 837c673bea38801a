#pragma once
// Signed distance fields of a sampled surface by any method of Jones &
// Satherley §3 (and the linear-time exact transform beyond it): float32, voxel
// units, negative inside, inside meaning phi < 0 (density above 127.5).
//
// Initialisation (what the distance is measured to):
//   kBinary  the inside boundary voxels B (equation 3: 0 at inside voxels with
//            an outside 26-neighbour); every method then approximates (or, for
//            brute / exact / octree, computes exactly) the distance to the
//            nearest voxel centre of B.
//   kShell   the sub-voxel surface (tiling-tetrahedra triangulation of the
//            iso-surface): brute and octree measure to its triangles exactly;
//            chamfer and vector transforms start from the distance shell S_n
//            (distance_shell.h); exact runs the hybrid: a feature transform to
//            S_n gives each voxel a first triangle, line sweeps along x, y
//            and z hand nearer triangles on between neighbours (measured
//            exactly), and the triangles within half a voxel of the final
//            foot point are searched: the distance to the triangulation but
//            near the medial axis (worst about 0.1 voxel there; see
//            signed_distance.cpp).

#include <optional>
#include <string>

#include "sculpt/base/result.h"
#include "sculpt/core/distance/distance_shell.h"
#include "sculpt/core/distance/surface_index.h"
#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/util/progress.h"

namespace sculpt::core {

enum class DistanceMethod {
  kBrute,
  kExact,
  kOctree,
  kChamferCity,
  kChamfer345,
  kChamfer5x5x5,
  kEvdt,
  kVcvdt
};
enum class DistanceInit { kBinary, kShell };

/// Command-line names: brute, exact, octree, chamfer-city, chamfer-345,
/// chamfer-5x5x5, evdt, vcvdt; binary, shell.
const char* distance_method_name(DistanceMethod method);
const char* distance_init_name(DistanceInit init);
Result<DistanceMethod> parse_distance_method(const std::string& name);
Result<DistanceInit> parse_distance_init(const std::string& name);

/// What every method starts from, computed once (the paper times the shell
/// separately: "7.100s + 124s").
struct DistanceInput {
  DenseGrid<float> phi;
  DenseGrid<uint8_t> inside;
  /// B (binary init only).
  DenseGrid<uint8_t> boundary;
  /// The sub-voxel surface and its shell (shell init only).
  std::optional<SurfaceIndex> surface;
  std::optional<DistanceShell> shell;
};

/// `progress` (optional, progress.h): reported 0..1; when it is cancelled
/// the returned input is incomplete and must be discarded.
DistanceInput prepare_distance_input(DenseGrid<float> phi, DistanceInit init, int threads = 0,
                                     Progress* progress = nullptr);

/// The signed field of `input` by `method` (input prepared for `init`).
/// `progress` as above: exact reports per slice, the other methods before and
/// after; a cancelled call returns a field to discard.
DenseGrid<float> compute_signed_distance(const DistanceInput& input, DistanceMethod method,
                                         DistanceInit init, int threads = 0,
                                         Progress* progress = nullptr);

/// prepare + compute in one call (progress: prepare 0..0.3, compute 0.3..1).
DenseGrid<float> signed_distance(const DenseGrid<float>& phi, DistanceMethod method,
                                 DistanceInit init, int threads = 0, Progress* progress = nullptr);
DenseGrid<float> signed_distance(const DenseGrid<uint8_t>& density, DistanceMethod method,
                                 DistanceInit init, int threads = 0);

}  // namespace sculpt::core
