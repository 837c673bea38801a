#include "sculpt/hal/registry/tracker_backends.h"

#include "sculpt/hal/backends/opentrack_backend.h"
#include "sculpt/hal/backends/openxr_backend.h"
#include "sculpt/hal/backends/vrpn_backend.h"
#include "sculpt/hal/registry/device_registry.h"

namespace sculpt::hal {

bool names_tracker(std::string_view device_spec) {
  return device_spec == "opentrack" || device_spec.rfind("opentrack:", 0) == 0 ||
         device_spec.rfind("vrpn:", 0) == 0 || device_spec == "openxr" ||
         device_spec.rfind("openxr:", 0) == 0;
}

Result<std::unique_ptr<Backend>> make_tracker_backend(const std::string& device_spec,
                                                      const std::string& listen_address) {
  if (device_spec.rfind("vrpn:", 0) == 0) {
    auto options = parse_vrpn_spec(device_spec);
    if (!options) return options.error();
    return make_vrpn_backend(std::move(options).value());
  }
  if (device_spec == "openxr" || device_spec.rfind("openxr:", 0) == 0) {
    auto options = parse_openxr_spec(device_spec);
    if (!options) return options.error();
    return make_openxr_backend(std::move(options).value());
  }
  if (names_tracker(device_spec)) {
    auto options = parse_opentrack_spec(device_spec);
    if (!options) return options.error();
    options->listen_address = listen_address;
    return make_opentrack_backend(std::move(options).value());
  }
  return Error(
      device_spec +
      ": not a tracker (want opentrack[:PORT], vrpn:NAME@HOST[:PORT] or openxr[:left|right])");
}

Result<std::string> add_named_tracker(DeviceRegistry& registry, const std::string& device_spec,
                                      const std::string& listen_address) {
  if (!names_tracker(device_spec)) return device_spec;
  auto backend = make_tracker_backend(device_spec, listen_address);
  if (!backend) return Error("--device " + backend.error().message());  // it names the spec
  // The backend's name opens its one device: the spec the user typed may
  // leave out what the device's id spells in full (VRPN's default port).
  std::string id((*backend)->name());
  registry.add_backend(std::move(backend).value());
  return id;
}

}  // namespace sculpt::hal
