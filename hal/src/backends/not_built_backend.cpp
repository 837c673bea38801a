#include "backends/not_built_backend.h"

namespace sculpt::hal::detail {
namespace {

class NotBuiltBackend final : public Backend {
 public:
  NotBuiltBackend(std::string name, std::string note)
      : name_(std::move(name)), note_(std::move(note)) {}
  std::string_view name() const override { return name_; }
  BackendStatus status() override { return {BackendState::kNotBuilt, note_}; }
  Result<std::vector<DeviceInfo>> enumerate() override { return Error(name_ + ": " + note_); }
  Result<std::unique_ptr<Device>> open(const DeviceInfo& info) override {
    return Error(info.id() + ": " + name_ + " backend " + note_);
  }
  bool changed() override { return false; }

 private:
  std::string name_;
  std::string note_;
};

}  // namespace

std::unique_ptr<Backend> make_not_built_backend(std::string name, const std::string& option,
                                                const std::string& package) {
  std::string note = "not built (configure with -D" + option + "=ON and " + package + " installed)";
  return std::make_unique<NotBuiltBackend>(std::move(name), std::move(note));
}

}  // namespace sculpt::hal::detail
