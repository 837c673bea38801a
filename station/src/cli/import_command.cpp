// sculpt import IN.{vdb,nrrd,glb,ply,obj,stl} -o OUT.{nrrd,vdb}
//               [--size N | --voxel-mm S [--unit-mm U]] [--margin M] [--sdf]
//
// Brings work from other programs in as a volume the station sculpts, the
// way File > Import works in Blender or Houdini: the input's extension picks
// the reader. A volume (.vdb from Blender or Houdini: its "density" grid,
// else its level set; or NRRD, with --window for CT data) is converted as it
// is, keeping its grid; a closed mesh is voxelized by voxelize_to_output(),
// the code of `sculpt voxelize`, to a grid of --size N or of voxels
// --voxel-mm S wide.

#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/field_options.h"
#include "cli/number_checks.h"
#include "sculpt/core/files/mesh_file.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::station::cli {
namespace {

struct ImportOptions {
  VoxelizeCliOptions voxelize;  ///< input, output and the mesh's grid
  DensityOptions density;
  bool grid_options = false;     ///< --size, --voxel-mm, --unit-mm, --margin or --sdf given
  bool density_options = false;  ///< --window or --data-iso given
};

int run_import(const ImportOptions& i) {
  const VoxelizeCliOptions& o = i.voxelize;
  if (!is_volume_file_name(o.output))
    return report(Error(o.output + ": import writes a volume (.nrrd, .vdb); `sculpt export` "
                                   "writes meshes"));
  if (core::is_mesh_file_name(o.input)) {
    if (i.density_options)
      return report(Error(o.input + ": --window and --data-iso apply to a volume input"));
    return voxelize_to_output(o);
  }
  if (!is_volume_file_name(o.input))
    return report(Error(o.input + ": import reads a volume (.vdb, .nrrd) or a mesh (.glb, .ply, "
                                  ".obj, .stl), chosen by the extension"));
  if (i.grid_options)
    return report(Error(o.input +
                        ": a volume is imported on its own grid; --size, --voxel-mm, --unit-mm, "
                        "--margin and --sdf apply to a mesh input (`sculpt distance` makes a "
                        "volume's distance field)"));
  core::VolumeOptions vo;
  vo.threads = o.threads;
  auto volume = read_volume_input(o.input, i.density, vo);
  if (!volume) return report(volume.error());
  return write_volume_level("import", o.output, *volume, 0);
}

}  // namespace

void add_import_command(CLI::App& app, Action& action) {
  auto i = std::make_shared<ImportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "import",
      "Bring a volume (.vdb, .nrrd) or a closed mesh (.glb, .ply, .obj, .stl: voxelized) in as "
      "a volume to sculpt");
  cmd->add_option("input", i->voxelize.input,
                  "volume: .vdb (its density grid, else its level set) or .nrrd; mesh: .glb "
                  "(glTF 2.0 binary), .ply, .obj or .stl, closed")
      ->required()
      ->check(input_file());
  cmd->add_option("-o,--output", i->voxelize.output, "output volume (.nrrd or .vdb)")->required();
  add_voxelize_grid_options(cmd, i->voxelize);
  add_density_options(cmd, i->density);
  cmd->callback([i, cmd, &action] {
    auto given = [cmd](const char* name) { return cmd->get_option(name)->count() > 0; };
    i->grid_options = given("--size") || given("--voxel-mm") || given("--unit-mm") ||
                      given("--margin") || given("--sdf");
    i->density_options = given("--window") || given("--data-iso");
    action = [i] { return run_import(*i); };
  });
}

}  // namespace sculpt::station::cli
