// A tracker opened through the registry, live over loopback, gives the same
// pose events as its recorded raw reports fed through the replay's pipeline:
// what makes a tracker's session replay bit for bit.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "free_udp_port.h"

#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "sculpt/hal/input/motion_pipeline.h"
#include "sculpt/hal/parsers/make_parser.h"
#include "sculpt/hal/parsers/opentrack_datagram.h"
#include "sculpt/hal/registry/device_registry.h"
#include "sculpt/hal/registry/tracker_backends.h"

namespace sculpt::hal {
namespace {

bool same_event(const InputEvent& a, const InputEvent& b) {
  return a.kind == b.kind && a.t_ns == b.t_ns && a.has_pose == b.has_pose &&
         a.pose.position_mm == b.pose.position_mm && a.pose.quat_wxyz == b.pose.quat_wxyz;
}

TEST(TrackerLiveReplay, LivePoseEventsEqualTheirRecordingReplayed) {
  std::mutex raw_mutex;
  std::vector<RawEvent> raws;
  ReaderOptions options;
  options.on_raw = [&](const RawEvent& e) {
    std::lock_guard lock(raw_mutex);
    raws.push_back(e);
  };
  DeviceRegistry registry({}, NormalizerConfig{}, options);
  // A port free a moment ago (the tracker binds it as it is added), another
  // if something took it in between.
  uint16_t port = 0;
  Result<std::string> spec = Error("no port tried");
  for (int attempt = 0; attempt < 5; ++attempt) {
    port = sculpt::test::free_udp_port();
    ASSERT_NE(port, 0);
    spec = add_named_tracker(registry, "opentrack:" + std::to_string(port));
    if (spec.ok() || spec.error().message().find("Address already in use") == std::string::npos)
      break;
  }
  ASSERT_TRUE(spec.ok()) << spec.error().message();
  auto id = registry.open_device(*spec);
  ASSERT_TRUE(id.ok()) << id.error().message();
  const DeviceInfo info = registry.reader(*id)->info();

  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  for (int i = 0; i < 20; ++i) {
    const auto bytes = encode_opentrack_datagram(0.5 * i, 1.0, -2.0, 3.0 * i, 10.0, -5.0);
    ::sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ::close(fd);
  // The datagrams stop: the receiver reports tracking lost, the last event
  // this test waits for (bounded).
  std::vector<InputEvent> live;
  InputFrame frame;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  bool lost = false;
  while (!lost && std::chrono::steady_clock::now() < deadline) {
    frame.clear();
    registry.poll(frame, 0);
    for (const InputEvent& e : frame.events) {
      if (e.kind == InputKind::kMotion || e.kind == InputKind::kTrackingLost) live.push_back(e);
      lost |= e.kind == InputKind::kTrackingLost;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(lost) << "no tracking lost within 10 s";
  ASSERT_GT(live.size(), 1u) << "no pose arrived";
  EXPECT_TRUE(live.front().has_pose);

  std::vector<RawEvent> recorded;
  {
    std::lock_guard lock(raw_mutex);
    recorded = raws;
  }
  MotionPipeline replay(make_parser(info).value(), NormalizerConfig{});
  std::vector<InputEvent> replayed;
  for (const RawEvent& r : recorded)
    replay.feed(r, *id, replayed);
  std::erase_if(replayed, [](const InputEvent& e) {
    return e.kind != InputKind::kMotion && e.kind != InputKind::kTrackingLost;
  });
  ASSERT_EQ(replayed.size(), live.size());
  for (size_t i = 0; i < live.size(); ++i)
    EXPECT_TRUE(same_event(live[i], replayed[i])) << "event " << i;
}

}  // namespace
}  // namespace sculpt::hal
