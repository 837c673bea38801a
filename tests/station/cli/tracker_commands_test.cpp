// Network trackers from the command line: `sculpt record --device
// opentrack:PORT` records datagrams sent over loopback and its replay gives
// their poses back; `sculpt devices` lists a tracker only when asked.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "free_udp_port.h"

#include "scratch_dir.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "run_sculpt.h"
#include "sculpt/hal/parsers/opentrack_datagram.h"

namespace sculpt::station::test {
namespace {

TEST(TrackerCommands, RecordsOpenTrackDatagramsAndReplaysTheirPoses) {
  sculpt::test::ScratchDir scratch;
  const std::string session = scratch.file("ot.scs");
  // Records for a second at `port` while sending to it until the recorder
  // exits (it binds a moment after it starts, so the first datagrams may
  // find no one), bounded in case it never does.
  int sent = 0;
  auto record_at = [&](uint16_t port) {
    std::atomic<bool> done{false};
    CommandResult recorded;
    std::thread recorder([&] {
      recorded = run_sculpt("record --device opentrack:" + std::to_string(port) +
                            " --seconds 1 -o " + session);
      done.store(true);
    });
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(port);
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!done.load() && std::chrono::steady_clock::now() < deadline) {
      // x walks 0, 0.1, ... cm, always a whole number of mm.
      const auto bytes = hal::encode_opentrack_datagram(0.1 * (sent % 100), 2.0, 3.0, 0, 0, 0);
      ::sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to),
               sizeof to);
      ++sent;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ::close(fd);
    recorder.join();
    return recorded;
  };
  // The port was free a moment ago; a test running beside this one (or this
  // test's own sending socket, bound by its first sendto before the
  // recorder binds) may take it in between: then another port.
  uint16_t port = 0;
  CommandResult recorded;
  for (int attempt = 0; attempt < 5; ++attempt) {
    port = sculpt::test::free_udp_port();
    ASSERT_NE(port, 0);
    recorded = record_at(port);
    if (recorded.err.find("Address already in use") == std::string::npos) break;
  }
  ASSERT_EQ(recorded.exit_code, 0) << recorded.err;
  EXPECT_NE(recorded.out.find("recording opentrack:" + std::to_string(port)), std::string::npos)
      << recorded.out;

  const CommandResult replayed =
      run_sculpt("replay " + session + " --fast --samples " + scratch.file("s.jsonl"));
  ASSERT_EQ(replayed.exit_code, 0) << replayed.err;
  std::ifstream in(scratch.file("s.jsonl"));
  int poses = 0;
  for (std::string line; std::getline(in, line);) {
    const auto j = nlohmann::json::parse(line);
    if (!j.contains("pose")) continue;
    ++poses;
    const double x_mm = j["pose"]["position_mm"][0].get<double>();
    EXPECT_NEAR(x_mm, std::round(x_mm), 1e-9) << line;
    EXPECT_NEAR(j["pose"]["position_mm"][1].get<double>(), 20.0, 1e-9) << line;
    EXPECT_NEAR(j["pose"]["position_mm"][2].get<double>(), 30.0, 1e-9) << line;
  }
  EXPECT_GT(poses, 0) << "no datagram reached the recording (" << sent << " sent)";
}

TEST(TrackerCommands, ABadTrackerSpecIsOneClearError) {
  sculpt::test::ScratchDir scratch;
  const CommandResult r =
      run_sculpt("record --device opentrack:99999 --seconds 1 -o " + scratch.file("x.scs"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("99999"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(TrackerCommands, DevicesListsATrackerOnlyWhenANamedOne) {
  const CommandResult plain = run_sculpt("devices --json");
  EXPECT_EQ(plain.out.find("opentrack"), std::string::npos) << plain.out;
  const CommandResult asked = run_sculpt("devices --json --device opentrack:4250");
  const auto j = nlohmann::json::parse(asked.out, nullptr, /*allow_exceptions=*/false);
  ASSERT_FALSE(j.is_discarded()) << asked.out << asked.err;
  EXPECT_NE(asked.out.find("opentrack:4250"), std::string::npos) << asked.out;
  const CommandResult wrong = run_sculpt("devices --device hidapi:/dev/hidraw0");
  EXPECT_EQ(wrong.exit_code, 1);
  EXPECT_NE(wrong.err.find("not a tracker"), std::string::npos) << wrong.err;
}

}  // namespace
}  // namespace sculpt::station::test
