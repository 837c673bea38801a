// The evdev 6-axis backend over a fake /dev/input and /sys/class/input tree
// in a temporary directory (read by the real sysfs code) and the fake event
// stream: listing, hot-plug, and, through the registry, priority below
// hidraw, no device opened twice, unplug and re-plug, and a live session
// whose recording replays to the same events.

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include <gtest/gtest.h>

#include "../evdev_ff/fake_evdev_io.h"
#include "backends/evdev_ff/linux_evdev_io.h"
#include "backends/evdev_input/evdev_input_backend.h"
#include "sculpt/hal/backends/feed_backend.h"
#include "sculpt/hal/input/motion_pipeline.h"
#include "sculpt/hal/parsers/make_parser.h"
#include "sculpt/hal/registry/device_registry.h"

namespace sculpt::hal::evdev_input {
namespace {

namespace fs = std::filesystem;
using evdev_ff::testing::FakeEvdevIo;
using evdev_ff::testing::FakeEvdevNode;
using evdev_ff::testing::FakeEvdevSystem;
using evdev_ff::testing::make_event;
using evdev_ff::testing::Op;
using evdev_ff::testing::sysfs_bitmap;

// The fake kernel, shared by the test thread and the readers' threads.
struct Kernel {
  std::mutex mutex;
  FakeEvdevSystem sys;
};

// The real sysfs and directory code on the temporary tree, the fake event
// stream for the rest; every call under the kernel's lock.
class TreeEvdevIo final : public evdev_ff::EvdevIo {
  // Defined first: clang 14 wants a deduced return type seen before use.
  template <class F>
  auto locked(F f) {
    std::lock_guard lock(k_.mutex);
    return f();
  }

 public:
  TreeEvdevIo(Kernel& k, const fs::path& root)
      : k_(k),
        tree_((root / "dev/input").string(), (root / "sys/class/input").string()),
        fake_(k.sys) {}
  std::vector<std::string> list_event_nodes() override { return tree_.list_event_nodes(); }
  std::optional<evdev_ff::EvdevSysfs> sysfs(const std::string& node) override {
    return tree_.sysfs(node);
  }
  int open(const std::string& node) override {
    return locked([&] { return fake_.open(node); });
  }
  void close() override {
    std::lock_guard lock(k_.mutex);
    fake_.close();
  }
  int get_bits(uint16_t t, std::span<uint8_t> b) override {
    return locked([&] { return fake_.get_bits(t, b); });
  }
  int get_key_state(std::span<uint8_t> b) override {
    return locked([&] { return fake_.get_key_state(b); });
  }
  int get_abs(uint16_t a, input_absinfo& o) override {
    return locked([&] { return fake_.get_abs(a, o); });
  }
  int get_id(input_id& o) override {
    return locked([&] { return fake_.get_id(o); });
  }
  int get_name(std::string& o) override {
    return locked([&] { return fake_.get_name(o); });
  }
  int upload_effect(ff_effect& e) override {
    return locked([&] { return fake_.upload_effect(e); });
  }
  int remove_effect(int16_t id) override {
    return locked([&] { return fake_.remove_effect(id); });
  }
  long write_bytes(std::span<const uint8_t> b) override {
    return locked([&] { return fake_.write_bytes(b); });
  }
  long read_bytes(std::span<uint8_t> b) override {
    return locked([&] { return fake_.read_bytes(b); });
  }
  int poll_readable(int timeout_ms) override {
    const int r = locked([&] { return fake_.poll_readable(0); });
    // The fake answers at once; wait a little like a real poll() so an
    // idle reader thread does not spin.
    if (r == 0 && timeout_ms > 0)
      std::this_thread::sleep_for(std::chrono::milliseconds(std::min(timeout_ms, 2)));
    return r;
  }

 private:
  Kernel& k_;
  evdev_ff::LinuxEvdevIo tree_;
  FakeEvdevIo fake_;
};

struct Caps {
  std::set<uint16_t> ev, abs, rel, key, props;
};

Caps six_axis_caps() {
  return {{EV_SYN, EV_KEY, EV_ABS},
          {ABS_X, ABS_Y, ABS_Z, ABS_RX, ABS_RY, ABS_RZ},
          {},
          {BTN_0, BTN_1},
          {}};
}

class EvdevBackendTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/sculpt_evdev_XXXXXX";
    ASSERT_NE(::mkdtemp(tmpl), nullptr);
    root_ = tmpl;
    fs::create_directories(root_ / "dev/input");
    fs::create_directories(root_ / "sys/class/input");
  }
  void TearDown() override { fs::remove_all(root_); }

  std::string node_path(int n) const {
    return (root_ / "dev/input").string() + "/event" + std::to_string(n);
  }

  // Plugs in eventN: the node, its sysfs device under a USB port, and the
  // fake kernel's answers.
  void plug(int n, const std::string& name, uint16_t vendor, uint16_t product, const Caps& caps,
            const std::string& usb_port, const std::string& uniq = "") {
    const std::string in = "input" + std::to_string(40 + n);
    const std::string ev = "event" + std::to_string(n);
    const fs::path dev = root_ / "sys/devices/pci0000:00/0000:00:14.0/usb1" / usb_port /
                         (usb_port + ":1.0") / ("0003:256F:C635.00" + std::to_string(10 + n)) /
                         "input" / in;
    fs::create_directories(dev / ev);
    fs::create_directories(dev / "id");
    fs::create_directories(dev / "capabilities");
    fs::create_symlink("..", dev / ev / "device");
    auto write = [](const fs::path& p, const std::string& text) {
      std::ofstream(p) << text << "\n";
    };
    char hex[8];
    write(dev / "name", name);
    write(dev / "uniq", uniq);
    std::snprintf(hex, sizeof hex, "%04x", vendor);
    write(dev / "id/vendor", hex);
    std::snprintf(hex, sizeof hex, "%04x", product);
    write(dev / "id/product", hex);
    write(dev / "capabilities/ev", sysfs_bitmap(caps.ev));
    write(dev / "capabilities/abs", sysfs_bitmap(caps.abs));
    write(dev / "capabilities/rel", sysfs_bitmap(caps.rel));
    write(dev / "capabilities/key", sysfs_bitmap(caps.key));
    write(dev / "capabilities/ff", "0");
    write(dev / "properties", sysfs_bitmap(caps.props));
    fs::create_symlink(dev / ev, root_ / "sys/class/input" / ev);
    std::ofstream(node_path(n));

    FakeEvdevNode node;
    node.ev_types = caps.ev;
    node.abs = caps.abs;
    node.rel = caps.rel;
    node.keys = caps.key;
    for (uint16_t c : caps.abs) {
      input_absinfo a{};
      a.minimum = -350;
      a.maximum = 350;
      node.absinfo[c] = a;
    }
    node.id = {BUS_USB, vendor, product, 1};
    node.name = name;
    std::lock_guard lock(kernel_.mutex);
    kernel_.sys.nodes[node_path(n)] = node;
  }

  // The node vanishes from the tree and its open descriptor answers ENODEV.
  void unplug(int n) {
    fs::remove(node_path(n));
    fs::remove(root_ / "sys/class/input" / ("event" + std::to_string(n)));
    std::lock_guard lock(kernel_.mutex);
    kernel_.sys.gone = true;
  }

  void queue(int n, std::initializer_list<input_event> events) {
    std::lock_guard lock(kernel_.mutex);
    kernel_.sys.queue(node_path(n), events);
  }

  size_t opens_of(int n) {
    std::lock_guard lock(kernel_.mutex);
    size_t count = 0;
    for (const auto& c : kernel_.sys.calls_of(Op::kOpen))
      count += c.node == node_path(n);
    return count;
  }

  std::unique_ptr<Backend> backend() {
    EvdevInputOptions options;
    options.log = [](std::string_view) {};
    return make_evdev_input_backend(
        [this] { return std::make_unique<TreeEvdevIo>(kernel_, root_); }, options);
  }

  fs::path root_;
  Kernel kernel_;
};

TEST_F(EvdevBackendTest, ListsSixAxisNodesFromSysfs) {
  plug(0, "Keyboard", 0x046d, 0xc31c, {{EV_SYN, EV_KEY}, {}, {}, {KEY_A, KEY_B}, {}}, "1-2");
  plug(3, "SpaceMouse Compact", 0x256f, 0xc635, six_axis_caps(), "1-4", "ABC123");
  Caps pad = six_axis_caps();
  pad.key = {BTN_SOUTH, BTN_EAST};
  plug(5, "Pad", 0x045e, 0x028e, pad, "1-5");
  Caps sensor = six_axis_caps();
  sensor.key.clear();
  sensor.props = {INPUT_PROP_ACCELEROMETER};
  plug(6, "Pad Motion Sensors", 0x054c, 0x09cc, sensor, "1-6");
  Caps relative = six_axis_caps();
  relative.ev = {EV_SYN, EV_KEY, EV_REL};
  relative.rel = {REL_X, REL_Y, REL_Z, REL_RX, REL_RY, REL_RZ};
  relative.abs.clear();
  plug(7, "SpaceNavigator", 0x046d, 0xc626, relative, "1-7");
  {
    std::lock_guard lock(kernel_.mutex);
    kernel_.sys.nodes[node_path(7)].open_error = -EACCES;
  }

  auto b = backend();
  EXPECT_EQ(b->name(), "evdev");
  EXPECT_EQ(b->status().state, BackendState::kReady);
  auto found = b->enumerate();
  ASSERT_TRUE(found.ok());
  ASSERT_EQ(found->size(), 2u);
  const DeviceInfo& mouse = (*found)[0];
  EXPECT_EQ(mouse.id(), "evdev:" + node_path(3));
  EXPECT_EQ(mouse.name, "SpaceMouse Compact");
  EXPECT_EQ(mouse.vendor_product(), "256f:c635");
  EXPECT_EQ(mouse.usb_location, "1-4");
  EXPECT_EQ(mouse.serial, "ABC123");
  EXPECT_TRUE(mouse.accessible);
  const DeviceInfo& navigator = (*found)[1];
  EXPECT_EQ(navigator.path, node_path(7));
  EXPECT_FALSE(navigator.accessible);
  EXPECT_EQ(navigator.name, "SpaceNavigator") << "from sysfs";
  EXPECT_EQ(opens_of(0) + opens_of(5) + opens_of(6), 0u) << "sysfs ruled them out unopened";
}

TEST_F(EvdevBackendTest, ChangedWhenANodeComesOrGoes) {
  auto b = backend();
  ASSERT_TRUE(b->enumerate().ok());
  EXPECT_FALSE(b->changed());
  plug(2, "SpaceMouse", 0x256f, 0xc635, six_axis_caps(), "1-4");
  EXPECT_TRUE(b->changed());
  ASSERT_EQ(b->enumerate()->size(), 1u);
  EXPECT_FALSE(b->changed());
  fs::remove(node_path(2));
  EXPECT_TRUE(b->changed());
}

// Polls until `done` holds for what arrived (bounded: a hang fails instead).
template <class Pred>
std::vector<InputEvent> poll_until(DeviceRegistry& r, Pred done) {
  std::vector<InputEvent> all;
  for (int i = 0; i < 5000 && !done(all); ++i) {
    InputFrame f;
    r.poll(f, 0);
    all.insert(all.end(), f.events.begin(), f.events.end());
    if (!done(all)) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_TRUE(done(all)) << "timed out waiting for input";
  return all;
}

size_t count(const std::vector<InputEvent>& events, InputKind kind) {
  size_t n = 0;
  for (const InputEvent& e : events)
    n += e.kind == kind;
  return n;
}

TEST_F(EvdevBackendTest, TheRegistryPrefersHidrawAndNeverOpensADeviceTwice) {
  plug(3, "SpaceMouse Compact", 0x256f, 0xc635, six_axis_caps(), "1-4");
  std::vector<std::unique_ptr<Backend>> backends;
  auto hid = std::make_unique<FeedBackend>("hidapi");
  FeedBackend* hidraw = hid.get();
  backends.push_back(std::move(hid));
  backends.push_back(backend());
  DeviceRegistry registry(std::move(backends));
  DeviceInfo same;
  same.path = "/dev/hidraw2";
  same.vendor_id = 0x256f;
  same.product_id = 0xc635;
  same.usb_location = "1-4";
  hidraw->attach(same);

  ScanReport first = registry.scan();
  ASSERT_EQ(first.opened.size(), 1u);
  EXPECT_EQ(registry.reader(first.opened[0])->info().backend, "hidapi");
  EXPECT_TRUE(registry.scan().opened.empty()) << "the event node is the same device";
  EXPECT_TRUE(registry.open_device("evdev:" + node_path(3)).ok());
  EXPECT_EQ(registry.open_count(), 1u) << "asked for by id, it is the one already open";
  {
    std::lock_guard lock(kernel_.mutex);
    EXPECT_TRUE(kernel_.sys.calls_of(Op::kGetAbs).empty())
        << "listed, never opened as a device (that reads the axis ranges)";
  }

  // Without hidraw (its device gone, say no permission), evdev takes over.
  hidraw->detach(same.path, 0);
  poll_until(registry, [](const auto& e) { return count(e, InputKind::kDisconnected) == 1; });
  const ScanReport second = registry.scan();
  ASSERT_EQ(second.opened.size(), 1u);
  EXPECT_EQ(registry.reader(second.opened[0])->info().backend, "evdev");
}

TEST_F(EvdevBackendTest, WhereHidrawIsNotThisUsersEvdevOpensItWithoutComplaint) {
  plug(3, "SpaceMouse Compact", 0x256f, 0xc635, six_axis_caps(), "1-4");
  plug(6, "SpaceMouse Pro", 0x256f, 0xc62b, six_axis_caps(), "1-6");
  {
    std::lock_guard lock(kernel_.mutex);
    kernel_.sys.nodes[node_path(6)].open_error = -EACCES;
  }
  std::vector<std::unique_ptr<Backend>> backends;
  auto hid = std::make_unique<FeedBackend>("hidapi");
  FeedBackend* hidraw = hid.get();
  backends.push_back(std::move(hid));
  backends.push_back(backend());
  DeviceRegistry registry(std::move(backends));
  DeviceInfo compact;
  compact.path = "/dev/hidraw2";
  compact.vendor_id = 0x256f;
  compact.product_id = 0xc635;
  compact.usb_location = "1-4";
  compact.accessible = false;
  hidraw->attach(compact);
  DeviceInfo pro = compact;
  pro.path = "/dev/hidraw3";
  pro.product_id = 0xc62b;
  pro.usb_location = "1-6";
  hidraw->attach(pro);

  const ScanReport r = registry.scan();
  ASSERT_EQ(r.opened.size(), 1u);
  EXPECT_EQ(registry.reader(r.opened[0])->info().path, node_path(3));
  ASSERT_EQ(r.errors.size(), 1u) << "only the device nobody could open";
  EXPECT_NE(r.errors[0].find("hidapi:/dev/hidraw3"), std::string::npos) << r.errors[0];
}

TEST_F(EvdevBackendTest, HotPlugUnplugAndReplugThroughTheRegistry) {
  std::mutex raw_mutex;
  std::vector<RawEvent> raws;
  ReaderOptions options;
  options.on_raw = [&](const RawEvent& e) {
    std::lock_guard lock(raw_mutex);
    raws.push_back(e);
  };
  NormalizerConfig direct;
  direct.deadzone.fill(0.0f);
  direct.curve = CurveKind::kLinear;
  direct.filter = false;
  std::vector<std::unique_ptr<Backend>> backends;
  backends.push_back(backend());
  DeviceRegistry registry(std::move(backends), direct, options);
  EXPECT_TRUE(registry.scan().opened.empty());

  plug(4, "SpaceMouse Compact", 0x256f, 0xc635, six_axis_caps(), "1-4");
  const ScanReport plugged = registry.scan();
  ASSERT_EQ(plugged.opened.size(), 1u) << (plugged.errors.empty() ? "" : plugged.errors[0]);
  const DeviceInfo info = registry.reader(plugged.opened[0])->info();
  queue(4, {make_event(EV_ABS, ABS_X, 350), make_event(EV_SYN, SYN_REPORT, 0)});
  queue(4, {make_event(EV_KEY, BTN_1, 1), make_event(EV_ABS, ABS_Y, -175),
            make_event(EV_SYN, SYN_REPORT, 0)});
  queue(4, {make_event(EV_ABS, ABS_X, 30), make_event(EV_SYN, SYN_DROPPED, 0),
            make_event(EV_SYN, SYN_REPORT, 0), make_event(EV_KEY, BTN_1, 0),
            make_event(EV_SYN, SYN_REPORT, 0)});
  auto live = poll_until(registry, [](const auto& e) {
    return count(e, InputKind::kButton) == 2 && count(e, InputKind::kMotion) >= 3;
  });

  unplug(4);
  const auto rest =
      poll_until(registry, [](const auto& e) { return count(e, InputKind::kDisconnected) == 1; });
  live.insert(live.end(), rest.begin(), rest.end());
  EXPECT_EQ(registry.open_count(), 0u);

  // What was recorded replays to the same events.
  std::vector<RawEvent> recorded;
  {
    std::lock_guard lock(raw_mutex);
    recorded = raws;
  }
  MotionPipeline replay(make_parser(info).value(), direct);
  std::vector<InputEvent> replayed;
  for (const RawEvent& r : recorded)
    replay.feed(r, plugged.opened[0], replayed);
  auto useful = [](std::vector<InputEvent> v) {
    std::erase_if(v, [](const InputEvent& e) {
      return e.kind != InputKind::kMotion && e.kind != InputKind::kButton;
    });
    return v;
  };
  const auto a = useful(live);
  const auto b = useful(replayed);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].kind, b[i].kind) << i;
    EXPECT_EQ(a[i].t_ns, b[i].t_ns) << i;
    EXPECT_EQ(a[i].axes, b[i].axes) << i;
    EXPECT_EQ(a[i].button, b[i].button) << i;
    EXPECT_EQ(a[i].pressed, b[i].pressed) << i;
  }

  // Plugged in again (the kernel gives the node a new number).
  {
    std::lock_guard lock(kernel_.mutex);
    kernel_.sys.gone = false;
  }
  plug(5, "SpaceMouse Compact", 0x256f, 0xc635, six_axis_caps(), "1-4");
  const ScanReport again = registry.scan();
  ASSERT_EQ(again.opened.size(), 1u);
  EXPECT_EQ(registry.reader(again.opened[0])->info().path, node_path(5));
}

}  // namespace
}  // namespace sculpt::hal::evdev_input
