// sculpt devices [--json] [--device opentrack[:PORT] | vrpn:NAME@HOST[:PORT]]...
//
// Lists what each HAL backend sees (name, vendor:product, backend, path,
// serial) without opening anything (network trackers only when a --device
// names them: they are never looked for uninvited); when nothing is found, says why:
// nothing attached, no permission (with the udev hint), backend not built or
// unavailable. Exit 0 when at least one backend could enumerate, even if it
// found nothing; 1 when none could.

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "sculpt/hal/backends/evdev_ff_backend.h"
#include "sculpt/hal/backends/falcon_backend.h"
#include "sculpt/hal/backends/openxr_backend.h"
#include "sculpt/hal/registry/device_registry.h"
#include "sculpt/hal/registry/force_devices.h"
#include "sculpt/hal/registry/tracker_backends.h"
#include "sculpt/hal/types/quirks.h"

namespace sculpt::station::cli {
namespace {

constexpr const char* kUdevHint =
    "install the udev rules: sudo cmake --install build --component udev && "
    "sudo udevadm control --reload && sudo udevadm trigger, then re-plug the device";

struct DevicesOptions {
  bool json = false;
  std::vector<std::string> trackers;  ///< --device specs of trackers to list too
};

const char* state_name(hal::BackendState s) {
  switch (s) {
    case hal::BackendState::kReady:
      return "ready";
    case hal::BackendState::kNotBuilt:
      return "not built";
    case hal::BackendState::kUnavailable:
      return "unavailable";
  }
  return "?";
}

std::string hex4(uint16_t v) {
  char b[8];
  std::snprintf(b, sizeof b, "%04x", v);
  return b;
}

int run_devices(const DevicesOptions& o) {
  hal::DeviceRegistry registry(hal::DeviceRegistry::default_backends());
  for (const std::string& spec : o.trackers) {
    if (!hal::names_tracker(spec))
      return report(Error("--device " + spec +
                          ": not a tracker (want opentrack[:PORT], "
                          "vrpn:NAME@HOST[:PORT] or openxr[:left|right]; other devices are listed "
                          "without --device)"));
    if (auto added = hal::add_named_tracker(registry, spec); !added) return report(added.error());
  }
  // OpenXR is listed (its runtime, or "no OpenXR runtime") but, like the
  // trackers, opened only with --device openxr.
  if (std::none_of(o.trackers.begin(), o.trackers.end(),
                   [](const std::string& s) { return s.rfind("openxr", 0) == 0; }))
    registry.add_backend(hal::make_openxr_backend());
  const std::vector<hal::BackendListing> listing = registry.list();
  int working = 0;
  size_t found = 0;
  size_t no_permission = 0;
  for (const hal::BackendListing& l : listing) {
    if (l.status.state == hal::BackendState::kReady && l.error.empty()) ++working;
    found += l.devices.size();
    for (const hal::DeviceInfo& d : l.devices)
      no_permission += !d.accessible;
  }
  // Force devices (DESIGN.md §5a) are listed apart: they are opened with
  // `sculpt run --haptic ID`, beside the pointing device.
  struct ForceBackend {
    std::string name;
    hal::BackendStatus status;
  };
  const std::vector<ForceBackend> force_backends = {{"falcon", hal::falcon_backend_status()},
                                                    {"evdev-ff", hal::evdev_ff_backend_status()}};
  std::vector<std::string> force_problems;
  const std::vector<hal::DeviceInfo> force = hal::list_force_devices(&force_problems);
  std::string summary;
  if (working == 0) {
    summary = "no backend could enumerate devices";
  } else if (found == 0) {
    summary = "no 6-DOF device attached (enumeration works)";
  } else if (no_permission > 0) {
    summary = std::to_string(no_permission) + " device(s) without permission: " + kUdevHint;
  } else {
    summary = std::to_string(found) + " device(s) found";
  }

  if (o.json) {
    nlohmann::json j;
    j["backends"] = nlohmann::json::array();
    for (const hal::BackendListing& l : listing) {
      nlohmann::json b;
      b["name"] = l.backend;
      b["state"] = state_name(l.status.state);
      b["note"] = l.error.empty() ? l.status.note : l.error;
      b["devices"] = nlohmann::json::array();
      for (const hal::DeviceInfo& d : l.devices) {
        b["devices"].push_back({{"name", d.name},
                                {"vendor_id", hex4(d.vendor_id)},
                                {"product_id", hex4(d.product_id)},
                                {"vendor_product", d.vendor_product()},
                                {"backend", d.backend},
                                {"path", d.path},
                                {"id", d.id()},
                                {"serial", d.serial},
                                {"manufacturer", d.manufacturer},
                                {"usb_location", d.usb_location},
                                {"known", hal::find_quirks(d.vendor_id, d.product_id) != nullptr},
                                {"accessible", d.accessible}});
      }
      j["backends"].push_back(std::move(b));
    }
    j["force_backends"] = nlohmann::json::array();
    for (const ForceBackend& fb : force_backends) {
      nlohmann::json f;
      f["name"] = fb.name;
      f["state"] = state_name(fb.status.state);
      f["note"] = fb.status.note;
      f["devices"] = nlohmann::json::array();
      for (const hal::DeviceInfo& d : force) {
        if (d.backend != fb.name) continue;
        f["devices"].push_back({{"name", d.name},
                                {"vendor_product", d.vendor_product()},
                                {"id", d.id()},
                                {"usb_location", d.usb_location},
                                {"accessible", d.accessible}});
      }
      j["force_backends"].push_back(std::move(f));
    }
    j["force_problems"] = force_problems;
    j["devices_found"] = found;
    j["summary"] = summary;
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    for (const hal::BackendListing& l : listing) {
      std::string line = l.backend + ": " + state_name(l.status.state);
      if (!l.error.empty()) {
        line += ", enumeration failed: " + l.error;
      } else if (!l.status.note.empty()) {
        line += " (" + l.status.note + ")";
      } else {
        line += l.devices.empty() ? ", nothing attached"
                                  : ", " + std::to_string(l.devices.size()) + " device(s)";
      }
      std::printf("%s\n", line.c_str());
      for (const hal::DeviceInfo& d : l.devices) {
        std::printf("  %-34s %s  %-7s %-24s serial %s%s\n", d.name.c_str(),
                    d.vendor_product().c_str(), d.backend.c_str(), d.path.c_str(),
                    d.serial.empty() ? "-" : d.serial.c_str(),
                    d.accessible ? "" : "  [no permission]");
      }
    }
    for (const ForceBackend& fb : force_backends) {
      std::string line = fb.name + " (force, --haptic): " + state_name(fb.status.state);
      size_t n = 0;
      for (const hal::DeviceInfo& d : force)
        n += d.backend == fb.name;
      if (!fb.status.note.empty()) {
        line += " (" + fb.status.note + ")";
      } else {
        line += n == 0 ? ", nothing attached" : ", " + std::to_string(n) + " device(s)";
      }
      std::printf("%s\n", line.c_str());
      for (const hal::DeviceInfo& d : force)
        if (d.backend == fb.name)
          std::printf("  %-34s %s  --haptic %s%s\n", d.name.c_str(), d.vendor_product().c_str(),
                      d.id().c_str(), d.accessible ? "" : "  [no permission]");
    }
    for (const std::string& p : force_problems)
      std::printf("  listing failed: %s\n", p.c_str());
    std::printf("%s\n", summary.c_str());
  }
  if (working == 0) {
    std::fprintf(stderr,
                 "sculpt: devices: no backend could enumerate devices (see the lines above)\n");
    return 1;
  }
  return 0;
}

}  // namespace

void add_devices_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<DevicesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "devices", "List the 6-DOF devices each backend (spnav, hidapi, evdev, libusb, openxr) sees");
  cmd->add_flag("--json", o->json, "machine-readable output");
  cmd->add_option("--device", o->trackers,
                  "list this network tracker too: opentrack[:PORT] or vrpn:NAME@HOST[:PORT] "
                  "(nothing is opened)");
  cmd->callback([o, &action] { action = [o] { return run_devices(*o); }; });
}

}  // namespace sculpt::station::cli
