// sculpt nurbs deform|tessellate|invert|example
//
// The NURBS deformation of La Greca, Raffin & Gesquière from the command
// line: a linear punctual constraint (§4.2, equation (2)) or a path
// constraint (§4.3) on a surface read from JSON, with natural, Gaussian or
// zone influence, optional refinement of the control net inside the zone,
// and the result written as JSON plus, if asked, a tessellated mesh.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "cli/commands.h"
#include "cli/number_checks.h"
#include "sculpt/base/output_set.h"
#include "sculpt/core/mesh/mesh_io.h"
#include "sculpt/core/nurbs/influence.h"
#include "sculpt/core/nurbs/nurbs_json.h"
#include "sculpt/core/nurbs/nurbs_obj.h"
#include "sculpt/core/nurbs/path_deformation.h"
#include "sculpt/core/nurbs/point_inversion.h"
#include "sculpt/core/nurbs/punctual_constraint.h"
#include "sculpt/core/nurbs/surface_tessellator.h"

namespace sculpt::station::cli {
namespace {

namespace nurbs = core::nurbs;

struct DeformOptions {
  std::string input;
  std::vector<double> uv;
  std::vector<double> pick;
  std::vector<double> to;
  std::string influence = "natural";
  int refine = 0;
  std::string path;
  int steps = 0;
  bool no_rotate = false;
  std::string output;
  std::string mesh;
  int per_span = 8;
};

// "natural", "gaussian:R" or "zone:FILE"; malformed specs are usage errors.
std::string check_influence(const std::string& spec) {
  if (spec == "natural") return "";
  if (spec.rfind("gaussian:", 0) == 0) {
    try {
      size_t used = 0;
      const double r = std::stod(spec.substr(9), &used);
      if (used == spec.size() - 9 && r >= 0.0 && std::isfinite(r)) return "";
    } catch (const std::exception&) {
    }
    return "gaussian:R needs a radius R >= 0 in control-point index units, got " + spec;
  }
  if (spec.rfind("zone:", 0) == 0 && spec.size() > 5) return "";
  return "expected natural, gaussian:R or zone:FILE, got " + spec;
}

std::string vec3(glm::dvec3 p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g)", p.x, p.y, p.z);
  return text;
}

bool finite(const std::vector<double>& v) {
  for (double x : v) {
    if (!std::isfinite(x)) return false;
  }
  return true;
}

Status write_mesh_output(const std::string& path, const nurbs::NurbsSurface& s, int per_span,
                         size_t* triangles) {
  auto format = core::mesh_format_for(path);
  if (!format) return format.error();
  const core::Mesh mesh = nurbs::tessellate(s, per_span);
  *triangles = mesh.triangles.size();
  return core::write_mesh(path, mesh, *format);
}

int run_deform(const DeformOptions& o) {
  using clock = std::chrono::steady_clock;
  if (o.to.empty() && o.path.empty()) {
    std::fprintf(stderr,
                 "sculpt nurbs deform: give the target with --to X,Y,Z or --path CURVE.json\n");
    return 2;
  }
  if (o.uv.empty() == o.pick.empty()) {
    std::fprintf(stderr, "sculpt nurbs deform: give exactly one of --uv U,V and --pick X,Y,Z\n");
    return 2;
  }
  if (!finite(o.uv) || !finite(o.pick) || !finite(o.to)) {
    return report(Error("--uv, --pick and --to take finite numbers"));
  }
  if (!o.mesh.empty()) {
    if (auto f = core::mesh_format_for(o.mesh); !f) return report(f.error());
  }
  if (o.refine > 0 && o.influence.rfind("zone:", 0) != 0) {
    return report(Error("--refine: refinement works inside a zone (--influence zone:FILE)"));
  }
  Result<nurbs::NurbsSurface> read = nurbs::read_surface_json(o.input);
  if (!read) return report(read.error());
  nurbs::NurbsSurface surface = std::move(read.value());
  const int points_before = surface.point_count();

  double u = 0.0, v = 0.0;
  if (!o.uv.empty()) {
    u = o.uv[0];
    v = o.uv[1];
    if (!(u >= surface.u_min() && u <= surface.u_max() && v >= surface.v_min() &&
          v <= surface.v_max())) {
      char text[200];
      std::snprintf(text, sizeof text, "--uv %g,%g: outside the domain [%g, %g] x [%g, %g] of %s",
                    u, v, surface.u_min(), surface.u_max(), surface.v_min(), surface.v_max(),
                    o.input.c_str());
      return report(Error(text));
    }
  } else {
    const nurbs::SurfacePoint hit =
        nurbs::closest_point(surface, {o.pick[0], o.pick[1], o.pick[2]});
    u = hit.u;
    v = hit.v;
    std::printf("picked      (u, v) = (%.9g, %.9g), %.6g from the given point\n", u, v,
                hit.distance);
  }

  std::optional<nurbs::NurbsCurve> path;
  if (!o.path.empty()) {
    Result<nurbs::NurbsCurve> c = nurbs::read_curve_json(o.path);
    if (!c) return report(c.error());
    path = std::move(c.value());
  }
  const glm::dvec3 start = nurbs::evaluate(surface, u, v);
  glm::dvec3 target = path ? nurbs::evaluate(*path, path->domain_max()) : glm::dvec3(0.0);
  if (!o.to.empty()) {
    const glm::dvec3 to(o.to[0], o.to[1], o.to[2]);
    if (path && glm::length(to - target) > 1e-6 * std::max(1.0, glm::length(target))) {
      return report(
          Error(o.path + ": the path ends at " + vec3(target) + ", not at --to " + vec3(to)));
    }
    target = to;
  }

  const auto t0 = clock::now();
  std::vector<double> f;
  const std::string& spec = o.influence;
  if (spec == "natural") {
    f = nurbs::natural_influence(surface, u, v);
  } else if (spec.rfind("gaussian:", 0) == 0) {
    f = nurbs::gaussian_influence(surface, u, v, std::stod(spec.substr(9)));
  } else {
    const std::string zone_file = spec.substr(5);
    Result<nurbs::ParameterZone> zone = nurbs::read_zone_json(zone_file);
    if (!zone) return report(zone.error());
    if (Status st = nurbs::validate(*zone, {u, v}); !st) return report(st.error().in(zone_file));
    if (o.refine > 0) {
      Result<nurbs::NurbsSurface> refined = nurbs::refine_in_zone(surface, u, v, *zone, o.refine);
      if (!refined) return report(refined.error().in(zone_file));
      surface = std::move(refined.value());
    }
    Result<std::vector<double>> zf = nurbs::zone_influence(surface, u, v, *zone);
    if (!zf) return report(zf.error().in(zone_file));
    f = std::move(zf.value());
  }
  const auto moving = std::count_if(f.begin(), f.end(), [](double x) { return x > 0.0; });

  int steps = 1;
  size_t moved = 0;
  if (path) {
    nurbs::PathOptions po;
    po.steps = o.steps;
    po.rotate = !o.no_rotate;
    Result<nurbs::PathDeformation> d =
        nurbs::PathDeformation::from_curve(surface, u, v, f, *path, po);
    if (!d) return report(d.error().in(o.path));
    moved = d->run().size();
    steps = d->step_count();
    surface = d->surface();
  } else {
    Result<std::vector<int>> m = nurbs::apply_linear_constraint(surface, u, v, target, f);
    if (!m) return report(m.error());
    moved = m->size();
  }
  const auto t1 = clock::now();
  const double residual = glm::length(nurbs::evaluate(surface, u, v) - target);

  // Both outputs or neither (a bad --mesh path must not leave -o written).
  OutputSet outputs;
  if (Status st = nurbs::write_json(outputs.stage(o.output), surface); !st) {
    return report(outputs.named(st.error()));
  }
  size_t triangles = 0;
  if (!o.mesh.empty()) {
    if (Status st = write_mesh_output(outputs.stage(o.mesh), surface, o.per_span, &triangles);
        !st) {
      return report(outputs.named(st.error()));
    }
  }
  if (Status st = outputs.commit(); !st) return report(st.error());
  std::printf("surface     degree %d x %d, %d control points", surface.degree_u, surface.degree_v,
              points_before);
  if (surface.point_count() != points_before) {
    std::printf(", refined to %d x %d = %d", surface.count_u, surface.count_v,
                surface.point_count());
  }
  std::printf("\nconstraint  S(%.9g, %.9g) = %s -> %s, influence %s (%lld control points)\n", u, v,
              vec3(start).c_str(), vec3(target).c_str(), spec.c_str(),
              static_cast<long long>(moving));
  if (path) {
    std::printf("path        %s, %d steps%s\n", o.path.c_str(), steps,
                o.no_rotate ? ", no rotation" : "");
  }
  std::printf("result      %zu control points moved, residual |S(u,v) - target| = %.3g\n", moved,
              residual);
  std::printf("time        %.3f ms\n", std::chrono::duration<double, std::milli>(t1 - t0).count());
  std::printf("wrote       %s", o.output.c_str());
  if (!o.mesh.empty()) std::printf(", %s (%zu triangles)", o.mesh.c_str(), triangles);
  std::printf("\n");
  return 0;
}

struct TessellateOptions {
  std::string input, output;
  int per_span = 8;
  bool freeform = false;
};

int run_tessellate(const TessellateOptions& o) {
  if (o.freeform) {
    if (std::filesystem::path(o.output).extension() != ".obj") {
      return report(Error(o.output + ": --freeform writes OBJ; name the output .obj"));
    }
  } else if (auto f = core::mesh_format_for(o.output); !f) {
    return report(f.error());
  }
  Result<nurbs::NurbsSurface> s = nurbs::read_surface_json(o.input);
  if (!s) return report(s.error());
  if (o.freeform) {
    if (Status st = nurbs::write_freeform_obj(o.output, *s); !st) return report(st.error());
    std::printf("wrote       %s (OBJ free-form, %s, %d x %d control points)\n", o.output.c_str(),
                s->rational() ? "rat bspline" : "bspline", s->count_u, s->count_v);
    return 0;
  }
  size_t triangles = 0;
  if (Status st = write_mesh_output(o.output, *s, o.per_span, &triangles); !st) {
    return report(st.error());
  }
  std::printf("wrote       %s (%zu triangles, %d cells per knot span)\n", o.output.c_str(),
              triangles, o.per_span);
  return 0;
}

struct InvertOptions {
  std::string input;
  std::vector<double> point;
};

int run_invert(const InvertOptions& o) {
  if (!finite(o.point)) return report(Error("--point takes finite numbers"));
  Result<nurbs::NurbsSurface> s = nurbs::read_surface_json(o.input);
  if (!s) return report(s.error());
  const nurbs::SurfacePoint r = nurbs::closest_point(*s, {o.point[0], o.point[1], o.point[2]});
  std::printf("u %.17g\nv %.17g\npoint %.17g %.17g %.17g\ndistance %.17g\n", r.u, r.v, r.point.x,
              r.point.y, r.point.z, r.distance);
  return 0;
}

struct ExampleOptions {
  std::string output, curve, zone;
};

int run_example(const ExampleOptions& o) {
  const nurbs::NurbsSurface s = nurbs::example_sheet();
  if (Status st = nurbs::write_json(o.output, s); !st) return report(st.error());
  std::printf("wrote       %s (15 x 10 bicubic sheet, 140 x 90)\n", o.output.c_str());
  if (!o.curve.empty()) {
    // An arch from S(0.5, 0.5): up, over and down to the side (Figure 11).
    glm::dvec3 a = nurbs::evaluate(s, 0.5, 0.5);
    // Rounding leaves ~1e-32 where the sheet crosses z = 0; C(0) may differ
    // from S(u,v) by far more (PathOptions::start_tolerance).
    for (int k = 0; k < 3; ++k)
      a[k] = std::abs(a[k]) < 1e-12 ? 0.0 : a[k];
    nurbs::NurbsCurve c;
    c.degree = 3;
    c.knots = nurbs::uniform_clamped_knots(3, 5);
    c.points = {a, a + glm::dvec3(0, 0, 30), a + glm::dvec3(15, 0, 45), a + glm::dvec3(30, 5, 30),
                a + glm::dvec3(35, 10, 10)};
    if (Status st = nurbs::write_json(o.curve, c); !st) return report(st.error());
    std::printf("wrote       %s (path from S(0.5, 0.5) to %s)\n", o.curve.c_str(),
                vec3(c.points.back()).c_str());
  }
  if (!o.zone.empty()) {
    nurbs::ParameterZone z;
    z.centre = {0.5, 0.5};
    z.radius = 0.3;
    if (Status st = nurbs::write_json(o.zone, z); !st) return report(st.error());
    std::printf("wrote       %s (circle of radius 0.3 about (0.5, 0.5))\n", o.zone.c_str());
  }
  return 0;
}

}  // namespace

void add_nurbs_command(CLI::App& app, Action& action) {
  CLI::App* nurbs_cmd = app.add_subcommand(
      "nurbs", "NURBS surfaces: punctual and path constraints (La Greca, Raffin, Gesquiere)");
  nurbs_cmd->require_subcommand(1);

  auto d = std::make_shared<DeformOptions>();
  CLI::App* deform = nurbs_cmd->add_subcommand(
      "deform", "move S(u,v) to a target, straight (equation 2) or along a path curve");
  deform->add_option("surface", d->input, "surface JSON")->required()->check(input_file());
  deform->add_option("--uv", d->uv, "U,V: parameters of the constrained point")
      ->delimiter(',')
      ->expected(2);
  deform->add_option("--pick", d->pick, "X,Y,Z: constrain the surface point closest to this")
      ->delimiter(',')
      ->expected(3);
  deform->add_option("--to", d->to, "X,Y,Z: target of S(u,v) (default: the path's end)")
      ->delimiter(',')
      ->expected(3);
  deform
      ->add_option("--influence", d->influence,
                   "natural (default), gaussian:R (R in control-point index units) or zone:FILE "
                   "(zone JSON in parameter space)")
      ->check([](const std::string& s) { return check_influence(s); });
  deform
      ->add_option("--refine", d->refine,
                   "with a zone: insert knots in it until it holds at least M control points")
      ->check(finite_range(0, 1000000));
  deform->add_option("--path", d->path, "path curve JSON, starting at S(u,v)");
  deform->add_option("--steps", d->steps, "path steps N (default 10 x degree x control points)")
      ->check(finite_range(1, 10000000));
  deform->add_flag("--no-rotate", d->no_rotate, "path: translate only, no rotation per step");
  deform->add_option("-o,--output", d->output, "deformed surface JSON")->required();
  deform->add_option("--mesh", d->mesh, "also write the tessellated result: .obj, .ply or .stl");
  deform->add_option("--per-span", d->per_span, "mesh cells per knot span (default 8)")
      ->check(finite_range(1, 256));
  deform->callback([d, &action] { action = [d] { return run_deform(*d); }; });

  auto t = std::make_shared<TessellateOptions>();
  CLI::App* tess =
      nurbs_cmd->add_subcommand("tessellate", "surface JSON to a mesh (or OBJ free-form)");
  tess->add_option("surface", t->input, "surface JSON")->required()->check(input_file());
  tess->add_option("-o,--output", t->output, ".obj, .ply or .stl")->required();
  tess->add_option("--per-span", t->per_span, "cells per knot span (default 8)")
      ->check(finite_range(1, 256));
  tess->add_flag("--freeform", t->freeform, "write exact OBJ free-form (cstype bspline) instead");
  tess->callback([t, &action] { action = [t] { return run_tessellate(*t); }; });

  auto i = std::make_shared<InvertOptions>();
  CLI::App* inv = nurbs_cmd->add_subcommand("invert", "closest surface point (u, v) to X,Y,Z");
  inv->add_option("surface", i->input, "surface JSON")->required()->check(input_file());
  inv->add_option("--point", i->point, "X,Y,Z")->required()->delimiter(',')->expected(3);
  inv->callback([i, &action] { action = [i] { return run_invert(*i); }; });

  auto e = std::make_shared<ExampleOptions>();
  CLI::App* ex = nurbs_cmd->add_subcommand(
      "example", "write the paper's 15 x 10 bicubic sheet (and a path and a zone)");
  ex->add_option("-o,--output", e->output, "surface JSON")->required();
  ex->add_option("--curve", e->curve, "also write an arch path from S(0.5, 0.5)");
  ex->add_option("--zone", e->zone, "also write a circular zone about (0.5, 0.5)");
  ex->callback([e, &action] { action = [e] { return run_example(*e); }; });
}

}  // namespace sculpt::station::cli
