#include "sculpt/hal/registry/device_registry.h"

#include <cctype>

#include "sculpt/hal/backends/evdev_backend.h"
#include "sculpt/hal/backends/hidapi_backend.h"
#include "sculpt/hal/backends/libusb_backend.h"
#include "sculpt/hal/backends/spnav_backend.h"
#include "sculpt/hal/parsers/make_parser.h"
#include "sculpt/hal/types/quirks.h"

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
    : backends_(std::move(backends)), config_(config), options_(std::move(options)) {
  if (!options_.doorbell) options_.doorbell = std::make_shared<Doorbell>();
}

DeviceRegistry::~DeviceRegistry() {
  // Readers first: their devices may belong to a backend's library state.
  readers_.clear();
}

std::vector<std::unique_ptr<Backend>> DeviceRegistry::default_backends() {
  std::vector<std::unique_ptr<Backend>> b;
  b.push_back(make_spnav_backend());
  b.push_back(make_hidapi_backend());
  // evdev needs no hidraw permission and detaches nothing, so it comes
  // before libusb, which takes the device from its kernel driver (and so
  // from evdev too); after hidapi, whose parsers know the devices' reports.
  b.push_back(make_evdev_backend());
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
  std::map<std::string, std::string> denied;  // physical key -> the first backend's complaint
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
        // Said at the end, and only if no later backend opens the device
        // (evdev may, where hidraw is not this user's).
        denied.emplace(key, info.id() + " (" + info.vendor_product() +
                                "): no permission; install the udev rules (see docs/devices.md)");
        continue;
      }
      auto id = start_reader(*backend, info);
      if (!id) {
        report.errors.push_back(id.error().message());
        continue;
      }
      report.opened.push_back(*id);
    }
  }
  for (const auto& [key, why] : denied) {
    if (!open_keys_.count(key)) report.errors.push_back(why);
  }
  return report;
}

Result<uint32_t> DeviceRegistry::start_reader(Backend& backend, const DeviceInfo& info) {
  auto device = backend.open(info);
  if (!device) return device.error();
  auto parser = make_parser((*device)->info());
  if (!parser) return parser.error();
  const uint32_t id = next_id_++;
  auto reader = std::make_unique<DeviceReader>(
      id, std::move(device).value(), MotionPipeline(std::move(parser).value(), config_), options_);
  reader->start();
  open_keys_[info.physical_key()] = id;
  if (backend.name() == "spnav") open_keys_[spnav_claim(info)] = id;
  readers_[id] = std::move(reader);
  return id;
}

void DeviceRegistry::add_backend(std::unique_ptr<Backend> backend, bool first) {
  backends_.insert(first ? backends_.begin() : backends_.end(), std::move(backend));
}

Result<uint32_t> DeviceRegistry::open_device(const std::string& id) {
  const size_t colon = id.find(':');
  const std::string head = id.substr(0, colon);
  const bool vendor_product = id.size() == 9 && colon == 4 &&
                              id.find_first_not_of("0123456789abcdefABCDEF:") == std::string::npos;
  std::string lower = id;
  for (char& ch : lower)
    ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  bool backend_named = false;
  std::vector<std::string> why;
  for (auto& backend : backends_) {
    const std::string name(backend->name());
    if (!vendor_product && name != head) continue;
    backend_named = true;
    const BackendStatus st = backend->status();
    if (st.state != BackendState::kReady) {
      why.push_back(name + ": " + st.note);
      continue;
    }
    auto devices = backend->enumerate();
    if (!devices) {
      why.push_back(devices.error().message());
      continue;
    }
    for (const DeviceInfo& info : *devices) {
      const bool match = vendor_product ? info.vendor_product() == lower
                                        : colon == std::string::npos || info.id() == id;
      if (!match) continue;
      const auto open = open_keys_.find(info.physical_key());
      if (open != open_keys_.end()) return open->second;
      if (!info.accessible) {
        return Error("--device " + id +
                     ": no permission; install the udev rules (see docs/devices.md)");
      }
      auto started = start_reader(*backend, info);
      if (!started) return started.error().in("--device " + id);
      return started;
    }
    why.push_back(name + " sees no such device");
  }
  if (!backend_named) {
    std::string known;
    for (auto& backend : backends_)
      known += (known.empty() ? "" : ", ") + std::string(backend->name());
    return Error("--device " + id + ": unknown backend '" + head + "' (have " + known +
                 ", or give vvvv:pppp)");
  }
  std::string joined;
  for (const std::string& w : why)
    joined += (joined.empty() ? "" : "; ") + w;
  return Error("--device " + id + ": not found (" + joined + ")");
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

std::optional<uint32_t> DeviceRegistry::first_device() const {
  if (readers_.empty()) return std::nullopt;
  return readers_.begin()->first;
}

}  // namespace sculpt::hal
