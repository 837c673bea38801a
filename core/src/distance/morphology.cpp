#include "sculpt/core/distance/morphology.h"

#include "sculpt/core/distance/signed_distance.h"

namespace sculpt::core {

DenseGrid<float> surface_distance(const DenseGrid<float>& phi, int threads, Progress* progress) {
  return signed_distance(phi, DistanceMethod::kExact, DistanceInit::kShell, threads, progress);
}

DenseGrid<float> offset_distance(const DenseGrid<float>& distance, float by_vox) {
  DenseGrid<float> out = distance;
  for (float& v : out.values())
    v -= by_vox;
  return out;
}

DenseGrid<float> close_distance(const DenseGrid<float>& phi, float radius_vox, int threads,
                                Progress* progress) {
  // The paper's reason for the second transform: D - R is the dilated shape,
  // but it is not the distance to the dilated surface where the dilation
  // merged parts (the bridge across a gap). Re-measuring from that surface
  // and stepping back R erodes by the true distance.
  SubProgress first(progress, 0.0, 0.5), second(progress, 0.5, 1.0);
  const DenseGrid<float> dilated =
      offset_distance(surface_distance(phi, threads, first.get()), radius_vox);
  if (cancelled(progress)) return dilated;
  return offset_distance(surface_distance(dilated, threads, second.get()), -radius_vox);
}

}  // namespace sculpt::core
