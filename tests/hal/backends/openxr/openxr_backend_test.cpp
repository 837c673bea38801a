// The OpenXR backend through the real OpenXR loader (Debian's
// libopenxr-loader1), which loads the tests' minimal runtime
// (fake_openxr_runtime.cpp) from a manifest named by XR_RUNTIME_JSON: no
// runtime, a runtime that needs a graphics binding, and a controller whose
// scripted pose and buttons arrive through the registry as events that its
// recording replays to.

#include "sculpt/hal/backends/openxr_backend.h"

#include <dlfcn.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include <gtest/gtest.h>

#include "sculpt/hal/input/motion_pipeline.h"
#include "sculpt/hal/parsers/make_parser.h"
#include "sculpt/hal/parsers/openxr_report.h"
#include "sculpt/hal/registry/device_registry.h"
#include "sculpt/hal/registry/tracker_backends.h"

namespace sculpt::hal {
namespace {

namespace fs = std::filesystem;

TEST(OpenXrSpec, HandsAndBadSpecs) {
  EXPECT_EQ(parse_openxr_spec("openxr")->hand, "right");
  EXPECT_EQ(parse_openxr_spec("openxr:left")->hand, "left");
  auto bad = parse_openxr_spec("openxr:foot");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message().find("openxr:foot"), std::string::npos);
  EXPECT_TRUE(names_tracker("openxr:left")) << "opened only when asked for";
}

TEST(OpenXrReport, RoundTripAndBadReports) {
  OpenXrControllerState s;
  s.tracked = true;
  s.buttons = 5;
  s.trigger = 0.75f;
  s.position_mm = {100, -20, 3.5};
  s.quat_wxyz = {0, 0, 0, 2};  // normalised by the decoder
  const auto bytes = encode_openxr_report(s);
  OpenXrControllerState back;
  ASSERT_EQ(decode_openxr_report(bytes, back), OpenXrReportError::kNone);
  EXPECT_EQ(back.buttons, 5);
  EXPECT_EQ(back.trigger, 0.75f);
  EXPECT_EQ(back.position_mm, s.position_mm);
  EXPECT_EQ(back.quat_wxyz, (std::array<double, 4>{0, 0, 0, 1}));

  auto nan = s;
  nan.position_mm[1] = std::nan("");
  EXPECT_EQ(decode_openxr_report(encode_openxr_report(nan), back), OpenXrReportError::kNotFinite);
  auto zero = s;
  zero.quat_wxyz = {0, 0, 0, 0};
  EXPECT_EQ(decode_openxr_report(encode_openxr_report(zero), back),
            OpenXrReportError::kNotRotation);
  EXPECT_EQ(decode_openxr_report(std::span(bytes).first(40), back), OpenXrReportError::kSize);
  auto other = bytes;
  other[0] = 'Y';
  EXPECT_EQ(decode_openxr_report(other, back), OpenXrReportError::kFormat);

  OpenXrReportParser p;
  std::vector<InputEvent> out;
  p.parse(RawEvent::report(1, std::span(bytes).first(40)), out);
  p.parse(RawEvent::report(1, encode_openxr_report(nan)), out);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(p.counters().short_reports, 1);
  EXPECT_EQ(p.counters().invalid_reports, 1);
}

#ifdef SCULPT_FAKE_OPENXR_RUNTIME

// The tests' runtime, loaded again here (the same copy the loader loads)
// for its script functions.
struct Script {
  void* lib = ::dlopen(SCULPT_FAKE_OPENXR_RUNTIME, RTLD_NOW);
  template <class F>
  F fn(const char* name) {
    return lib ? reinterpret_cast<F>(::dlsym(lib, name)) : nullptr;
  }
  void reset() { fn<void (*)()>("sculpt_fake_xr_reset")(); }
  void pose(bool tracked, std::array<float, 3> m, std::array<float, 4> xyzw) {
    fn<void (*)(int, const float*, const float*)>("sculpt_fake_xr_set_pose")(tracked, m.data(),
                                                                             xyzw.data());
  }
  void input(const char* path, float v) {
    fn<void (*)(const char*, float)>("sculpt_fake_xr_set_input")(path, v);
  }
  void lose_session() { fn<void (*)()>("sculpt_fake_xr_lose_session")(); }
  int count(int what) { return fn<int (*)(int)>("sculpt_fake_xr_count")(what); }
  ~Script() {
    if (lib) ::dlclose(lib);
  }
};

class OpenXrBackendTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/sculpt_openxr_XXXXXX";
    ASSERT_NE(::mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
    manifest_ = dir_ / "runtime.json";
    std::ofstream(manifest_) << R"({"file_format_version": "1.0.0", "runtime": {"name": )"
                             << R"("sculpt test runtime", "library_path": ")"
                             << SCULPT_FAKE_OPENXR_RUNTIME << "\"}}\n";
    ASSERT_NE(script_.lib, nullptr) << ::dlerror();
    script_.reset();
    ::setenv("XR_RUNTIME_JSON", manifest_.c_str(), 1);
  }
  void TearDown() override {
    ::unsetenv("XR_RUNTIME_JSON");
    ::unsetenv("SCULPT_FAKE_XR_NO_HEADLESS");
    fs::remove_all(dir_);
  }

  fs::path dir_;
  fs::path manifest_;
  Script script_;
};

TEST_F(OpenXrBackendTest, WithoutARuntimeItIsSkippedWithoutAnError) {
  ::setenv("XR_RUNTIME_JSON", (dir_ / "none.json").c_str(), 1);
  EXPECT_EQ(find_openxr_runtime_manifest(), "");
  DeviceRegistry registry({});
  registry.add_backend(make_openxr_backend());
  const auto listing = registry.list();
  ASSERT_EQ(listing.size(), 1u);
  EXPECT_EQ(listing[0].status.state, BackendState::kUnavailable);
  EXPECT_NE(listing[0].status.note.find("no OpenXR runtime"), std::string::npos)
      << listing[0].status.note;
  const ScanReport scan = registry.scan();
  EXPECT_TRUE(scan.opened.empty());
  EXPECT_TRUE(scan.errors.empty()) << scan.errors[0];
  EXPECT_EQ(script_.count(2), 0) << "the loader was not even asked";
}

TEST_F(OpenXrBackendTest, ARuntimeWithoutHeadlessNeedsAGraphicsBinding) {
  ::setenv("SCULPT_FAKE_XR_NO_HEADLESS", "1", 1);
  auto backend = make_openxr_backend();
  const BackendStatus st = backend->status();
  EXPECT_EQ(st.state, BackendState::kUnavailable);
  EXPECT_NE(st.note.find("needs a graphics binding"), std::string::npos) << st.note;
  // Opened anyway, it fails with the loader's reason. (The failed instance
  // also makes the loader unload the runtime, whose extensions it keeps from
  // the moment it loaded it: the next test's runtime offers headless again.)
  auto device = backend->open(backend->enumerate()->front());
  ASSERT_FALSE(device.ok());
  EXPECT_NE(device.error().message().find("XR_ERROR_EXTENSION_NOT_PRESENT"), std::string::npos)
      << device.error().message();
}

bool same_event(const InputEvent& a, const InputEvent& b) {
  return a.kind == b.kind && a.t_ns == b.t_ns && a.has_pose == b.has_pose &&
         a.pose.position_mm == b.pose.position_mm && a.pose.quat_wxyz == b.pose.quat_wxyz &&
         a.button == b.button && a.pressed == b.pressed;
}

TEST_F(OpenXrBackendTest, AControllerThroughTheRealLoaderReplaysBitForBit) {
  std::mutex raw_mutex;
  std::vector<RawEvent> raws;
  ReaderOptions options;
  options.on_raw = [&](const RawEvent& e) {
    std::lock_guard lock(raw_mutex);
    raws.push_back(e);
  };
  DeviceRegistry registry({}, NormalizerConfig{}, options);
  auto spec = add_named_tracker(registry, "openxr");
  ASSERT_TRUE(spec.ok()) << spec.error().message();
  const auto listing = registry.list();
  ASSERT_EQ(listing.size(), 1u);
  ASSERT_EQ(listing[0].status.state, BackendState::kReady) << listing[0].status.note;
  EXPECT_NE(listing[0].status.note.find(manifest_.string()), std::string::npos);

  // Half a turn about +Y, 0.1 m right, 1.2 m up, 0.3 m toward the user.
  script_.pose(true, {0.1f, 1.2f, 0.3f}, {0.0f, 1.0f, 0.0f, 0.0f});
  auto id = registry.open_device(*spec);
  ASSERT_TRUE(id.ok()) << id.error().message();
  const DeviceInfo info = registry.reader(*id)->info();
  EXPECT_EQ(info.id(), "openxr:right");

  std::vector<InputEvent> live;
  auto wait_for = [&](auto done) {
    for (int i = 0; i < 5000 && !done(); ++i) {
      InputFrame f;
      registry.poll(f, 0);
      live.insert(live.end(), f.events.begin(), f.events.end());
      if (!done()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return done();
  };
  auto has = [&](InputKind kind, int button = -1) {
    return std::any_of(live.begin(), live.end(), [&](const InputEvent& e) {
      return e.kind == kind && (button < 0 || e.button == button);
    });
  };
  ASSERT_TRUE(wait_for([&] { return has(InputKind::kMotion); })) << "no pose arrived";
  EXPECT_EQ(script_.count(1), 1) << "the headless session was begun once";
  const auto first_pose =
      std::find_if(live.begin(), live.end(), [](const InputEvent& e) { return e.has_pose; });
  ASSERT_NE(first_pose, live.end());
  EXPECT_TRUE(first_pose->absolute);
  EXPECT_NEAR(first_pose->pose.position_mm[0], 100.0, 1e-3);
  EXPECT_NEAR(first_pose->pose.position_mm[1], 1200.0, 1e-3);
  EXPECT_NEAR(first_pose->pose.position_mm[2], 300.0, 1e-3);
  EXPECT_EQ(first_pose->pose.quat_wxyz, (std::array<double, 4>{0, 0, 1, 0}));

  // The simple controller's select button: select, and the trigger bound to it.
  script_.input("/input/select/click", 1.0f);
  ASSERT_TRUE(wait_for([&] { return has(InputKind::kButton, 0) && has(InputKind::kButton, 1); }));
  script_.input("/input/menu/click", 1.0f);
  ASSERT_TRUE(wait_for([&] { return has(InputKind::kButton, 2); }));
  script_.pose(false, {0, 0, 0}, {0, 0, 0, 1});
  ASSERT_TRUE(wait_for([&] { return has(InputKind::kTrackingLost); }));
  EXPECT_GT(script_.count(0), 0) << "actions were synced";
  script_.lose_session();
  ASSERT_TRUE(wait_for([&] { return has(InputKind::kDisconnected); }));
  EXPECT_EQ(registry.open_count(), 0u);

  std::vector<RawEvent> recorded;
  {
    std::lock_guard lock(raw_mutex);
    recorded = raws;
  }
  MotionPipeline replay(make_parser(info).value(), NormalizerConfig{});
  std::vector<InputEvent> replayed;
  for (const RawEvent& r : recorded)
    replay.feed(r, *id, replayed);
  auto useful = [](std::vector<InputEvent> v) {
    std::erase_if(v, [](const InputEvent& e) {
      return e.kind != InputKind::kMotion && e.kind != InputKind::kButton &&
             e.kind != InputKind::kTrackingLost;
    });
    return v;
  };
  const auto a = useful(live);
  const auto b = useful(replayed);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i)
    EXPECT_TRUE(same_event(a[i], b[i])) << "event " << i;
}

#endif

}  // namespace
}  // namespace sculpt::hal
