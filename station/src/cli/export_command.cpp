// sculpt export IN.{nrrd,vdb}|SESSION -o OUT.{vdb,nrrd,ply,obj,stl,glb}
//               [--iso V] [--lod K] [--simplify R] [--max-error E] [--check [--voxel-mm S]]
//
// One command for "get my sculpture out", the way File > Export works in
// Blender or Houdini: the output's extension picks what is written. A volume
// extension writes the volume (level K with --lod), a mesh extension its
// iso-surface. The work is the other commands' own, not a copy: a volume
// goes through mesh_to_output() (`sculpt mesh`) or write_volume_level()
// (`sculpt wavelet --lod`); a session (.scs, .jsonl) is replayed as fast as
// it can by replay_to_outputs() (`sculpt replay --fast`), so an export of a
// session is the sculpture the station showed.

#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/field_options.h"
#include "cli/mesh_export_options.h"
#include "cli/number_checks.h"
#include "sculpt/core/mesh/mesh_io.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::station::cli {
namespace {

struct ExportOptions {
  MeshCliOptions mesh;  ///< input, output, iso, lod, threads, density, mesh export options
  bool mesh_only_options = false;    ///< --iso, --simplify, ... given
  bool volume_only_options = false;  ///< --window, --data-iso, --iso, --lod given
};

bool is_session_file_name(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".scs" || ext == ".jsonl";
}

int export_session(const ExportOptions& e, bool volume_out) {
  const MeshCliOptions& o = e.mesh;
  if (e.volume_only_options)
    return report(Error(o.input +
                        ": a session exports the sculpture the station made; --iso, --lod, "
                        "--window and --data-iso apply to a volume input"));
  ReplayCliOptions r;
  r.session = o.input;
  r.fast = true;
  r.threads = o.threads;
  (volume_out ? r.volume : r.mesh) = o.output;
  r.mesh_export = o.mesh;
  return replay_to_outputs(r);
}

int run_export(const ExportOptions& e) {
  const MeshCliOptions& o = e.mesh;
  const bool volume_out = is_volume_file_name(o.output);
  if (!volume_out && !core::mesh_format_for(o.output).ok())
    return report(Error(o.output +
                        ": export writes a volume (.vdb, .nrrd) or a mesh (.ply, .obj, .stl, "
                        ".glb), chosen by the extension"));
  if (volume_out && e.mesh_only_options)
    return report(Error(o.output +
                        ": --iso, --simplify, --max-error, --check and --ascii apply to a mesh "
                        "output (.ply, .obj, .stl, .glb)"));
  if (is_session_file_name(o.input)) return export_session(e, volume_out);
  if (!is_volume_file_name(o.input))
    return report(Error(o.input +
                        ": export reads a volume (.nrrd, .vdb) or a session (.scs, .jsonl); "
                        "`sculpt import` brings a mesh in, `sculpt mesh --check` checks one"));
  if (!volume_out) return mesh_to_output(o);
  core::VolumeOptions vo;
  vo.threads = o.threads;
  auto volume = read_volume_input(o.input, o.density, vo);
  if (!volume) return report(volume.error());
  return write_volume_level("export", o.output, *volume, o.lod);
}

}  // namespace

void add_export_command(CLI::App& app, Action& action) {
  auto e = std::make_shared<ExportOptions>();
  MeshCliOptions& o = e->mesh;
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Write a volume or a session for other programs: .vdb (Blender, Houdini), .nrrd, or "
      "its surface as .glb, .ply, .obj, .stl (by OUT's extension)");
  cmd->add_option("input", o.input,
                  "volume (.nrrd, .vdb) or session (.scs, .jsonl: replayed, its sculpture "
                  "exported)")
      ->required()
      ->check(input_file());
  cmd->add_option("-o,--output", o.output,
                  "volume .vdb (OpenVDB: density fog volume and surface level set) or .nrrd; "
                  "mesh .glb (glTF 2.0), .ply, .obj or .stl")
      ->required();
  add_density_options(cmd, o.density);
  cmd->add_option("--iso", o.iso, "mesh: iso-level in density units, 0 <= V < 255 (default 127.5)")
      ->check(finite_range(0.0f, 254.999f));
  cmd->add_option("--lod", o.lod, "level of detail: 0 = full resolution .. 5 = 1/32")
      ->check(finite_range(0, 5));
  add_mesh_export_options(cmd, o.mesh);
  add_threads_option(cmd, o.threads);
  cmd->callback([e, cmd, &action] {
    auto given = [cmd](const char* name) { return cmd->get_option(name)->count() > 0; };
    e->mesh_only_options = given("--iso") || given("--simplify") || given("--max-error") ||
                           given("--check") || given("--ascii");
    e->volume_only_options =
        given("--iso") || given("--lod") || given("--window") || given("--data-iso");
    action = [e] { return run_export(*e); };
  });
}

}  // namespace sculpt::station::cli
