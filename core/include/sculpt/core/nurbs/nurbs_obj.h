#pragma once
// Wavefront OBJ free-form geometry (OBJ spec, "Free-form curve/surface
// attributes"): control vertices `v x y z [w]`, then
//   cstype bspline | cstype rat bspline    (rat when any weight != 1)
//   deg p [q]
//   curv t0 t1 i1 i2 ...  |  surf u0 u1 v0 v1 i1 i2 ...  (u varies fastest)
//   parm u knots...  [parm v knots...]
//   end
// which CAD programs (e.g. Rhino, Blender's importer) read as exact NURBS.
// Files appear whole or not at all (AtomicFileWriter).

#include <filesystem>
#include <string>

#include "sculpt/base/result.h"
#include "sculpt/core/nurbs/nurbs_curve.h"
#include "sculpt/core/nurbs/nurbs_surface.h"

namespace sculpt::core::nurbs {

std::string to_freeform_obj(const NurbsSurface& surface);
std::string to_freeform_obj(const NurbsCurve& curve);

Status write_freeform_obj(const std::filesystem::path& path, const NurbsSurface& surface);
Status write_freeform_obj(const std::filesystem::path& path, const NurbsCurve& curve);

}  // namespace sculpt::core::nurbs
