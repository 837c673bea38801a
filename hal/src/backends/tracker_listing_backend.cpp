#include "backends/tracker_listing_backend.h"

namespace sculpt::hal::detail {
namespace {

class TrackerListingBackend final : public Backend {
 public:
  TrackerListingBackend(DeviceInfo info, OpenTracker open)
      : info_(std::move(info)), open_(std::move(open)) {}
  std::string_view name() const override { return info_.backend; }
  BackendStatus status() override { return {}; }
  Result<std::vector<DeviceInfo>> enumerate() override { return std::vector<DeviceInfo>{info_}; }

  Result<std::unique_ptr<Device>> open(const DeviceInfo& info) override {
    if (info.path != info_.path) return Error(info.id() + ": this backend serves " + info_.id());
    auto device = open_();
    if (!device) return device.error().in(info.id());
    return device;
  }

  // One fixed tracker: after the first enumeration nothing comes or goes.
  bool changed() override {
    const bool first = first_;
    first_ = false;
    return first;
  }

 private:
  DeviceInfo info_;
  OpenTracker open_;
  bool first_ = true;
};

}  // namespace

std::unique_ptr<Backend> make_tracker_listing_backend(DeviceInfo info, OpenTracker open) {
  return std::make_unique<TrackerListingBackend>(std::move(info), std::move(open));
}

}  // namespace sculpt::hal::detail
