#include "sculpt/station/app/session_loading.h"

#include <cstring>
#include <fstream>
#include <sstream>

#include "sculpt/base/input_file.h"
#include "sculpt/sim/session/session_text.h"

namespace sculpt::station {

Result<sim::Session> load_session(const std::filesystem::path& path, sim::SessionReadInfo* info) {
  // A sim device's FILE comes from the device string, not a checked option.
  if (const Status s = check_input_file(path); !s) return s.error();
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error(path.string() + ": cannot open: " + std::strerror(errno));
  char magic[sizeof(sim::kSessionMagic)] = {};
  in.read(magic, sizeof magic);
  if (in.gcount() == sizeof magic && std::memcmp(magic, sim::kSessionMagic, sizeof magic) == 0) {
    return sim::read_session_file(path, info);
  }
  in.clear();
  in.seekg(0);
  std::stringstream text;
  text << in.rdbuf();
  return sim::session_from_text(text.str(), path.string());
}

}  // namespace sculpt::station
