// sculpt bench [--json] [--filter REGEX]
//
// Runs the project's Google Benchmark suites (tests/bench), the same ones as
// build/bin/sculpt_bench: a table on stdout, or Google Benchmark's JSON.

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/number_checks.h"

#ifdef SCULPT_HAVE_BENCH
#include <benchmark/benchmark.h>
#endif

namespace sculpt::station::cli {
namespace {

struct BenchOptions {
  bool json = false;
  std::string filter;
  double min_time = 0;
  bool list = false;
};

int run_bench(const BenchOptions& o) {
#ifdef SCULPT_HAVE_BENCH
  std::vector<std::string> args = {"sculpt bench"};
  if (o.json) args.emplace_back("--benchmark_format=json");
  if (!o.filter.empty()) args.push_back("--benchmark_filter=" + o.filter);
  if (o.min_time > 0) args.push_back("--benchmark_min_time=" + std::to_string(o.min_time));
  if (o.list) args.emplace_back("--benchmark_list_tests=true");
  args.emplace_back("--benchmark_counters_tabular=true");
  std::vector<char*> argv;
  for (std::string& a : args)
    argv.push_back(a.data());
  int argc = static_cast<int>(argv.size());
  benchmark::Initialize(&argc, argv.data());
  if (benchmark::RunSpecifiedBenchmarks() == 0 && !o.list) {
    return report(
        Error("--filter '" + o.filter + "' matches no benchmark (see sculpt bench --list)"));
  }
  benchmark::Shutdown();
  return 0;
#else
  (void)o;
  return report(Error("benchmarks were not built (configure with -DSCULPT_BUILD_BENCH=ON)"));
#endif
}

}  // namespace

void add_bench_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "run the benchmarks (tests/bench) and print a table");
  cmd->add_flag("--json", o->json, "machine-readable results (Google Benchmark JSON)");
  cmd->add_option("--filter", o->filter,
                  "only benchmarks whose name matches this regular expression");
  cmd->add_option("--min-time", o->min_time, "minimum seconds per benchmark")
      ->check(finite_positive());
  cmd->add_flag("--list", o->list, "list the benchmarks without running them");
  cmd->callback([o, &action] { action = [o] { return run_bench(*o); }; });
}

}  // namespace sculpt::station::cli
