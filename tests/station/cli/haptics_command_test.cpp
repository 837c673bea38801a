// The `sculpt haptics trace` command-line contract.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <glm/geometric.hpp>

#include "run_sculpt.h"
#include "scratch_dir.h"
#include "sculpt/core/haptics/probe_file.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;

// A device pressed straight down into the top of a radius-10 ball (centre
// 19.5) and back out, 0.25 voxel a millisecond.
void write_press_probe(const std::string& path) {
  std::ofstream out(path);
  int i = 0;
  for (float z = 34.0f; z >= 26.0f; z -= 0.25f, ++i)
    out << "{\"t\": " << 0.001 * i << ", \"at\": [19.5, 19.5, " << z << "]}\n";
  for (float z = 26.0f; z <= 34.0f; z += 0.25f, ++i)
    out << "{\"t\": " << 0.001 * i << ", \"at\": [19.5, 19.5, " << z << "]}\n";
}

TEST(HapticsCommand, TraceGivesTheSpringForceLineByLine) {
  sculpt::test::ScratchDir scratch;
  ASSERT_TRUE(core::write_nrrd(scratch.file("ball.nrrd"), core::sphere_density(40, 0.25f)).ok());
  write_press_probe(scratch.file("probe.jsonl"));
  const CommandResult r = run_sculpt(
      "haptics trace " + scratch.file("ball.nrrd") + " --probe " + scratch.file("probe.jsonl") +
      " --stiffness 2 --voxel-mm 0.5 --max-force 3 -o " + scratch.file("trace.jsonl"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto trace = core::parse_trace_text(read_text(scratch.file("trace.jsonl")), "trace");
  ASSERT_TRUE(trace.ok()) << trace.error().message();
  ASSERT_EQ(trace->size(), 66u);
  int contact = 0;
  for (const core::TraceLine& line : *trace) {
    // The proxy rests on the ball's top (z 29.5 + radius 1), never inside.
    EXPECT_GE(line.proxy_vox.z, 30.5f - 0.1f);
    if (!line.contact) {
      EXPECT_EQ(line.force_n, glm::vec3(0.0f));
      continue;
    }
    ++contact;
    const glm::vec3 spring = 2.0f * 0.5f * (line.proxy_vox - line.device_vox);
    const float length = glm::length(spring);
    const glm::vec3 expected = length > 3.0f ? spring * (3.0f / length) : spring;
    EXPECT_LT(glm::length(line.force_n - expected), 1e-4f) << "t " << line.t_s;
  }
  EXPECT_GT(contact, 30);
}

TEST(HapticsCommand, BadInputGetsOneLineNamingItAndNoOutput) {
  sculpt::test::ScratchDir scratch;
  ASSERT_TRUE(core::write_nrrd(scratch.file("ball.nrrd"), core::sphere_density(24, 0.25f)).ok());
  std::ofstream(scratch.file("back.jsonl")) << "{\"t\": 0.002, \"at\": [1, 2, 3]}\n"
                                               "{\"t\": 0.001, \"at\": [1, 2, 3]}\n";
  const std::string out = scratch.file("t.jsonl");
  const CommandResult back = run_sculpt("haptics trace " + scratch.file("ball.nrrd") + " --probe " +
                                        scratch.file("back.jsonl") + " -o " + out);
  EXPECT_EQ(back.exit_code, 1);
  EXPECT_EQ(line_count(back.err), 1) << back.err;
  EXPECT_NE(back.err.find("back.jsonl:2:"), std::string::npos) << back.err;
  EXPECT_FALSE(fs::exists(out));

  ASSERT_TRUE(core::write_nrrd(scratch.file("f.nrrd"), core::DenseGrid<float>(glm::ivec3(4))).ok());
  write_press_probe(scratch.file("p.jsonl"));
  const CommandResult f32 = run_sculpt("haptics trace " + scratch.file("f.nrrd") + " --probe " +
                                       scratch.file("p.jsonl") + " -o " + out);
  EXPECT_EQ(f32.exit_code, 1);
  EXPECT_EQ(line_count(f32.err), 1) << f32.err;
  EXPECT_NE(f32.err.find("f.nrrd"), std::string::npos) << f32.err;
  EXPECT_FALSE(fs::exists(out));

  for (const std::string option :
       {"--radius nan", "--stiffness -1", "--friction 0.2", "--max-force inf", "--voxel-mm 0"}) {
    const CommandResult bad =
        run_sculpt("haptics trace " + scratch.file("ball.nrrd") + " --probe " +
                   scratch.file("p.jsonl") + " " + option + " -o " + out);
    EXPECT_EQ(bad.exit_code, 2) << option;
    EXPECT_FALSE(fs::exists(out)) << option;
  }
  const CommandResult friction =
      run_sculpt("haptics trace " + scratch.file("ball.nrrd") + " --probe " +
                 scratch.file("p.jsonl") + " --friction 0.2,0.5 -o " + out);
  EXPECT_EQ(friction.exit_code, 1);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace sculpt::station::test
