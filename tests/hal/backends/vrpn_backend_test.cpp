// The VRPN tracker client against a scripted server on loopback: the test
// plays the server step by step on one thread (the client only moves inside
// read()), so every exchange is deterministic. No timing is asserted; every
// wait polls with a generous deadline.

#include "sculpt/hal/backends/vrpn_backend.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "sculpt/hal/parsers/vrpn_message.h"

namespace sculpt::hal {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kDeadline = std::chrono::seconds(5);

// One VRPN server, as scripted by the test: listens on 127.0.0.1.
class ScriptedServer {
 public:
  explicit ScriptedServer(uint16_t port = 0) {
    listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    const int one = 1;
    ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(::bind(listen_fd_, reinterpret_cast<sockaddr*>(&a), sizeof a), 0)
        << std::strerror(errno);
    EXPECT_EQ(::listen(listen_fd_, 4), 0);
    socklen_t len = sizeof a;
    ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
  }
  ~ScriptedServer() { go_away(); }
  uint16_t port() const { return port_; }

  /// Waits for the client's connection, pumping the client meanwhile.
  bool accept(VrpnTrackerDevice& client) {
    const auto end = Clock::now() + kDeadline;
    while (Clock::now() < end) {
      RawEvent e;
      client.read(e, 10);
      pollfd p{listen_fd_, POLLIN, 0};
      if (::poll(&p, 1, 10) > 0) {
        conn_fd_ = ::accept(listen_fd_, nullptr, nullptr);
        return conn_fd_ >= 0;
      }
    }
    return false;
  }
  /// Reads exactly n bytes from the client (the client must already have sent them).
  std::vector<uint8_t> receive(size_t n) {
    std::vector<uint8_t> out;
    const auto end = Clock::now() + kDeadline;
    while (out.size() < n && Clock::now() < end) {
      pollfd p{conn_fd_, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      uint8_t buf[256];
      const ssize_t got = ::recv(conn_fd_, buf, std::min(sizeof buf, n - out.size()), 0);
      if (got <= 0) break;
      out.insert(out.end(), buf, buf + got);
    }
    return out;
  }
  void send(std::span<const uint8_t> bytes) {
    ASSERT_EQ(::send(conn_fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL),
              static_cast<ssize_t>(bytes.size()));
  }
  void send_message(int32_t sender, int32_t type, std::span<const uint8_t> payload) {
    send(encode_vrpn_message(sender, type, payload));
  }
  /// Accepts, swaps cookies (checking the client's) and describes the
  /// tracker "Tracker0" as sender 5 and Pos_Quat as type 2.
  void handshake(VrpnTrackerDevice& client) {
    ASSERT_TRUE(accept(client));
    const auto cookie = receive(kVrpnCookieBytes);
    ASSERT_EQ(cookie.size(), kVrpnCookieBytes);
    EXPECT_EQ(check_vrpn_cookie(cookie), VrpnCookieError::kNone);
    send(make_vrpn_cookie());
    send_message(5, kVrpnSenderDescription, encode_vrpn_description("Tracker0"));
    send_message(2, kVrpnTypeDescription, encode_vrpn_description(kVrpnPosQuatType));
  }
  void pose(int32_t sensor, double x_m) {
    send_message(5, 2, encode_vrpn_pos_quat(sensor, {x_m, 0, 0}, {0, 0, 0, 1}));
  }
  /// The server process ends: both sockets close.
  void go_away() {
    if (conn_fd_ >= 0) ::close(conn_fd_);
    if (listen_fd_ >= 0) ::close(listen_fd_);
    conn_fd_ = listen_fd_ = -1;
  }
  void hang_up() {
    if (conn_fd_ >= 0) ::close(conn_fd_);
    conn_fd_ = -1;
  }

 private:
  int listen_fd_ = -1;
  int conn_fd_ = -1;
  uint16_t port_ = 0;
};

struct Client {
  std::vector<std::string> log;
  std::unique_ptr<VrpnTrackerDevice> device;

  explicit Client(uint16_t port, int cookie_timeout_ms = 2000) {
    VrpnOptions o;
    o.tracker = "Tracker0";
    o.host = "127.0.0.1";
    o.port = port;
    o.backoff_initial_ms = 10;
    o.backoff_max_ms = 40;
    o.cookie_timeout_ms = cookie_timeout_ms;
    o.log = [this](std::string_view line) { log.emplace_back(line); };
    auto d = VrpnTrackerDevice::open(std::move(o));
    EXPECT_TRUE(d.ok());
    if (d) device = std::move(d).value();
  }
  /// Reads until `n` events came or the deadline passed.
  std::vector<RawEvent> events(size_t n) {
    std::vector<RawEvent> out;
    const auto end = Clock::now() + kDeadline;
    while (out.size() < n && Clock::now() < end) {
      RawEvent e;
      if (device->read(e, 20) == ReadResult::kEvent) out.push_back(e);
    }
    return out;
  }
  /// Reads until `done()` or the deadline passed.
  template <class F>
  bool until(F done) {
    const auto end = Clock::now() + kDeadline;
    while (!done() && Clock::now() < end) {
      RawEvent e;
      device->read(e, 10);
    }
    return done();
  }
  size_t log_lines_with(std::string_view text) const {
    size_t n = 0;
    for (const std::string& l : log)
      n += l.find(text) != std::string::npos;
    return n;
  }
};

TrackerPose decode(const RawEvent& e) {
  TrackerPose p;
  EXPECT_EQ(decode_vrpn_pos_quat(e.bytes(), p), VrpnPayloadError::kNone);
  return p;
}

TEST(VrpnBackend, CookieExchangeDescriptionsAndTwoSensors) {
  ScriptedServer server;
  Client client(server.port());
  server.handshake(*client.device);
  // The client describes itself like any VRPN client: its sender and type.
  ASSERT_TRUE(client.until([&] { return client.device->streaming(); }));
  const size_t sender_bytes = kVrpnHeaderBytes + 16;  // 4 + "Tracker0\0", padded to 8
  const size_t type_bytes = kVrpnHeaderBytes + 32;    // 4 + "vrpn_Tracker Pos_Quat\0", padded
  const auto hello = server.receive(sender_bytes + type_bytes);
  ASSERT_EQ(hello.size(), sender_bytes + type_bytes);
  VrpnMessage m;
  std::string_view name;
  ASSERT_EQ(next_vrpn_message(hello, m), VrpnFrameResult::kMessage);
  EXPECT_EQ(m.type, kVrpnSenderDescription);
  ASSERT_EQ(decode_vrpn_description(m.payload, name), VrpnPayloadError::kNone);
  EXPECT_EQ(name, "Tracker0");
  ASSERT_EQ(next_vrpn_message(std::span(hello).subspan(sender_bytes), m),
            VrpnFrameResult::kMessage);
  EXPECT_EQ(m.type, kVrpnTypeDescription);
  ASSERT_EQ(decode_vrpn_description(m.payload, name), VrpnPayloadError::kNone);
  EXPECT_EQ(name, kVrpnPosQuatType);
  // Noise a real server sends too: another tracker, another message type,
  // a system message.
  server.send_message(6, kVrpnSenderDescription, encode_vrpn_description("Other"));
  server.send_message(3, kVrpnTypeDescription, encode_vrpn_description("vrpn_Tracker Velocity"));
  server.pose(0, 0.5);
  server.send_message(6, 2, encode_vrpn_pos_quat(0, {9, 9, 9}, {0, 0, 0, 1}));
  server.send_message(5, 3, std::vector<uint8_t>(72, 0));
  server.send_message(0, -3, std::vector<uint8_t>(8, 0));
  server.pose(1, -0.25);
  const auto got = client.events(2);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].size, kVrpnPosQuatBytes);
  EXPECT_EQ(decode(got[0]).sensor, 0);
  EXPECT_DOUBLE_EQ(decode(got[0]).position_mm[0], 500.0);
  EXPECT_EQ(decode(got[1]).sensor, 1);
  EXPECT_DOUBLE_EQ(decode(got[1]).position_mm[0], -250.0);
  const VrpnCounters& c = client.device->counters();
  EXPECT_EQ(c.connects, 1);
  EXPECT_EQ(c.poses, 2);
  EXPECT_EQ(c.other_senders, 1);
  EXPECT_EQ(c.other_types, 1);
  EXPECT_EQ(c.system_messages, 1);
  EXPECT_TRUE(client.log.empty()) << client.log.front();
}

TEST(VrpnBackend, TheNewestPoseOfASensorWins) {
  ScriptedServer server;
  Client client(server.port());
  server.handshake(*client.device);
  std::vector<uint8_t> burst;
  for (int i = 1; i <= 5; ++i) {
    const auto m =
        encode_vrpn_message(5, 2, encode_vrpn_pos_quat(0, {i * 0.001, 0, 0}, {0, 0, 0, 1}));
    burst.insert(burst.end(), m.begin(), m.end());
  }
  server.send(burst);
  ASSERT_TRUE(client.until([&] {
    const auto& c = client.device->counters();
    return c.poses + c.superseded == 5 && c.poses > 0;
  }));
  EXPECT_EQ(client.device->counters().messages, 2 + 5);
}

TEST(VrpnBackend, BadPosesAreCountedAndDropped) {
  ScriptedServer server;
  Client client(server.port());
  server.handshake(*client.device);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  server.send_message(5, 2, encode_vrpn_pos_quat(0, {nan, 0, 0}, {0, 0, 0, 1}));
  const auto whole = encode_vrpn_pos_quat(0, {}, {0, 0, 0, 1});
  server.send_message(5, 2, std::span(whole).first(40));
  server.send_message(5, 2, encode_vrpn_pos_quat(0, {}, {0, 0, 0, 0}));
  server.send_message(9, kVrpnSenderDescription, std::vector<uint8_t>{0, 0, 0, 50, 'x'});
  server.pose(0, 0.125);
  const auto got = client.events(1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_DOUBLE_EQ(decode(got[0]).position_mm[0], 125.0);
  EXPECT_EQ(client.device->counters().bad_poses, 3);
  EXPECT_EQ(client.device->counters().bad_descriptions, 1);
  EXPECT_TRUE(client.device->streaming()) << "bad payloads do not end the connection";
}

TEST(VrpnBackend, ServerGoingAwayIsTrackingLostThenItReconnects) {
  auto server = std::make_unique<ScriptedServer>();
  const uint16_t port = server->port();
  Client client(port);
  server->handshake(*client.device);
  server->pose(0, 0.1);
  ASSERT_EQ(client.events(1).size(), 1u);
  server->go_away();
  auto lost = client.events(1);
  ASSERT_EQ(lost.size(), 1u);
  EXPECT_EQ(lost[0].kind, RawEventKind::kReport);
  EXPECT_EQ(lost[0].size, 0) << "an empty report is 'tracking lost'";
  EXPECT_EQ(client.device->counters().disconnects, 1);
  EXPECT_EQ(client.device->counters().tracking_lost, 1);
  // "closed the connection", or "Connection reset by peer" when the server
  // left the client's descriptions unread: either way one line.
  EXPECT_EQ(client.log.size(), 1u);
  // While the server is down the client keeps trying, and says so once.
  ASSERT_TRUE(client.until([&] { return client.device->counters().failed_connects >= 3; }));
  EXPECT_EQ(client.log.size(), 2u);
  // The server comes back on the same port.
  server = std::make_unique<ScriptedServer>(port);
  server->handshake(*client.device);
  server->pose(1, 0.2);
  const auto again = client.events(1);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(decode(again[0]).sensor, 1);
  EXPECT_EQ(client.device->counters().connects, 2);
}

TEST(VrpnBackend, GarbageCookieEndsTheConnectionWithOneLogLine) {
  ScriptedServer server;
  Client client(server.port());
  ASSERT_TRUE(server.accept(*client.device));
  const std::string junk = "HTTP/1.1 400 Bad Request\r\n\r\n";
  server.send(std::span(reinterpret_cast<const uint8_t*>(junk.data()), junk.size()));
  ASSERT_TRUE(client.until([&] { return client.device->counters().bad_cookies == 1; }));
  EXPECT_EQ(client.log_lines_with("bad cookie"), 1u);
  EXPECT_EQ(client.device->counters().connects, 0);
}

TEST(VrpnBackend, AnOversizedLengthEndsTheConnection) {
  ScriptedServer server;
  Client client(server.port());
  server.handshake(*client.device);
  server.send(std::vector<uint8_t>{0xff, 0xff, 0xff, 0xff, 0, 0, 0, 0});
  ASSERT_TRUE(client.until([&] { return client.device->counters().bad_lengths == 1; }));
  EXPECT_EQ(client.log_lines_with("message length 4294967295"), 1u);
  EXPECT_FALSE(client.device->streaming());
}

TEST(VrpnBackend, AServerThatNeverSendsItsCookieIsDropped) {
  ScriptedServer server;
  Client client(server.port(), /*cookie_timeout_ms=*/30);
  ASSERT_TRUE(server.accept(*client.device));
  ASSERT_TRUE(client.until([&] { return client.device->counters().stalls >= 1; }));
  EXPECT_EQ(client.log_lines_with("no cookie"), 1u);
}

TEST(VrpnBackend, NoServerMeansRetriesNotAHang) {
  uint16_t port = 0;
  {
    ScriptedServer gone;  // a port that was free a moment ago, now closed
    port = gone.port();
  }
  Client client(port);
  RawEvent e;
  for (int i = 0; i < 5; ++i)
    EXPECT_EQ(client.device->read(e, 20), ReadResult::kTimeout);
  EXPECT_GE(client.device->counters().failed_connects, 1);
  EXPECT_EQ(client.log.size(), 1u) << "a server that stays away is reported once";
}

TEST(VrpnBackend, ParsesTheDeviceSpec) {
  auto s = parse_vrpn_spec("vrpn:Tracker0@localhost");
  ASSERT_TRUE(s.ok()) << s.error().message();
  EXPECT_EQ(s->tracker, "Tracker0");
  EXPECT_EQ(s->host, "localhost");
  EXPECT_EQ(s->port, kVrpnDefaultPort);
  s = parse_vrpn_spec("vrpn:DTrack@10.0.0.5:3884");
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->host, "10.0.0.5");
  EXPECT_EQ(s->port, 3884);
  EXPECT_FALSE(parse_vrpn_spec("vrpn:Tracker0").ok());
  EXPECT_FALSE(parse_vrpn_spec("vrpn:@host").ok());
  EXPECT_FALSE(parse_vrpn_spec("vrpn:T@").ok());
  EXPECT_FALSE(parse_vrpn_spec("vrpn:T@host:99999").ok());
  EXPECT_FALSE(parse_vrpn_spec("opentrack:4242").ok());
}

TEST(VrpnBackend, ListsTheTrackerWithoutConnecting) {
  auto options = parse_vrpn_spec("vrpn:Tracker0@localhost");
  ASSERT_TRUE(options.ok());
  auto b = make_vrpn_backend(*options);
  EXPECT_EQ(b->name(), "vrpn");
  auto devices = b->enumerate();
  ASSERT_TRUE(devices.ok());
  ASSERT_EQ(devices->size(), 1u);
  EXPECT_EQ((*devices)[0].id(), "vrpn:Tracker0@localhost:3883");
}

}  // namespace
}  // namespace sculpt::hal
