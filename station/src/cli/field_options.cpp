#include "cli/field_options.h"

#include "cli/number_checks.h"
#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/io/nrrd.h"

namespace sculpt::station::cli {

CLI::Option* add_threads_option(CLI::App* command, int& threads) {
  return command->add_option("--threads", threads, "threads (0 = all cores)")
      ->check(finite_range(0, 1024));
}

Status write_field(const std::string& path, const core::DenseGrid<float>& field,
                   bool as_distance) {
  return as_distance ? core::write_nrrd(path, field)
                     : core::write_nrrd(path, core::density_from_distance_field(field));
}

const char* field_kind(bool as_distance) {
  return as_distance ? "float32 signed distance" : "uint8 density";
}

}  // namespace sculpt::station::cli
