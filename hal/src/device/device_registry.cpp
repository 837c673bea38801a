#include "sculpt/hal/device/device_registry.h"

#include "sculpt/hal/backends/hidapi_backend.h"
#include "sculpt/hal/backends/libusb_backend.h"
#include "sculpt/hal/backends/spnav_backend.h"
#include "sculpt/hal/device/quirks.h"
#include "sculpt/hal/parsers/make_parser.h"

namespace sculpt::hal {
namespace {

// spacenavd names no USB location; while it owns a device, the same
// vendor:product is not opened again through a raw transport.
std::string spnav_claim(const DeviceInfo& info) {
  return "spnav-owns:" + info.vendor_product();
}

}  // namespace

DeviceRegistry::DeviceRegistry(std::vector<std::unique_ptr<Backend>> backends,
                               NormalizerConfig config, ReaderOptions options)
    : backends_(std::move(backends)), config_(config), options_(options) {}

DeviceRegistry::~DeviceRegistry() {
  // Readers first: their devices may belong to a backend's library state.
  readers_.clear();
}

std::vector<std::unique_ptr<Backend>> DeviceRegistry::default_backends() {
  std::vector<std::unique_ptr<Backend>> b;
  b.push_back(make_spnav_backend());
  b.push_back(make_hidapi_backend());
  b.push_back(make_libusb_backend());
  return b;
}

std::vector<BackendListing> DeviceRegistry::list() {
  std::vector<BackendListing> out;
  for (auto& backend : backends_) {
    BackendListing l;
    l.backend = std::string(backend->name());
    l.status = backend->status();
    if (l.status.state == BackendState::kReady) {
      auto devices = backend->enumerate();
      if (devices) {
        l.devices = std::move(devices).value();
      } else {
        l.error = devices.error().message();
      }
    }
    out.push_back(std::move(l));
  }
  return out;
}

ScanReport DeviceRegistry::scan() {
  ScanReport report;
  for (auto& backend : backends_) {
    const std::string name(backend->name());
    if (backend->status().state != BackendState::kReady) continue;
    if (backend->changed() || !last_seen_.count(name)) {
      auto devices = backend->enumerate();
      if (!devices) {
        report.errors.push_back(devices.error().message());
        continue;
      }
      last_seen_[name] = std::move(devices).value();
    }
    for (const DeviceInfo& info : last_seen_[name]) {
      if (is_ignored(info.vendor_id, info.product_id, info.usage_page, info.usage)) continue;
      const std::string key = info.physical_key();
      if (open_keys_.count(key) || (name != "spnav" && open_keys_.count(spnav_claim(info))))
        continue;
      if (!info.accessible) {
        report.errors.push_back(info.id() + " (" + info.vendor_product() +
                                "): no permission; install the udev rules (see README: Devices)");
        continue;
      }
      auto device = backend->open(info);
      if (!device) {
        report.errors.push_back(device.error().message());
        continue;
      }
      auto parser = make_parser((*device)->info());
      if (!parser) {
        report.errors.push_back(parser.error().message());
        continue;
      }
      const uint32_t id = next_id_++;
      auto reader = std::make_unique<DeviceReader>(
          id, std::move(device).value(), MotionPipeline(std::move(parser).value(), config_),
          options_);
      reader->start();
      open_keys_[key] = id;
      if (name == "spnav") open_keys_[spnav_claim(info)] = id;
      readers_[id] = std::move(reader);
      report.opened.push_back(id);
    }
  }
  return report;
}

void DeviceRegistry::poll(InputFrame& frame, int64_t now_ns) {
  for (auto it = readers_.begin(); it != readers_.end();) {
    it->second->poll(frame, now_ns);
    if (!it->second->finished()) {
      ++it;
      continue;
    }
    const uint32_t id = it->first;
    for (auto k = open_keys_.begin(); k != open_keys_.end();) {
      k = k->second == id ? open_keys_.erase(k) : std::next(k);
    }
    it = readers_.erase(it);
  }
}

const DeviceReader* DeviceRegistry::reader(uint32_t device_id) const {
  const auto it = readers_.find(device_id);
  return it == readers_.end() ? nullptr : it->second.get();
}

}  // namespace sculpt::hal
