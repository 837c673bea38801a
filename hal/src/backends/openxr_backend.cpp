// openxr backend: a controller through the OpenXR loader (see
// sculpt/hal/backends/openxr_backend.h for what it implements).
// Implements: the headless session (XR_MND_headless), one action set with
// the grip pose, trigger, select, menu and squeeze of one hand, bindings
// suggested for /interaction_profiles/khr/simple_controller and
// oculus/touch_controller, the session's life from its state events (begin
// at READY, end at STOPPING, gone at EXITING or LOSS_PENDING), poses asked
// for "now" through XR_KHR_convert_timespec_time at sample_period_ms.
// Lacks: a graphics binding (a runtime without XR_MND_headless is
// unavailable), other interaction profiles (the runtime's own remapping
// applies), both hands in one session, haptic output to the controller.

#include "sculpt/hal/backends/openxr_backend.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <vector>

#include "backends/not_built_backend.h"

#if SCULPT_HAL_HAVE_OPENXR
#include <poll.h>
#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>

#define XR_USE_TIMESPEC
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include "sculpt/hal/parsers/openxr_report.h"
#include "sculpt/hal/types/clock.h"
#endif

namespace sculpt::hal {

Result<OpenXrOptions> parse_openxr_spec(const std::string& spec) {
  OpenXrOptions options;
  if (spec == "openxr" || spec == "openxr:right") return options;
  if (spec == "openxr:left") {
    options.hand = "left";
    return options;
  }
  return Error(spec + ": not an OpenXR controller (want openxr, openxr:right or openxr:left)");
}

std::string find_openxr_runtime_manifest() {
  namespace fs = std::filesystem;
  std::error_code ec;
  auto exists = [&ec](const fs::path& p) { return fs::is_regular_file(p, ec); };
  if (const char* env = std::getenv("XR_RUNTIME_JSON"); env && *env)
    return exists(env) ? std::string(env) : std::string();
  std::vector<fs::path> dirs;
  if (const char* home = std::getenv("XDG_CONFIG_HOME"); home && *home) {
    dirs.emplace_back(home);
  } else if (const char* h = std::getenv("HOME"); h && *h) {
    dirs.push_back(fs::path(h) / ".config");
  }
  const char* xdg_dirs = std::getenv("XDG_CONFIG_DIRS");
  std::istringstream list(xdg_dirs && *xdg_dirs ? xdg_dirs : "/etc/xdg");
  for (std::string dir; std::getline(list, dir, ':');)
    if (!dir.empty()) dirs.emplace_back(dir);
  dirs.emplace_back("/etc");
  for (const fs::path& d : dirs) {
    const fs::path manifest = d / "openxr" / "1" / "active_runtime.json";
    if (exists(manifest)) return manifest.string();
  }
  return {};
}

#if SCULPT_HAL_HAVE_OPENXR
namespace {

// An OpenXR input or output struct, zeroed, with its type set.
template <class T>
T xr_struct(XrStructureType type) {
  T v{};
  v.type = type;
  return v;
}

constexpr const char* kNoRuntime =
    "no OpenXR runtime: no manifest in XR_RUNTIME_JSON, $XDG_CONFIG_HOME/openxr/1, "
    "$XDG_CONFIG_DIRS/openxr/1 or /etc/openxr/1";
constexpr const char* kNeedsGraphics =
    "the OpenXR runtime needs a graphics binding (it offers no XR_MND_headless, and the station "
    "has no VR view to give it one)";

std::string xr_text(XrResult r) {
  // The loader's xrResultToString needs an instance; the common ones by hand.
  switch (r) {
    case XR_ERROR_RUNTIME_UNAVAILABLE:
      return "XR_ERROR_RUNTIME_UNAVAILABLE";
    case XR_ERROR_RUNTIME_FAILURE:
      return "XR_ERROR_RUNTIME_FAILURE";
    case XR_ERROR_FORM_FACTOR_UNAVAILABLE:
      return "XR_ERROR_FORM_FACTOR_UNAVAILABLE (no headset or controller connected)";
    case XR_ERROR_EXTENSION_NOT_PRESENT:
      return "XR_ERROR_EXTENSION_NOT_PRESENT";
    case XR_ERROR_SESSION_LOST:
      return "XR_ERROR_SESSION_LOST";
    case XR_ERROR_INSTANCE_LOST:
      return "XR_ERROR_INSTANCE_LOST";
    case XR_ERROR_GRAPHICS_DEVICE_INVALID:
      return "XR_ERROR_GRAPHICS_DEVICE_INVALID";
    default:
      return "XrResult " + std::to_string(static_cast<int>(r));
  }
}

// The runtime's instance extensions, or an error line.
Result<std::vector<std::string>> runtime_extensions() {
  uint32_t n = 0;
  XrResult r = xrEnumerateInstanceExtensionProperties(nullptr, 0, &n, nullptr);
  if (XR_FAILED(r)) return Error("OpenXR runtime failed to list its extensions: " + xr_text(r));
  std::vector<XrExtensionProperties> props(n, {XR_TYPE_EXTENSION_PROPERTIES, nullptr, {}, 0});
  r = xrEnumerateInstanceExtensionProperties(nullptr, n, &n, props.data());
  if (XR_FAILED(r)) return Error("OpenXR runtime failed to list its extensions: " + xr_text(r));
  std::vector<std::string> names;
  for (uint32_t i = 0; i < n && i < props.size(); ++i)
    names.emplace_back(props[i].extensionName);
  return names;
}

// Why the runtime cannot serve a headless session, or kReady.
BackendStatus probe_runtime() {
  const std::string manifest = find_openxr_runtime_manifest();
  if (manifest.empty()) return {BackendState::kUnavailable, kNoRuntime};
  auto ext = runtime_extensions();
  if (!ext) return {BackendState::kUnavailable, ext.error().message() + " (" + manifest + ")"};
  auto has = [&](const char* name) {
    return std::find(ext->begin(), ext->end(), name) != ext->end();
  };
  if (!has(XR_MND_HEADLESS_EXTENSION_NAME)) return {BackendState::kUnavailable, kNeedsGraphics};
  if (!has(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME))
    return {BackendState::kUnavailable,
            "the OpenXR runtime offers no XR_KHR_convert_timespec_time, needed to ask for poses "
            "without a frame loop"};
  return {BackendState::kReady, "runtime " + manifest};
}

DeviceInfo openxr_device_info(const OpenXrOptions& options) {
  DeviceInfo info;
  info.backend = "openxr";
  info.path = options.hand;
  info.name = "OpenXR controller, " + options.hand + " hand";
  info.serial = "openxr:" + options.hand;  // the physical key: one hand, one device
  return info;
}

class OpenXrControllerDevice final : public Device {
 public:
  explicit OpenXrControllerDevice(OpenXrOptions options)
      : options_(std::move(options)), info_(openxr_device_info(options_)) {}
  ~OpenXrControllerDevice() override {
    if (session_ != XR_NULL_HANDLE) {
      if (running_) xrEndSession(session_);
      xrDestroySession(session_);  // destroys its spaces too
    }
    if (instance_ != XR_NULL_HANDLE) xrDestroyInstance(instance_);  // and its actions
  }
  OpenXrControllerDevice(const OpenXrControllerDevice&) = delete;
  OpenXrControllerDevice& operator=(const OpenXrControllerDevice&) = delete;

  Status start();
  const DeviceInfo& info() const override { return info_; }
  ReadResult read(RawEvent& out, int timeout_ms) override;

 private:
  Status fail(const std::string& step, XrResult r) {
    return Error("openxr:" + options_.hand + ": " + step + ": " + xr_text(r));
  }
  Status make_actions();
  XrPath path(const char* text) {
    XrPath p = XR_NULL_PATH;
    xrStringToPath(instance_, text, &p);
    return p;
  }
  void pump_events();
  void sample(int64_t now_ns);
  void gone(const std::string& why);
  void log(const std::string& line) {
    const std::string full = "openxr: " + options_.hand + ": " + line;
    if (options_.log) {
      options_.log(full);
    } else {
      std::fprintf(stderr, "%s\n", full.c_str());
    }
  }

  OpenXrOptions options_;
  DeviceInfo info_;
  XrInstance instance_ = XR_NULL_HANDLE;
  XrSystemId system_ = XR_NULL_SYSTEM_ID;
  XrSession session_ = XR_NULL_HANDLE;
  XrActionSet set_ = XR_NULL_HANDLE;
  XrAction grip_ = XR_NULL_HANDLE;
  XrAction trigger_ = XR_NULL_HANDLE;
  XrAction select_ = XR_NULL_HANDLE;
  XrAction menu_ = XR_NULL_HANDLE;
  XrAction squeeze_ = XR_NULL_HANDLE;
  XrSpace grip_space_ = XR_NULL_HANDLE;
  XrSpace base_space_ = XR_NULL_HANDLE;
  XrPath hand_ = XR_NULL_PATH;
  PFN_xrConvertTimespecTimeToTimeKHR to_xr_time_ = nullptr;
  bool running_ = false;
  bool removed_ = false;
  bool error_logged_ = false;
  bool have_last_ = false;
  OpenXrControllerState last_;
  std::deque<RawEvent> pending_;
};

Status OpenXrControllerDevice::start() {
  const char* extensions[] = {XR_MND_HEADLESS_EXTENSION_NAME,
                              XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME};
  auto ci = xr_struct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
  std::snprintf(ci.applicationInfo.applicationName, XR_MAX_APPLICATION_NAME_SIZE, "sculpt");
  std::snprintf(ci.applicationInfo.engineName, XR_MAX_ENGINE_NAME_SIZE, "sculpt");
  ci.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  ci.enabledExtensionCount = 2;
  ci.enabledExtensionNames = extensions;
  if (const XrResult r = xrCreateInstance(&ci, &instance_); XR_FAILED(r)) {
    instance_ = XR_NULL_HANDLE;
    return fail("creating the instance", r);
  }
  if (const XrResult r = xrGetInstanceProcAddr(instance_, "xrConvertTimespecTimeToTimeKHR",
                                               reinterpret_cast<PFN_xrVoidFunction*>(&to_xr_time_));
      XR_FAILED(r) || to_xr_time_ == nullptr)
    return fail("finding xrConvertTimespecTimeToTimeKHR", r);
  auto sys = xr_struct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
  sys.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  if (const XrResult r = xrGetSystem(instance_, &sys, &system_); XR_FAILED(r))
    return fail("finding the headset", r);
  hand_ = path(("/user/hand/" + options_.hand).c_str());
  if (auto actions = make_actions(); !actions) return actions;
  // XR_MND_headless: no graphics binding in the chain.
  auto si = xr_struct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
  si.systemId = system_;
  if (const XrResult r = xrCreateSession(instance_, &si, &session_); XR_FAILED(r)) {
    session_ = XR_NULL_HANDLE;
    return fail("creating a headless session", r);
  }
  auto attach = xr_struct<XrSessionActionSetsAttachInfo>(XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO);
  attach.countActionSets = 1;
  attach.actionSets = &set_;
  if (const XrResult r = xrAttachSessionActionSets(session_, &attach); XR_FAILED(r))
    return fail("attaching the actions", r);
  auto as = xr_struct<XrActionSpaceCreateInfo>(XR_TYPE_ACTION_SPACE_CREATE_INFO);
  as.action = grip_;
  as.subactionPath = hand_;
  as.poseInActionSpace.orientation.w = 1.0f;
  if (const XrResult r = xrCreateActionSpace(session_, &as, &grip_space_); XR_FAILED(r))
    return fail("creating the grip space", r);
  auto rs = xr_struct<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
  rs.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
  rs.poseInReferenceSpace.orientation.w = 1.0f;
  if (const XrResult r = xrCreateReferenceSpace(session_, &rs, &base_space_); XR_FAILED(r))
    return fail("creating the reference space", r);
  return {};
}

Status OpenXrControllerDevice::make_actions() {
  auto sc = xr_struct<XrActionSetCreateInfo>(XR_TYPE_ACTION_SET_CREATE_INFO);
  std::snprintf(sc.actionSetName, XR_MAX_ACTION_SET_NAME_SIZE, "sculpt");
  std::snprintf(sc.localizedActionSetName, XR_MAX_LOCALIZED_ACTION_SET_NAME_SIZE, "Sculpt");
  if (const XrResult r = xrCreateActionSet(instance_, &sc, &set_); XR_FAILED(r))
    return fail("creating the action set", r);
  struct Want {
    XrAction* action;
    const char* name;
    XrActionType type;
  };
  const Want wants[] = {{&grip_, "grip", XR_ACTION_TYPE_POSE_INPUT},
                        {&trigger_, "trigger", XR_ACTION_TYPE_FLOAT_INPUT},
                        {&select_, "select", XR_ACTION_TYPE_BOOLEAN_INPUT},
                        {&menu_, "menu", XR_ACTION_TYPE_BOOLEAN_INPUT},
                        {&squeeze_, "squeeze", XR_ACTION_TYPE_FLOAT_INPUT}};
  for (const Want& w : wants) {
    auto ac = xr_struct<XrActionCreateInfo>(XR_TYPE_ACTION_CREATE_INFO);
    std::snprintf(ac.actionName, XR_MAX_ACTION_NAME_SIZE, "%s", w.name);
    std::snprintf(ac.localizedActionName, XR_MAX_LOCALIZED_ACTION_NAME_SIZE, "%s", w.name);
    ac.actionType = w.type;
    ac.countSubactionPaths = 1;
    ac.subactionPaths = &hand_;
    if (const XrResult r = xrCreateAction(set_, &ac, w.action); XR_FAILED(r))
      return fail(std::string("creating the ") + w.name + " action", r);
  }
  const std::string h = "/user/hand/" + options_.hand;
  auto suggest = [&](const char* profile, std::vector<std::pair<XrAction, std::string>> binds) {
    std::vector<XrActionSuggestedBinding> b;
    for (auto& [action, input] : binds)
      b.push_back({action, path((h + input).c_str())});
    auto s = xr_struct<XrInteractionProfileSuggestedBinding>(
        XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
    s.interactionProfile = path(profile);
    s.countSuggestedBindings = static_cast<uint32_t>(b.size());
    s.suggestedBindings = b.data();
    return xrSuggestInteractionProfileBindings(instance_, &s);
  };
  // The simple controller is the profile every runtime maps its
  // controllers to; its one button serves as trigger too.
  if (const XrResult r =
          suggest("/interaction_profiles/khr/simple_controller", {{grip_, "/input/grip/pose"},
                                                                  {trigger_, "/input/select/click"},
                                                                  {select_, "/input/select/click"},
                                                                  {menu_, "/input/menu/click"}});
      XR_FAILED(r))
    return fail("suggesting the simple controller's bindings", r);
  // Touch controllers have an analogue trigger and grip; a runtime that
  // does not know the profile keeps the simple one.
  (void)suggest("/interaction_profiles/oculus/touch_controller",
                {{grip_, "/input/grip/pose"},
                 {trigger_, "/input/trigger/value"},
                 {squeeze_, "/input/squeeze/value"}});
  return {};
}

void OpenXrControllerDevice::gone(const std::string& why) {
  if (removed_) return;
  removed_ = true;
  log(why);
}

void OpenXrControllerDevice::pump_events() {
  for (int i = 0; i < 64 && !removed_; ++i) {
    auto e = xr_struct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
    const XrResult r = xrPollEvent(instance_, &e);
    if (r == XR_EVENT_UNAVAILABLE) return;
    if (XR_FAILED(r)) {
      gone("polling events failed: " + xr_text(r));
      return;
    }
    if (e.type == XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING) {
      gone("the runtime is going away (instance loss pending)");
      return;
    }
    if (e.type != XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) continue;
    const auto& changed = reinterpret_cast<const XrEventDataSessionStateChanged&>(e);
    switch (changed.state) {
      case XR_SESSION_STATE_READY: {
        auto b = xr_struct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
        b.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
        const XrResult br = xrBeginSession(session_, &b);
        if (XR_FAILED(br)) {
          gone("beginning the session failed: " + xr_text(br));
          return;
        }
        running_ = true;
        break;
      }
      case XR_SESSION_STATE_STOPPING:
        xrEndSession(session_);
        running_ = false;
        break;
      case XR_SESSION_STATE_EXITING:
      case XR_SESSION_STATE_LOSS_PENDING:
        gone("the runtime ended the session");
        return;
      default:
        break;
    }
  }
}

void OpenXrControllerDevice::sample(int64_t now_ns) {
  XrActiveActionSet active{set_, XR_NULL_PATH};
  auto sync = xr_struct<XrActionsSyncInfo>(XR_TYPE_ACTIONS_SYNC_INFO);
  sync.countActiveActionSets = 1;
  sync.activeActionSets = &active;
  XrResult r = xrSyncActions(session_, &sync);
  if (r == XR_ERROR_SESSION_LOST || r == XR_ERROR_INSTANCE_LOST) {
    gone("the session was lost (" + xr_text(r) + ")");
    return;
  }
  OpenXrControllerState s;
  s.buttons = last_.buttons;
  if (XR_SUCCEEDED(r) && r != XR_SESSION_NOT_FOCUSED) {
    timespec ts{};
    ::clock_gettime(CLOCK_MONOTONIC, &ts);
    XrTime t = 0;
    auto loc = xr_struct<XrSpaceLocation>(XR_TYPE_SPACE_LOCATION);
    auto pose = xr_struct<XrActionStatePose>(XR_TYPE_ACTION_STATE_POSE);
    auto get = xr_struct<XrActionStateGetInfo>(XR_TYPE_ACTION_STATE_GET_INFO);
    get.action = grip_;
    get.subactionPath = hand_;
    constexpr XrSpaceLocationFlags kValid =
        XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
    if (XR_SUCCEEDED(to_xr_time_(instance_, &ts, &t)) &&
        XR_SUCCEEDED(xrGetActionStatePose(session_, &get, &pose)) && pose.isActive &&
        XR_SUCCEEDED(xrLocateSpace(grip_space_, base_space_, t, &loc)) &&
        (loc.locationFlags & kValid) == kValid) {
      s.tracked = true;
      const XrPosef& p = loc.pose;
      s.position_mm = {p.position.x * 1000.0, p.position.y * 1000.0, p.position.z * 1000.0};
      s.quat_wxyz = {p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z};
    }
    auto value = [&](XrAction a) {
      auto v = xr_struct<XrActionStateFloat>(XR_TYPE_ACTION_STATE_FLOAT);
      get.action = a;
      return XR_SUCCEEDED(xrGetActionStateFloat(session_, &get, &v)) && v.isActive ? v.currentState
                                                                                   : 0.0f;
    };
    auto held = [&](XrAction a) {
      auto v = xr_struct<XrActionStateBoolean>(XR_TYPE_ACTION_STATE_BOOLEAN);
      get.action = a;
      return XR_SUCCEEDED(xrGetActionStateBoolean(session_, &get, &v)) && v.isActive &&
             v.currentState;
    };
    s.trigger = value(trigger_);
    if (!std::isfinite(s.trigger)) s.trigger = 0.0f;
    // Past half is held; a little hysteresis so a resting finger does not chatter.
    const bool was = last_.buttons & 1u;
    const bool trigger = was ? s.trigger > 0.45f : s.trigger > 0.55f;
    const float squeeze = value(squeeze_);
    s.buttons = static_cast<uint16_t>((trigger ? 1 : 0) | (held(select_) ? 2 : 0) |
                                      (held(menu_) ? 4 : 0) | (squeeze > 0.5f ? 8 : 0));
  } else if (XR_FAILED(r) && !error_logged_) {
    error_logged_ = true;
    log("syncing the actions failed: " + xr_text(r) + " (further failures not logged)");
  }
  // Motion is state: a report only when something changed.
  const bool same = have_last_ && s.tracked == last_.tracked && s.buttons == last_.buttons &&
                    s.trigger == last_.trigger && s.position_mm == last_.position_mm &&
                    s.quat_wxyz == last_.quat_wxyz;
  if (same) return;
  have_last_ = true;
  last_ = s;
  pending_.push_back(RawEvent::report(now_ns, encode_openxr_report(s)));
}

ReadResult OpenXrControllerDevice::read(RawEvent& out, int timeout_ms) {
  const int64_t deadline = monotonic_ns() + int64_t{std::max(timeout_ms, 0)} * 1'000'000;
  for (;;) {
    if (!pending_.empty()) {
      out = pending_.front();
      pending_.pop_front();
      return ReadResult::kEvent;
    }
    if (removed_) {
      out = RawEvent::removed(monotonic_ns());
      return ReadResult::kRemoved;
    }
    pump_events();
    if (running_ && !removed_) sample(monotonic_ns());
    if (!pending_.empty() || removed_) continue;
    const int64_t now = monotonic_ns();
    if (now >= deadline) return ReadResult::kTimeout;
    const int64_t wait_ns = std::min<int64_t>(
        deadline - now, int64_t{std::max(options_.sample_period_ms, 1)} * 1'000'000);
    ::poll(nullptr, 0, static_cast<int>((wait_ns + 999'999) / 1'000'000));
  }
}

class OpenXrBackend final : public Backend {
 public:
  explicit OpenXrBackend(OpenXrOptions options) : options_(std::move(options)) {}
  std::string_view name() const override { return "openxr"; }
  // Probed once: loading the runtime is not free, and the registry asks at
  // every scan.
  BackendStatus status() override {
    if (!probed_) {
      status_ = probe_runtime();
      probed_ = true;
    }
    return status_;
  }
  Result<std::vector<DeviceInfo>> enumerate() override {
    return std::vector<DeviceInfo>{openxr_device_info(options_)};
  }
  Result<std::unique_ptr<Device>> open(const DeviceInfo& info) override {
    if (info.path != options_.hand)
      return Error(info.id() + ": this backend serves openxr:" + options_.hand);
    auto device = std::make_unique<OpenXrControllerDevice>(options_);
    if (auto started = device->start(); !started) return started.error();
    return std::unique_ptr<Device>(std::move(device));
  }
  bool changed() override {
    const bool first = first_;
    first_ = false;
    return first;
  }

 private:
  OpenXrOptions options_;
  bool probed_ = false;
  bool first_ = true;
  BackendStatus status_;
};

}  // namespace
#endif

std::unique_ptr<Backend> make_openxr_backend(OpenXrOptions options) {
#if SCULPT_HAL_HAVE_OPENXR
  return std::make_unique<OpenXrBackend>(std::move(options));
#else
  (void)options;
  return detail::make_not_built_backend("openxr", "SCULPT_WITH_OPENXR", "libopenxr-dev");
#endif
}

}  // namespace sculpt::hal
