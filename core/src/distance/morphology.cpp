#include "sculpt/core/distance/morphology.h"

#include "sculpt/core/distance/signed_distance.h"

namespace sculpt::core {

DenseGrid<float> surface_distance(const DenseGrid<float>& phi, int threads) {
  return signed_distance(phi, DistanceMethod::kExact, DistanceInit::kShell, threads);
}

DenseGrid<float> offset_distance(const DenseGrid<float>& distance, float by_vox) {
  DenseGrid<float> out = distance;
  for (float& v : out.values())
    v -= by_vox;
  return out;
}

DenseGrid<float> close_distance(const DenseGrid<float>& phi, float radius_vox, int threads) {
  // The paper's reason for the second transform: D - R is the dilated shape,
  // but it is not the distance to the dilated surface where the dilation
  // merged parts (the bridge across a gap). Re-measuring from that surface
  // and stepping back R erodes by the true distance.
  const DenseGrid<float> dilated = offset_distance(surface_distance(phi, threads), radius_vox);
  return offset_distance(surface_distance(dilated, threads), -radius_vox);
}

}  // namespace sculpt::core
