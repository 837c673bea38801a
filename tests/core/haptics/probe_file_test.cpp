#include "sculpt/core/haptics/probe_file.h"

#include <gtest/gtest.h>

#include "scratch_dir.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <random>
#include <string>

namespace sculpt::core {
namespace {

std::string probe_error(std::string_view text) {
  const auto r = parse_probe_text(text, "p.jsonl");
  return r.ok() ? "(accepted)" : r.error().message();
}

TEST(ProbeFile, ReadsSamplesWithAndWithoutOrientation) {
  const auto r = parse_probe_text(
      "{\"t\": 0, \"at\": [1, 2.5, -3]}\n"
      "\n"
      "  \t\r\n"
      "{\"at\": [4, 5, 6], \"t\": 0.001, \"quat\": [0, 0, 0, 1]}\r\n"
      "{\"t\": 1e-2, \"at\": [1e6, -1e6, 0], \"quat\": [1.0005, 0, 0, 0]}",
      "p.jsonl");
  ASSERT_TRUE(r.ok()) << r.error().message();
  ASSERT_EQ(r->size(), 3u);
  const ProbeSample& a = (*r)[0];
  EXPECT_EQ(a.t_s, 0.0);
  EXPECT_EQ(a.at_vox, glm::vec3(1.0f, 2.5f, -3.0f));
  EXPECT_FALSE(a.orientation);
  const ProbeSample& b = (*r)[1];
  EXPECT_EQ(b.t_s, 0.001);
  EXPECT_EQ(b.at_vox, glm::vec3(4, 5, 6));
  ASSERT_TRUE(b.orientation);
  // glm::quat(w, x, y, z): the file's order.
  EXPECT_EQ(*b.orientation, glm::quat(0, 0, 0, 1));
  EXPECT_EQ(b.orientation->z, 1.0f);
  const ProbeSample& c = (*r)[2];
  EXPECT_EQ(c.at_vox, glm::vec3(1e6f, -1e6f, 0));
  ASSERT_TRUE(c.orientation);
  // Slightly off unit length is accepted and normalised.
  EXPECT_EQ(*c.orientation, glm::quat(1, 0, 0, 0));
}

TEST(ProbeFile, EachProblemIsOneLineNamingTheLine) {
  const std::string ok = "{\"t\": 0, \"at\": [0, 0, 0]}\n";
  const struct {
    std::string text, error;
  } cases[] = {
      {"hello\n", "p.jsonl:1: not a JSON object (invalid JSON at column 1)"},
      {ok + "[1, 2, 3]\n", "p.jsonl:2: not a JSON object"},
      {ok + "\n{\"t\": 1, \"at\": [0, 0, 0]} {}\n",
       "p.jsonl:3: not a JSON object (invalid JSON at column 27)"},
      {ok + "{\"t\": 1}\n", "p.jsonl:2: missing \"at\""},
      {ok + "{\"at\": [0, 0, 0]}\n", "p.jsonl:2: missing \"t\""},
      {ok + "{\"t\": \"1\", \"at\": [0, 0, 0]}\n", "p.jsonl:2: \"t\" is not a finite number"},
      {ok + "{\"t\": null, \"at\": [0, 0, 0]}\n", "p.jsonl:2: \"t\" is not a finite number"},
      {"{\"t\": -0.5, \"at\": [0, 0, 0]}\n", "p.jsonl:1: the first \"t\" must be >= 0 (got -0.5)"},
      {ok + "{\"t\": 2.5, \"at\": [0, 0, 0]}\n{\"t\": 2.5, \"at\": [0, 0, 0]}\n",
       "p.jsonl:3: \"t\" must increase strictly (2.5 after 2.5)"},
      {ok + "{\"t\": 2, \"at\": [0, 0, 0]}\n{\"t\": 1, \"at\": [0, 0, 0]}\n",
       "p.jsonl:3: \"t\" must increase strictly (1 after 2)"},
      {ok + "{\"t\": 1, \"at\": [0, 0]}\n", "p.jsonl:2: \"at\" must be 3 finite numbers"},
      {ok + "{\"t\": 1, \"at\": [0, 0, 0, 0]}\n", "p.jsonl:2: \"at\" must be 3 finite numbers"},
      {ok + "{\"t\": 1, \"at\": [0, \"0\", 0]}\n", "p.jsonl:2: \"at\" must be 3 finite numbers"},
      {ok + "{\"t\": 1, \"at\": {\"x\": 0}}\n", "p.jsonl:2: \"at\" must be 3 finite numbers"},
      {ok + "{\"t\": 1, \"at\": [0, 1000000.5, 0]}\n",
       "p.jsonl:2: \"at\" is out of range (1000000.5, at most 1e6 voxels either way)"},
      {ok + "{\"t\": 1, \"at\": [0, 0, 0], \"quat\": [1, 0, 0]}\n",
       "p.jsonl:2: \"quat\" must be 4 finite numbers of length 1 (within 1e-3)"},
      {ok + "{\"t\": 1, \"at\": [0, 0, 0], \"quat\": [1.002, 0, 0, 0]}\n",
       "p.jsonl:2: \"quat\" must be 4 finite numbers of length 1 (within 1e-3)"},
      {ok + "{\"t\": 1, \"at\": [0, 0, 0], \"quat\": [0, 0, 0, 0]}\n",
       "p.jsonl:2: \"quat\" must be 4 finite numbers of length 1 (within 1e-3)"},
      {ok + "{\"t\": 1, \"at\": [0, 0, 0], \"quat\": [1e300, 1e300, 0, 0]}\n",
       "p.jsonl:2: \"quat\" must be 4 finite numbers of length 1 (within 1e-3)"},
      {ok + "{\"t\": 1, \"at\": [0, 0, 0], \"foo\": 1}\n", "p.jsonl:2: unknown key \"foo\""},
      {ok + "{\"t\": 1, \"at\": [0, 0, 0], \"a\\nb\": 1}\n", "p.jsonl:2: unknown key \"a\\nb\""},
      {"", "p.jsonl: no probe samples"},
      {"\n  \n\r\n", "p.jsonl: no probe samples"},
  };
  for (const auto& c : cases)
    EXPECT_EQ(probe_error(c.text), c.error) << c.text;
}

TEST(ProbeFile, NanAndInfinityGetAClearError) {
  // JSON has no such numbers, but Python's json.dumps writes them.
  for (const char* word : {"NaN", "nan", "Infinity", "-Infinity", "inf"}) {
    const std::string text = "{\"t\": 0, \"at\": [0, " + std::string(word) + ", 0]}\n";
    const std::string error = probe_error(text);
    EXPECT_EQ(error.rfind("p.jsonl:1: not a JSON object (invalid JSON at column ", 0), 0u) << error;
    EXPECT_NE(error.find("NaN and Infinity are not JSON numbers"), std::string::npos) << error;
  }
  EXPECT_EQ(probe_error("{\"t\": 1e400, \"at\": [0, 0, 0]}"),
            "p.jsonl:1: a number is out of range for a double");
}

TEST(ProbeFile, ATraceLineWithANonFiniteNumberIsCaughtBeforeWriting) {
  // The trace reader refuses what format_trace_line writes as null.
  TraceLine line;
  line.force_n = {0.5f, 0.0f, -1.0f};
  EXPECT_TRUE(trace_line_finite(line));
  TraceLine nan_force = line;
  nan_force.force_n.y = std::nanf("");
  TraceLine inf_torque = line;
  inf_torque.torque_nm = glm::vec3(0.0f, std::numeric_limits<float>::infinity(), 0.0f);
  TraceLine inf_time = line;
  inf_time.t_s = std::numeric_limits<double>::infinity();
  for (const TraceLine& bad : {nan_force, inf_torque, inf_time}) {
    EXPECT_FALSE(trace_line_finite(bad));
    EXPECT_FALSE(parse_trace_text(format_trace_line(bad), "t").ok());
  }
}

TEST(ProbeFile, HostileBytesGiveAnErrorNotACrash) {
  using namespace std::string_literals;
  EXPECT_EQ(probe_error("{\"t\": 0,\0 \"at\": [0, 0, 0]}"s),
            "p.jsonl:1: not a JSON object (invalid JSON at column 9)");
  EXPECT_EQ(probe_error("{\"t\": 0, \"at\": [0, 0, 0], \"\xff\xfe\": 1}"),
            "p.jsonl:1: not a JSON object (invalid JSON at column 28)");
  EXPECT_EQ(probe_error(std::string(2000, '[') + std::string(2000, ']')),
            "p.jsonl:1: not a JSON object");
  const std::string long_line = "{\"t\": 0, \"at\": [0, 0, 0]}" + std::string(4072, ' ');
  ASSERT_EQ(long_line.size(), kMaxProbeLineBytes + 1);
  EXPECT_EQ(probe_error("\n" + long_line), "p.jsonl:2: line too long (more than 4096 bytes)");
  EXPECT_EQ(probe_error(long_line.substr(1) + "\n").rfind("p.jsonl:1: not a JSON object", 0), 0u)
      << "4096 bytes are parsed";
}

TEST(ProbeFile, AtMostTenMillionLines) {
  const std::string sample = "{\"t\": 0, \"at\": [0, 0, 0]}\n";
  std::string text(kMaxProbeLines - 1, '\n');
  EXPECT_TRUE(parse_probe_text(text + sample, "p.jsonl").ok());
  EXPECT_EQ(probe_error(text + "\n" + sample),
            "p.jsonl:10000001: too many lines (at most 10000000)");
}

TEST(ProbeFile, ReadsAFileAndNamesItInErrors) {
  sculpt::test::ScratchDir dir;
  const std::string path = dir.file("probe.jsonl");
  std::ofstream(path) << "{\"t\": 0, \"at\": [1, 2, 3]}\n{\"t\": 0.5, \"at\": [1, 2, 4]}\n"
                      << "{\"t\": 0.25, \"at\": [1, 2, 4]}\n";
  const auto bad = read_probe_file(path);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message(), path + ":3: \"t\" must increase strictly (0.25 after 0.5)");

  std::ofstream(path) << "{\"t\": 0, \"at\": [1, 2, 3]}\n";
  const auto good = read_probe_file(path);
  ASSERT_TRUE(good.ok()) << good.error().message();
  EXPECT_EQ(good->at(0).at_vox, glm::vec3(1, 2, 3));

  const auto missing = read_probe_file(dir.file("missing.jsonl"));
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().message(),
            dir.file("missing.jsonl") + ": cannot open: No such file or directory");
  const auto folder = read_probe_file(dir.path());
  ASSERT_FALSE(folder.ok());
  EXPECT_EQ(folder.error().message(), dir.path().string() + ": cannot read: Is a directory");
}

TEST(TraceLine, FormatsOneCompactJsonObject) {
  TraceLine l;
  l.t_s = 0.001;
  l.device_vox = {1.5f, 2, -3};
  l.proxy_vox = {1.5f, 2, -2.75f};
  l.force_n = {0, 0, 0.1f};
  l.contact = true;
  EXPECT_EQ(format_trace_line(l),
            "{\"t\":0.001,\"device\":[1.5,2,-3],\"proxy\":[1.5,2,-2.75],"
            "\"force\":[0,0,0.100000001],\"contact\":true}\n");
  l.torque_nm = glm::vec3(-0.0f, 1e-3f, 3e38f);
  l.contact = false;
  EXPECT_EQ(format_trace_line(l),
            "{\"t\":0.001,\"device\":[1.5,2,-3],\"proxy\":[1.5,2,-2.75],"
            "\"force\":[0,0,0.100000001],\"torque\":[-0.0,0.00100000005,3.00000001e+38],"
            "\"contact\":false}\n");
}

bool same_bits(glm::vec3 a, glm::vec3 b) {
  for (int i = 0; i < 3; ++i)
    if (std::bit_cast<uint32_t>(a[i]) != std::bit_cast<uint32_t>(b[i])) return false;
  return true;
}

TEST(TraceLine, FormatThenParseGivesTheSameBits) {
  std::mt19937 rng(7);
  // Any finite float: random bit patterns cover denormals, huge and tiny values.
  auto any_float = [&] {
    for (;;) {
      const float f = std::bit_cast<float>(static_cast<uint32_t>(rng()));
      if (std::isfinite(f)) return f;
    }
  };
  auto any_vec3 = [&] { return glm::vec3(any_float(), any_float(), any_float()); };
  std::vector<TraceLine> lines;
  std::string text;
  for (int i = 0; i < 2000; ++i) {
    TraceLine l;
    l.t_s = std::bit_cast<double>((uint64_t{rng()} << 32) | rng());
    if (!std::isfinite(l.t_s)) l.t_s = i * 1e-3;
    l.device_vox = any_vec3();
    l.proxy_vox = any_vec3();
    l.force_n = any_vec3();
    if (i % 2) l.torque_nm = any_vec3();
    l.contact = i % 3 == 0;
    lines.push_back(l);
    text += format_trace_line(l);
  }
  // The edges random bits rarely hit.
  constexpr float kMax = std::numeric_limits<float>::max();
  constexpr float kDenormMin = std::numeric_limits<float>::denorm_min();
  lines.push_back({-0.0, {-0.0f, kMax, -kMax}, {kDenormMin, -kDenormMin, 0.1f}, {}, {}, true});
  text += format_trace_line(lines.back());

  const auto back = parse_trace_text(text, "trace.jsonl");
  ASSERT_TRUE(back.ok()) << back.error().message();
  ASSERT_EQ(back->size(), lines.size());
  for (size_t i = 0; i < lines.size(); ++i) {
    const TraceLine& a = lines[i];
    const TraceLine& b = (*back)[i];
    EXPECT_EQ(std::bit_cast<uint64_t>(a.t_s), std::bit_cast<uint64_t>(b.t_s)) << i;
    EXPECT_TRUE(same_bits(a.device_vox, b.device_vox)) << i;
    EXPECT_TRUE(same_bits(a.proxy_vox, b.proxy_vox)) << i;
    EXPECT_TRUE(same_bits(a.force_n, b.force_n)) << i;
    ASSERT_EQ(a.torque_nm.has_value(), b.torque_nm.has_value()) << i;
    if (a.torque_nm) {
      EXPECT_TRUE(same_bits(*a.torque_nm, *b.torque_nm)) << i;
    }
    EXPECT_EQ(a.contact, b.contact) << i;
  }
}

TEST(TraceLine, ParseRefusesWhatFormatNeverWrites) {
  auto error = [](std::string_view text) {
    const auto r = parse_trace_text(text, "t.jsonl");
    return r.ok() ? "(accepted)" : r.error().message();
  };
  TraceLine nan_force;
  nan_force.force_n.y = std::numeric_limits<float>::quiet_NaN();
  const std::string ok = format_trace_line(TraceLine{});
  EXPECT_EQ(error(ok + format_trace_line(nan_force)),
            "t.jsonl:2: \"force\" must be 3 finite numbers");
  EXPECT_EQ(error("{\"t\":0,\"device\":[0,0,0],\"proxy\":[0,0,0],\"force\":[0,0,0]}"),
            "t.jsonl:1: missing \"contact\"");
  EXPECT_EQ(error("{\"t\":0,\"device\":[0,0,0],\"proxy\":[0,0,0],\"force\":[0,0,0],\"contact\":1}"),
            "t.jsonl:1: \"contact\" must be true or false");
  EXPECT_EQ(error("{\"t\":0,\"device\":[0,0,3.4028236e38],\"proxy\":[0,0,0],\"force\":[0,0,0],"
                  "\"contact\":true}"),
            "t.jsonl:1: \"device\" must be 3 finite numbers");
  EXPECT_EQ(error("{\"t\":0,\"device\":[0,0,0],\"force\":[0,0,0],\"contact\":true}"),
            "t.jsonl:1: missing \"proxy\"");
  EXPECT_EQ(error(ok + "{\"t\":0,\"at\":[0,0,0]}"), "t.jsonl:2: unknown key \"at\"");
  EXPECT_EQ(error("\n"), "t.jsonl: no trace lines");
}

}  // namespace
}  // namespace sculpt::core
