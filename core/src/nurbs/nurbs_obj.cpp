// OBJ free-form export. Control vertex indices are 1-based and the surface's
// are listed u fastest, which is also our storage order.

#include "sculpt/core/nurbs/nurbs_obj.h"

#include <cstdio>

#include "sculpt/base/atomic_file.h"

namespace sculpt::core::nurbs {
namespace {

std::string num(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string vertex(glm::dvec3 p, double w, bool rational) {
  std::string s = "v";
  for (double x : {p.x, p.y, p.z})
    s.append(" ").append(num(x));
  if (rational) s.append(" ").append(num(w));
  return s + "\n";
}

std::string knots(const std::vector<double>& k) {
  std::string s;
  for (double x : k)
    s.append(" ").append(num(x));
  return s;
}

Status write_text(const std::filesystem::path& path, const std::string& text) {
  AtomicFileWriter out(path);
  if (!out.ok()) return out.error();
  out.write(text);
  return out.commit();
}

}  // namespace

std::string to_freeform_obj(const NurbsSurface& s) {
  const bool rational = s.rational();
  std::string t = "# NURBS surface, " + std::to_string(s.count_u) + " x " +
                  std::to_string(s.count_v) + " control points (sculpt nurbs)\n";
  for (int k = 0; k < s.point_count(); ++k) {
    t += vertex(s.points[static_cast<size_t>(k)], s.weight(k), rational);
  }
  t += rational ? "cstype rat bspline\n" : "cstype bspline\n";
  t += "deg " + std::to_string(s.degree_u) + " " + std::to_string(s.degree_v) + "\n";
  t +=
      "surf " + num(s.u_min()) + " " + num(s.u_max()) + " " + num(s.v_min()) + " " + num(s.v_max());
  for (int k = 1; k <= s.point_count(); ++k)
    t.append(" ").append(std::to_string(k));
  t += "\nparm u" + knots(s.knots_u) + "\nparm v" + knots(s.knots_v) + "\nend\n";
  return t;
}

std::string to_freeform_obj(const NurbsCurve& c) {
  const bool rational = c.rational();
  std::string t =
      "# NURBS curve, " + std::to_string(c.count()) + " control points (sculpt nurbs)\n";
  for (int k = 0; k < c.count(); ++k) {
    t += vertex(c.points[static_cast<size_t>(k)], c.weight(k), rational);
  }
  t += rational ? "cstype rat bspline\n" : "cstype bspline\n";
  t += "deg " + std::to_string(c.degree) + "\n";
  t += "curv " + num(c.domain_min()) + " " + num(c.domain_max());
  for (int k = 1; k <= c.count(); ++k)
    t.append(" ").append(std::to_string(k));
  t += "\nparm u" + knots(c.knots) + "\nend\n";
  return t;
}

Status write_freeform_obj(const std::filesystem::path& path, const NurbsSurface& s) {
  return write_text(path, to_freeform_obj(s));
}
Status write_freeform_obj(const std::filesystem::path& path, const NurbsCurve& c) {
  return write_text(path, to_freeform_obj(c));
}

}  // namespace sculpt::core::nurbs
