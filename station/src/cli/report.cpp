#include <iostream>

#include "cli/commands.h"

namespace sculpt::station::cli {

int report(const core::Error& error) {
  std::cerr << "sculpt: " << error.message() << "\n";
  return 1;
}

}  // namespace sculpt::station::cli
