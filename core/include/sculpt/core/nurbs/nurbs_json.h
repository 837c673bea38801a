#pragma once
// The JSON files of NURBS curves, surfaces and parameter zones (docs/formats.md,
// "NURBS files"; examples in docs/nurbs/).
//
// Surface:
//   {"type": "nurbs_surface", "degree_u": 3, "degree_v": 3,
//    "count_u": 15, "count_v": 10,
//    "knots_u": [count_u + degree_u + 1 numbers], "knots_v": [...],
//    "control_points": [[x, y, z], ...]   (count_u * count_v, u fastest:
//                                           P_ij is entry i + count_u * j),
//    "weights": [...]}                     (optional, one > 0 per point)
// Curve:
//   {"type": "nurbs_curve", "degree": 3, "knots": [...],
//    "control_points": [[x, y, z], ...], "weights": [...]}
// Zone (in parameter space):
//   {"type": "zone", "shape": "circle", "centre": [u, v], "radius": r}
//   {"type": "zone", "shape": "polygon", "points": [[u, v], ...]}
//
// "type" may be left out. Readers check the JSON, then validate(); an error
// names the file and the field. Writers print every number with 17
// significant digits, so a file read back gives the same doubles.

#include <filesystem>
#include <string>

#include "sculpt/base/result.h"
#include "sculpt/core/nurbs/nurbs_curve.h"
#include "sculpt/core/nurbs/nurbs_surface.h"
#include "sculpt/core/nurbs/parameter_zone.h"

namespace sculpt::core::nurbs {

/// Parse from text; errors carry no file name.
Result<NurbsSurface> parse_surface_json(const std::string& text);
Result<NurbsCurve> parse_curve_json(const std::string& text);
Result<ParameterZone> parse_zone_json(const std::string& text);

/// Read a file; errors start with the path.
Result<NurbsSurface> read_surface_json(const std::filesystem::path& path);
Result<NurbsCurve> read_curve_json(const std::filesystem::path& path);
Result<ParameterZone> read_zone_json(const std::filesystem::path& path);

std::string to_json(const NurbsSurface& surface);
std::string to_json(const NurbsCurve& curve);
std::string to_json(const ParameterZone& zone);

/// Written whole or not at all (AtomicFileWriter); errors name the path.
Status write_json(const std::filesystem::path& path, const NurbsSurface& surface);
Status write_json(const std::filesystem::path& path, const NurbsCurve& curve);
Status write_json(const std::filesystem::path& path, const ParameterZone& zone);

}  // namespace sculpt::core::nurbs
