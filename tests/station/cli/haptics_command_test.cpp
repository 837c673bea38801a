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

TEST(HapticsCommand, ATraceIsTheSameRunTwice) {
  sculpt::test::ScratchDir scratch;
  ASSERT_TRUE(core::write_nrrd(scratch.file("ball.nrrd"), core::sphere_density(40, 0.25f)).ok());
  write_press_probe(scratch.file("probe.jsonl"));
  const std::string args = "haptics trace " + scratch.file("ball.nrrd") + " --probe " +
                           scratch.file("probe.jsonl") + " --friction 0.4,0.3 --damping 5 -o ";
  ASSERT_EQ(run_sculpt(args + scratch.file("a.jsonl")).exit_code, 0);
  ASSERT_EQ(run_sculpt(args + scratch.file("b.jsonl")).exit_code, 0);
  EXPECT_EQ(read_text(scratch.file("a.jsonl")), read_text(scratch.file("b.jsonl")));
}

TEST(HapticsCommand, AToolShapedTraceHasTorqueAndACubeRestsOnTheBall) {
  sculpt::test::ScratchDir scratch;
  ASSERT_TRUE(core::write_nrrd(scratch.file("ball.nrrd"), core::sphere_density(40, 0.25f)).ok());
  std::ofstream probe(scratch.file("probe.jsonl"));
  // Pressed down onto the top of the ball, held a little off its axis.
  for (int i = 0; i <= 40; ++i)
    probe << "{\"t\": " << 0.001 * i << ", \"at\": [21.5, 19.5, " << 40.0f - 0.2f * float(i)
          << "], \"quat\": [1, 0, 0, 0]}\n";
  probe.close();
  const CommandResult r =
      run_sculpt("haptics trace " + scratch.file("ball.nrrd") + " --probe " +
                 scratch.file("probe.jsonl") + " --tool cube:6 -o " + scratch.file("trace.jsonl"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto trace = core::parse_trace_text(read_text(scratch.file("trace.jsonl")), "trace");
  ASSERT_TRUE(trace.ok()) << trace.error().message();
  const core::TraceLine& last = trace->back();
  ASSERT_TRUE(last.torque_nm.has_value());
  EXPECT_TRUE(last.contact);
  EXPECT_GT(last.force_n.z, 0.0f);
  // The cube's bottom (3 below its centre) stays on the ball's top (z 29.5).
  EXPECT_GT(last.proxy_vox.z, 32.0f);
}

TEST(HapticsCommand, PushingInCarvesAndTheCarvedVolumeIsWritten) {
  sculpt::test::ScratchDir scratch;
  ASSERT_TRUE(core::write_nrrd(scratch.file("ball.nrrd"), core::sphere_density(40, 0.25f)).ok());
  write_press_probe(scratch.file("probe.jsonl"));
  const CommandResult r = run_sculpt(
      "haptics trace " + scratch.file("ball.nrrd") + " --probe " + scratch.file("probe.jsonl") +
      " --radius 2 --carve subtract --press-threshold 1 --press-depth 0.5 --carved " +
      scratch.file("carved.nrrd") + " -o " + scratch.file("trace.jsonl"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("dabs"), std::string::npos);
  auto carved = core::read_nrrd_u8(scratch.file("carved.nrrd"));
  ASSERT_TRUE(carved.ok());
  // The top of the ball (z 29.5 on the axis) is carved down.
  EXPECT_LT(carved->at(19, 19, 29), 128);
  EXPECT_GT(core::sphere_density(40, 0.25f).at(19, 19, 29), 127);
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
    EXPECT_EQ(bad.exit_code, 1) << option;
    EXPECT_EQ(line_count(bad.err), 1) << option << ": " << bad.err;
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
