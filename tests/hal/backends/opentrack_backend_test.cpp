// The OpenTrack receiver over a real loopback UDP socket: the test is the
// sender. Bound to an ephemeral port, so runs never clash. No timing is
// asserted; every wait polls with a generous deadline.

#include "sculpt/hal/backends/opentrack_backend.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <limits>
#include <vector>

#include "sculpt/hal/parsers/opentrack_datagram.h"

namespace sculpt::hal {
namespace {

// A UDP socket on loopback that sends to the receiver's port.
class Sender {
 public:
  explicit Sender(uint16_t to_port) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    to_.sin_family = AF_INET;
    to_.sin_port = htons(to_port);
    to_.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  }
  ~Sender() { ::close(fd_); }
  void send(std::span<const uint8_t> bytes) {
    ASSERT_EQ(
        ::sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&to_), sizeof to_),
        static_cast<ssize_t>(bytes.size()));
  }
  void pose(double x_cm) { send(encode_opentrack_datagram(x_cm, 0, 0, 0, 0, 0)); }

 private:
  int fd_ = -1;
  sockaddr_in to_{};
};

std::unique_ptr<OpenTrackDevice> open_ephemeral(int lost_after_ms = 250) {
  OpenTrackOptions o;
  o.port = 0;
  o.lost_after_ms = lost_after_ms;
  auto d = OpenTrackDevice::open(o);
  EXPECT_TRUE(d.ok()) << d.error().message();
  return d ? std::move(d).value() : nullptr;
}

// Reads until an event arrives or 5 s pass.
bool read_event(OpenTrackDevice& d, RawEvent& out) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (std::chrono::steady_clock::now() < deadline) {
    if (d.read(out, 50) == ReadResult::kEvent) return true;
  }
  return false;
}

double x_mm(const RawEvent& e) {
  TrackerPose p;
  EXPECT_EQ(decode_opentrack_datagram(e.bytes(), p), OpenTrackDatagramError::kNone);
  return p.position_mm[0];
}

TEST(OpenTrackBackend, DeliversTheDatagramAsARecordableReport) {
  auto d = open_ephemeral();
  ASSERT_TRUE(d);
  ASSERT_NE(d->bound_port(), 0);
  Sender s(d->bound_port());
  s.pose(12.5);
  RawEvent e;
  ASSERT_TRUE(read_event(*d, e));
  EXPECT_EQ(e.kind, RawEventKind::kReport);
  EXPECT_EQ(e.size, kOpenTrackDatagramBytes);
  EXPECT_GT(e.t_ns, 0);
  // The recorded bytes decode to the pose again.
  EXPECT_DOUBLE_EQ(x_mm(e), 125.0);
  EXPECT_EQ(d->counters().accepted, 1);
}

TEST(OpenTrackBackend, DrainsToTheNewestDatagram) {
  auto d = open_ephemeral();
  ASSERT_TRUE(d);
  Sender s(d->bound_port());
  for (int i = 1; i <= 5; ++i)
    s.pose(i);
  // Loopback delivers in sendto(): all five are queued before the read.
  RawEvent e;
  ASSERT_TRUE(read_event(*d, e));
  EXPECT_DOUBLE_EQ(x_mm(e), 50.0);
  EXPECT_EQ(d->counters().datagrams, 5);
  EXPECT_EQ(d->counters().superseded, 4);
  EXPECT_EQ(d->counters().accepted, 1);
  EXPECT_EQ(d->read(e, 0), ReadResult::kTimeout) << "nothing left after the drain";
}

TEST(OpenTrackBackend, CountsAndDropsShortLongAndNotFiniteDatagrams) {
  auto d = open_ephemeral();
  ASSERT_TRUE(d);
  Sender s(d->bound_port());
  const auto good = encode_opentrack_datagram(3, 0, 0, 0, 0, 0);
  s.send(std::span(good.data(), 40));
  std::vector<uint8_t> longer(200, 0);
  s.send(longer);
  s.send(std::span(good.data(), 0));
  s.send(encode_opentrack_datagram(std::numeric_limits<double>::quiet_NaN(), 0, 0, 0, 0, 0));
  s.send(encode_opentrack_datagram(0, 0, 0, std::numeric_limits<double>::infinity(), 0, 0));
  s.send(good);
  RawEvent e;
  ASSERT_TRUE(read_event(*d, e));
  EXPECT_DOUBLE_EQ(x_mm(e), 30.0);
  const OpenTrackCounters& c = d->counters();
  EXPECT_EQ(c.datagrams, 6);
  EXPECT_EQ(c.short_datagrams, 2);
  EXPECT_EQ(c.long_datagrams, 1);
  EXPECT_EQ(c.not_finite, 2);
  EXPECT_EQ(c.accepted, 1);
}

TEST(OpenTrackBackend, OnlyBadDatagramsDeliverNothing) {
  auto d = open_ephemeral();
  ASSERT_TRUE(d);
  Sender s(d->bound_port());
  const auto good = encode_opentrack_datagram(3, 0, 0, 0, 0, 0);
  s.send(std::span(good.data(), 47));
  RawEvent e;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (d->counters().datagrams == 0 && std::chrono::steady_clock::now() < deadline)
    EXPECT_EQ(d->read(e, 20), ReadResult::kTimeout);
  EXPECT_EQ(d->counters().short_datagrams, 1);
  EXPECT_EQ(d->counters().accepted, 0);
}

TEST(OpenTrackBackend, LocksInTheFirstSenderAndDropsOthers) {
  auto d = open_ephemeral();
  ASSERT_TRUE(d);
  Sender first(d->bound_port());
  Sender intruder(d->bound_port());
  first.pose(1);
  RawEvent e;
  ASSERT_TRUE(read_event(*d, e));
  EXPECT_FALSE(d->locked_sender().empty());
  EXPECT_EQ(d->locked_sender().rfind("127.0.0.1:", 0), 0u) << d->locked_sender();
  intruder.pose(99);
  first.pose(2);
  intruder.pose(98);
  ASSERT_TRUE(read_event(*d, e));
  EXPECT_DOUBLE_EQ(x_mm(e), 20.0) << "the intruder's pose must never win";
  EXPECT_EQ(d->counters().foreign_sender, 2);
  EXPECT_EQ(d->counters().accepted, 2);
}

TEST(OpenTrackBackend, BadDatagramsDoNotLockASender) {
  auto d = open_ephemeral();
  ASSERT_TRUE(d);
  Sender noise(d->bound_port());
  Sender tracker(d->bound_port());
  noise.send(std::vector<uint8_t>(10, 1));
  tracker.pose(4);
  RawEvent e;
  ASSERT_TRUE(read_event(*d, e));
  EXPECT_DOUBLE_EQ(x_mm(e), 40.0);
  EXPECT_EQ(d->counters().foreign_sender, 0);
}

TEST(OpenTrackBackend, SilenceIsReportedOnceAsTrackingLostThenTrackingResumes) {
  auto d = open_ephemeral(/*lost_after_ms=*/30);
  ASSERT_TRUE(d);
  Sender s(d->bound_port());
  RawEvent e;
  EXPECT_EQ(d->read(e, 40), ReadResult::kTimeout) << "no loss before tracking ever started";
  s.pose(1);
  ASSERT_TRUE(read_event(*d, e));
  ASSERT_EQ(e.size, kOpenTrackDatagramBytes);
  ASSERT_TRUE(read_event(*d, e));
  EXPECT_EQ(e.kind, RawEventKind::kReport);
  EXPECT_EQ(e.size, 0) << "an empty report is 'tracking lost'";
  EXPECT_EQ(d->counters().tracking_lost, 1);
  EXPECT_EQ(d->read(e, 60), ReadResult::kTimeout) << "lost is reported once";
  s.pose(2);
  ASSERT_TRUE(read_event(*d, e));
  EXPECT_DOUBLE_EQ(x_mm(e), 20.0);
}

TEST(OpenTrackBackend, BindsToLoopbackByDefaultAndRefusesABadAddress) {
  EXPECT_EQ(OpenTrackOptions{}.listen_address, "127.0.0.1");
  OpenTrackOptions o;
  o.port = 0;
  o.listen_address = "not-an-address";
  auto d = OpenTrackDevice::open(o);
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message().find("not-an-address"), std::string::npos);
}

TEST(OpenTrackBackend, APortInUseIsAnErrorNamingIt) {
  auto first = open_ephemeral();
  ASSERT_TRUE(first);
  OpenTrackOptions o;
  o.port = first->bound_port();
  auto second = OpenTrackDevice::open(o);
  ASSERT_FALSE(second.ok());
  EXPECT_NE(second.error().message().find(std::to_string(o.port)), std::string::npos)
      << second.error().message();
}

TEST(OpenTrackBackend, ListsOneListenerWithoutBindingIt) {
  auto b = make_opentrack_backend();
  EXPECT_EQ(b->name(), "opentrack");
  auto devices = b->enumerate();
  ASSERT_TRUE(devices.ok());
  ASSERT_EQ(devices->size(), 1u);
  EXPECT_EQ((*devices)[0].id(), "opentrack:4242");
}

TEST(OpenTrackBackend, ParsesTheDeviceSpec) {
  auto plain = parse_opentrack_spec("opentrack");
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain->port, kOpenTrackDefaultPort);
  auto port = parse_opentrack_spec("opentrack:5555");
  ASSERT_TRUE(port.ok());
  EXPECT_EQ(port->port, 5555);
  EXPECT_FALSE(parse_opentrack_spec("opentrack:0").ok());
  EXPECT_FALSE(parse_opentrack_spec("opentrack:70000").ok());
  EXPECT_FALSE(parse_opentrack_spec("opentrack:12x").ok());
  EXPECT_FALSE(parse_opentrack_spec("vrpn:x@y").ok());
}

}  // namespace
}  // namespace sculpt::hal
