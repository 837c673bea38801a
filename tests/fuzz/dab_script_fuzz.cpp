// libFuzzer target: dab scripts (`sculpt stamp --dabs`), JSON Lines read
// field by field. Seeds: corpus/dab_script (the bundled example script).

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "sculpt/station/project/dab_script.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  (void)sculpt::station::dab_script::parse(in, "fuzz.jsonl", glm::ivec3(96, 80, 64));
  return 0;
}
