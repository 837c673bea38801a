// A minimal OpenXR runtime for the tests, loaded by the real OpenXR loader
// through XR_RUNTIME_JSON (the test writes the manifest): the loader-runtime
// negotiation (xrNegotiateLoaderRuntimeInterface, written from the loader
// specification's "Runtime Negotiation" section; the structs are not in
// Debian's 1.0.20 headers), and the handful of functions the openxr backend
// calls, serving the pose, buttons and session events the test scripts
// through the sculpt_fake_xr_* functions (the test dlopen()s this same
// library, so it shares the state the loader's copy sees).
//
// What it checks of the caller: a session only with XR_MND_headless
// enabled (else XR_ERROR_GRAPHICS_DEVICE_INVALID: "needs a graphics
// binding"), begun only after READY, actions synced only while running,
// bindings only for the profiles it knows. It offers XR_MND_headless unless
// SCULPT_FAKE_XR_NO_HEADLESS is set.

#include <time.h>

#include <cstdlib>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <string>

#define XR_USE_TIMESPEC
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

// The loader interface (OpenXR loader specification, XR_LOADER_VERSION_1_0).
enum XrLoaderInterfaceStructs {
  XR_LOADER_INTERFACE_STRUCT_UNINTIALIZED = 0,
  XR_LOADER_INTERFACE_STRUCT_LOADER_INFO = 1,
  XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST = 2,
  XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST = 3,
};
struct XrNegotiateLoaderInfo {
  XrLoaderInterfaceStructs structType;
  uint32_t structVersion;
  size_t structSize;
  uint32_t minInterfaceVersion;
  uint32_t maxInterfaceVersion;
  XrVersion minApiVersion;
  XrVersion maxApiVersion;
};
struct XrNegotiateRuntimeRequest {
  XrLoaderInterfaceStructs structType;
  uint32_t structVersion;
  size_t structSize;
  uint32_t runtimeInterfaceVersion;
  XrVersion runtimeApiVersion;
  PFN_xrGetInstanceProcAddr getInstanceProcAddr;
};
constexpr uint32_t kLoaderInfoStructVersion = 1;
constexpr uint32_t kRuntimeInfoStructVersion = 1;
constexpr uint32_t kLoaderRuntimeVersion = 1;

namespace {

const std::string kSimple = "/interaction_profiles/khr/simple_controller";

struct State {
  std::mutex mutex;
  uint64_t next_handle = 1;
  std::map<std::string, XrPath> path_ids;
  std::map<XrPath, std::string> paths;
  bool headless = false;  // enabled on the instance
  XrInstance instance = XR_NULL_HANDLE;
  XrSession session = XR_NULL_HANDLE;
  XrSessionState session_state = XR_SESSION_STATE_UNKNOWN;
  bool running = false;
  std::deque<XrSessionState> events;
  std::map<uint64_t, std::string> binding;  // action -> input path bound for the simple controller
  std::map<uint64_t, uint64_t> action_space;  // space -> action
  bool tracked = false;
  XrPosef pose{{0, 0, 0, 1}, {0, 0, 0}};
  std::map<std::string, float> inputs;  // "/input/select/click" -> value
  int syncs = 0;
  int sessions_begun = 0;
  int instances_created = 0;
};

State& state() {
  static State s;
  return s;
}

template <class H>
H new_handle(State& s) {
  return reinterpret_cast<H>(static_cast<uintptr_t>(s.next_handle++));
}

uint64_t id_of(const void* handle) {
  return static_cast<uint64_t>(reinterpret_cast<uintptr_t>(handle));
}

void queue_state(State& s, XrSessionState st) {
  s.events.push_back(st);
}

XRAPI_ATTR XrResult XRAPI_CALL enumerate_extensions(const char* layer, uint32_t capacity,
                                                    uint32_t* count, XrExtensionProperties* props) {
  if (layer != nullptr) return XR_ERROR_API_LAYER_NOT_PRESENT;
  std::deque<const char*> names = {XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME};
  if (std::getenv("SCULPT_FAKE_XR_NO_HEADLESS") == nullptr)
    names.push_front(XR_MND_HEADLESS_EXTENSION_NAME);
  *count = static_cast<uint32_t>(names.size());
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < names.size()) return XR_ERROR_SIZE_INSUFFICIENT;
  for (size_t i = 0; i < names.size(); ++i) {
    std::strncpy(props[i].extensionName, names[i], XR_MAX_EXTENSION_NAME_SIZE - 1);
    props[i].extensionVersion = 1;
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL create_instance(const XrInstanceCreateInfo* info,
                                               XrInstance* instance) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  if (s.instance != XR_NULL_HANDLE) return XR_ERROR_LIMIT_REACHED;
  s.headless = false;
  for (uint32_t i = 0; i < info->enabledExtensionCount; ++i) {
    if (std::strcmp(info->enabledExtensionNames[i], XR_MND_HEADLESS_EXTENSION_NAME) == 0)
      s.headless = true;
  }
  s.instance = *instance = new_handle<XrInstance>(s);
  ++s.instances_created;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL destroy_instance(XrInstance instance) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  if (instance != s.instance) return XR_ERROR_HANDLE_INVALID;
  s.instance = XR_NULL_HANDLE;
  s.session = XR_NULL_HANDLE;
  s.running = false;
  s.events.clear();
  s.binding.clear();
  s.action_space.clear();
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL get_instance_properties(XrInstance, XrInstanceProperties* p) {
  p->runtimeVersion = XR_MAKE_VERSION(0, 1, 0);
  std::strncpy(p->runtimeName, "sculpt test runtime", XR_MAX_RUNTIME_NAME_SIZE - 1);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL poll_event(XrInstance, XrEventDataBuffer* buffer) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  if (s.events.empty()) return XR_EVENT_UNAVAILABLE;
  auto* e = reinterpret_cast<XrEventDataSessionStateChanged*>(buffer);
  e->type = XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED;
  e->next = nullptr;
  e->session = s.session;
  e->state = s.session_state = s.events.front();
  e->time = 1;
  s.events.pop_front();
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL string_to_path(XrInstance, const char* text, XrPath* out) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  if (text == nullptr || text[0] != '/') return XR_ERROR_PATH_FORMAT_INVALID;
  auto [it, added] = s.path_ids.emplace(text, s.path_ids.size() + 1);
  if (added) s.paths[it->second] = text;
  *out = it->second;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL get_system(XrInstance, const XrSystemGetInfo* info, XrSystemId* id) {
  if (info->formFactor != XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY)
    return XR_ERROR_FORM_FACTOR_UNSUPPORTED;
  *id = 1;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL create_session(XrInstance, const XrSessionCreateInfo* info,
                                              XrSession* session) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  if (info->systemId != 1) return XR_ERROR_SYSTEM_INVALID;
  // Without XR_MND_headless a session needs a graphics binding in `next`.
  if (!s.headless || info->next != nullptr) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
  if (s.session != XR_NULL_HANDLE) return XR_ERROR_LIMIT_REACHED;
  s.session = *session = new_handle<XrSession>(s);
  queue_state(s, XR_SESSION_STATE_IDLE);
  queue_state(s, XR_SESSION_STATE_READY);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL destroy_session(XrSession session) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  if (session != s.session) return XR_ERROR_HANDLE_INVALID;
  s.session = XR_NULL_HANDLE;
  s.running = false;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL begin_session(XrSession session, const XrSessionBeginInfo*) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  if (session != s.session) return XR_ERROR_HANDLE_INVALID;
  if (s.session_state != XR_SESSION_STATE_READY) return XR_ERROR_SESSION_NOT_READY;
  s.running = true;
  ++s.sessions_begun;
  queue_state(s, XR_SESSION_STATE_SYNCHRONIZED);
  queue_state(s, XR_SESSION_STATE_VISIBLE);
  queue_state(s, XR_SESSION_STATE_FOCUSED);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL end_session(XrSession session) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  if (session != s.session) return XR_ERROR_HANDLE_INVALID;
  if (!s.running) return XR_ERROR_SESSION_NOT_RUNNING;
  s.running = false;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL create_reference_space(XrSession, const XrReferenceSpaceCreateInfo*,
                                                      XrSpace* space) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  *space = new_handle<XrSpace>(s);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL create_action_space(XrSession, const XrActionSpaceCreateInfo* info,
                                                   XrSpace* space) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  *space = new_handle<XrSpace>(s);
  s.action_space[id_of(*space)] = id_of(info->action);
  return XR_SUCCESS;
}

// Spaces, action sets and actions hold nothing worth freeing here.
XRAPI_ATTR XrResult XRAPI_CALL destroy_space(XrSpace) {
  return XR_SUCCESS;
}
XRAPI_ATTR XrResult XRAPI_CALL destroy_action_set(XrActionSet) {
  return XR_SUCCESS;
}
XRAPI_ATTR XrResult XRAPI_CALL destroy_action(XrAction) {
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL locate_space(XrSpace space, XrSpace, XrTime time,
                                            XrSpaceLocation* location) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  if (time <= 0) return XR_ERROR_TIME_INVALID;
  location->locationFlags = 0;
  if (s.action_space.count(id_of(space)) && s.tracked && s.running) {
    location->locationFlags =
        XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT |
        XR_SPACE_LOCATION_POSITION_TRACKED_BIT | XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;
    location->pose = s.pose;
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL create_action_set(XrInstance, const XrActionSetCreateInfo*,
                                                 XrActionSet* set) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  *set = new_handle<XrActionSet>(s);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL create_action(XrActionSet, const XrActionCreateInfo*,
                                             XrAction* action) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  *action = new_handle<XrAction>(s);
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL suggest_bindings(XrInstance,
                                                const XrInteractionProfileSuggestedBinding* b) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  const std::string profile = s.paths[b->interactionProfile];
  // A profile this runtime does not know is refused, as the spec allows.
  if (profile != kSimple) return XR_ERROR_PATH_UNSUPPORTED;
  for (uint32_t i = 0; i < b->countSuggestedBindings; ++i) {
    const std::string& full = s.paths[b->suggestedBindings[i].binding];
    const size_t input = full.find("/input/");
    if (input == std::string::npos) return XR_ERROR_PATH_UNSUPPORTED;
    s.binding[id_of(b->suggestedBindings[i].action)] = full.substr(input);
  }
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL attach_action_sets(XrSession, const XrSessionActionSetsAttachInfo*) {
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL sync_actions(XrSession session, const XrActionsSyncInfo*) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  if (session != s.session) return XR_ERROR_HANDLE_INVALID;
  if (!s.running) return XR_ERROR_SESSION_NOT_RUNNING;
  ++s.syncs;
  return s.session_state == XR_SESSION_STATE_FOCUSED ? XR_SUCCESS : XR_SESSION_NOT_FOCUSED;
}

// The input an action is bound to, or nullptr.
const float* bound_input(State& s, XrAction action) {
  const auto b = s.binding.find(id_of(action));
  if (b == s.binding.end()) return nullptr;
  const auto v = s.inputs.find(b->second);
  static const float kZero = 0.0f;
  return v == s.inputs.end() ? &kZero : &v->second;
}

XRAPI_ATTR XrResult XRAPI_CALL get_boolean(XrSession, const XrActionStateGetInfo* info,
                                           XrActionStateBoolean* out) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  const float* v = bound_input(s, info->action);
  out->isActive = v != nullptr;
  out->currentState = v != nullptr && *v > 0.5f;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL get_float(XrSession, const XrActionStateGetInfo* info,
                                         XrActionStateFloat* out) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  const float* v = bound_input(s, info->action);
  out->isActive = v != nullptr;
  out->currentState = v != nullptr ? *v : 0.0f;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL get_pose(XrSession, const XrActionStateGetInfo* info,
                                        XrActionStatePose* out) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  out->isActive = s.binding.count(id_of(info->action)) > 0;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL convert_timespec(XrInstance, const struct timespec* ts,
                                                XrTime* time) {
  *time = static_cast<XrTime>(ts->tv_sec) * 1'000'000'000 + ts->tv_nsec;
  return XR_SUCCESS;
}

XRAPI_ATTR XrResult XRAPI_CALL get_proc_addr(XrInstance instance, const char* name,
                                             PFN_xrVoidFunction* function) {
  static const std::map<std::string, PFN_xrVoidFunction> kGlobal = {
      {"xrEnumerateInstanceExtensionProperties",
       reinterpret_cast<PFN_xrVoidFunction>(&enumerate_extensions)},
      {"xrCreateInstance", reinterpret_cast<PFN_xrVoidFunction>(&create_instance)},
      {"xrGetInstanceProcAddr", reinterpret_cast<PFN_xrVoidFunction>(&get_proc_addr)},
  };
  static const std::map<std::string, PFN_xrVoidFunction> kInstance = {
      {"xrDestroyInstance", reinterpret_cast<PFN_xrVoidFunction>(&destroy_instance)},
      {"xrGetInstanceProperties", reinterpret_cast<PFN_xrVoidFunction>(&get_instance_properties)},
      {"xrPollEvent", reinterpret_cast<PFN_xrVoidFunction>(&poll_event)},
      {"xrStringToPath", reinterpret_cast<PFN_xrVoidFunction>(&string_to_path)},
      {"xrGetSystem", reinterpret_cast<PFN_xrVoidFunction>(&get_system)},
      {"xrCreateSession", reinterpret_cast<PFN_xrVoidFunction>(&create_session)},
      {"xrDestroySession", reinterpret_cast<PFN_xrVoidFunction>(&destroy_session)},
      {"xrBeginSession", reinterpret_cast<PFN_xrVoidFunction>(&begin_session)},
      {"xrEndSession", reinterpret_cast<PFN_xrVoidFunction>(&end_session)},
      {"xrCreateReferenceSpace", reinterpret_cast<PFN_xrVoidFunction>(&create_reference_space)},
      {"xrCreateActionSpace", reinterpret_cast<PFN_xrVoidFunction>(&create_action_space)},
      {"xrDestroySpace", reinterpret_cast<PFN_xrVoidFunction>(&destroy_space)},
      {"xrLocateSpace", reinterpret_cast<PFN_xrVoidFunction>(&locate_space)},
      {"xrCreateActionSet", reinterpret_cast<PFN_xrVoidFunction>(&create_action_set)},
      {"xrDestroyActionSet", reinterpret_cast<PFN_xrVoidFunction>(&destroy_action_set)},
      {"xrCreateAction", reinterpret_cast<PFN_xrVoidFunction>(&create_action)},
      {"xrDestroyAction", reinterpret_cast<PFN_xrVoidFunction>(&destroy_action)},
      {"xrSuggestInteractionProfileBindings",
       reinterpret_cast<PFN_xrVoidFunction>(&suggest_bindings)},
      {"xrAttachSessionActionSets", reinterpret_cast<PFN_xrVoidFunction>(&attach_action_sets)},
      {"xrSyncActions", reinterpret_cast<PFN_xrVoidFunction>(&sync_actions)},
      {"xrGetActionStateBoolean", reinterpret_cast<PFN_xrVoidFunction>(&get_boolean)},
      {"xrGetActionStateFloat", reinterpret_cast<PFN_xrVoidFunction>(&get_float)},
      {"xrGetActionStatePose", reinterpret_cast<PFN_xrVoidFunction>(&get_pose)},
      {"xrConvertTimespecTimeToTimeKHR", reinterpret_cast<PFN_xrVoidFunction>(&convert_timespec)},
  };
  *function = nullptr;
  if (const auto g = kGlobal.find(name); g != kGlobal.end()) {
    *function = g->second;
    return XR_SUCCESS;
  }
  if (instance == XR_NULL_HANDLE) return XR_ERROR_HANDLE_INVALID;
  if (const auto f = kInstance.find(name); f != kInstance.end()) {
    *function = f->second;
    return XR_SUCCESS;
  }
  return XR_ERROR_FUNCTION_UNSUPPORTED;
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) XrResult xrNegotiateLoaderRuntimeInterface(
    const XrNegotiateLoaderInfo* loader, XrNegotiateRuntimeRequest* request) {
  if (loader == nullptr || request == nullptr ||
      loader->structType != XR_LOADER_INTERFACE_STRUCT_LOADER_INFO ||
      loader->structVersion != kLoaderInfoStructVersion ||
      loader->structSize != sizeof(XrNegotiateLoaderInfo) ||
      request->structType != XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST ||
      request->structVersion != kRuntimeInfoStructVersion ||
      request->structSize != sizeof(XrNegotiateRuntimeRequest) ||
      loader->minInterfaceVersion > kLoaderRuntimeVersion ||
      loader->maxInterfaceVersion < kLoaderRuntimeVersion ||
      XR_VERSION_MAJOR(loader->maxApiVersion) < 1 || XR_VERSION_MAJOR(loader->minApiVersion) > 1)
    return XR_ERROR_INITIALIZATION_FAILED;
  request->runtimeInterfaceVersion = kLoaderRuntimeVersion;
  request->runtimeApiVersion = XR_CURRENT_API_VERSION;
  request->getInstanceProcAddr = &get_proc_addr;
  return XR_SUCCESS;
}

// The test's script.
__attribute__((visibility("default"))) void sculpt_fake_xr_reset() {
  State& s = state();
  std::lock_guard lock(s.mutex);
  s.tracked = false;
  s.pose = XrPosef{{0, 0, 0, 1}, {0, 0, 0}};
  s.inputs.clear();
  s.syncs = 0;
  s.sessions_begun = 0;
  s.instances_created = 0;
}

__attribute__((visibility("default"))) void sculpt_fake_xr_set_pose(int tracked, const float* xyz_m,
                                                                    const float* quat_xyzw) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  s.tracked = tracked != 0;
  s.pose.position = {xyz_m[0], xyz_m[1], xyz_m[2]};
  s.pose.orientation = {quat_xyzw[0], quat_xyzw[1], quat_xyzw[2], quat_xyzw[3]};
}

__attribute__((visibility("default"))) void sculpt_fake_xr_set_input(const char* input,
                                                                     float value) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  s.inputs[input] = value;
}

// The runtime ends the session (its service stopping, say).
__attribute__((visibility("default"))) void sculpt_fake_xr_lose_session() {
  State& s = state();
  std::lock_guard lock(s.mutex);
  queue_state(s, XR_SESSION_STATE_LOSS_PENDING);
}

// 0 syncs, 1 sessions begun, 2 instances created.
__attribute__((visibility("default"))) int sculpt_fake_xr_count(int what) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  return what == 0 ? s.syncs : what == 1 ? s.sessions_begun : s.instances_created;
}

}  // extern "C"
