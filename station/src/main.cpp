// The `sculpt` executable: one command with subcommands (DESIGN.md §7).

#include <exception>
#include <new>
#include <string>

#include "cli/commands.h"
#include "sculpt/base/temp_files.h"

int main(int argc, char** argv) {
  namespace cli = sculpt::station::cli;
  // Ctrl-C or a kill while an output is being written leaves no temporary.
  sculpt::remove_temp_files_on_signals();
  CLI::App app{"sculpt: a virtual sculpting station for 6-DOF input devices", "sculpt"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "sculpt 0.1.0");
  cli::Action action;
  cli::add_run_command(app, action);
  cli::add_wavelet_command(app, action);
  cli::add_bench_command(app, action);
  cli::add_devices_command(app, action);
  cli::add_mesh_command(app, action);
  cli::add_rotate_command(app, action);
  cli::add_stamp_command(app, action);
  cli::add_replay_command(app, action);
  cli::add_session_command(app, action);
  cli::add_record_command(app, action);
  cli::add_distance_command(app, action);
  cli::add_voxelize_command(app, action);
  cli::add_close_command(app, action);
  cli::add_offset_command(app, action);
  cli::add_contours_command(app, action);
  cli::add_nurbs_command(app, action);
  cli::add_haptics_command(app, action);
  cli::add_export_command(app, action);
  cli::add_import_command(app, action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ValidationError& e) {
    // A value out of range or not a number is bad input: one line, exit 1.
    return cli::report(sculpt::Error(e.what()));
  } catch (const CLI::ConversionError& e) {
    return cli::report(sculpt::Error(e.what()));
  } catch (const CLI::ArgumentMismatch& e) {
    // An option given the wrong number of values ("--friction 0.2").
    return cli::report(sculpt::Error(e.what()));
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; everything else (an unknown command or
    // option, a missing argument) is a usage error, exit 2.
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    return action ? action() : 2;
  } catch (const std::bad_alloc&) {
    // The inputs are on the command line: name it, not the allocator.
    std::string command = "sculpt";
    for (int i = 1; i < argc; ++i)
      command += std::string(" ") + argv[i];
    return cli::report(sculpt::Error("out of memory running `" + command +
                                     "`: an input asks for more than this machine holds"));
  } catch (const std::exception& e) {
    // Out of memory and the like: still one line and a clean exit.
    return cli::report(sculpt::Error(e.what()));
  }
}
