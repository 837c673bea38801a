// sculpt session to-text IN OUT | from-text IN OUT | generate NAME OUT
//
// Converts a session between the binary and the JSON Lines form (lossless
// both ways), or writes one of the bundled scripted sessions.

#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/number_checks.h"
#include "sculpt/base/atomic_file.h"
#include "sculpt/sim/session/session_file.h"
#include "sculpt/sim/session/session_text.h"
#include "sculpt/sim/synth/bundled_sessions.h"
#include "sculpt/station/app/session_loading.h"

namespace sculpt::station::cli {
namespace {

struct SessionOptions {
  std::string input;
  std::string output;
};

int to_text(const SessionOptions& o) {
  sim::SessionReadInfo info;
  auto session = sim::read_session_file(o.input, &info);
  if (!session) return report(session.error());
  if (!info.warning.empty()) std::fprintf(stderr, "sculpt: warning: %s\n", info.warning.c_str());
  AtomicFileWriter out(o.output);
  out.write(sim::session_to_text(*session));
  if (Status st = out.commit(); !st) return report(st.error());
  return 0;
}

int from_text(const SessionOptions& o) {
  auto session = load_session(o.input);
  if (!session) return report(session.error());
  if (Status st = sim::write_session_file(o.output, *session); !st) return report(st.error());
  return 0;
}

int generate(const SessionOptions& o) {
  const sim::Session session = sim::bundled_session(o.input);
  if (session.records.empty())
    return report(Error("no bundled session named '" + o.input + "' (short, demo, sheet, bust)"));
  if (Status st = sim::write_session_file(o.output, session); !st) return report(st.error());
  std::printf("wrote %s: %zu records, %.1f s\n", o.output.c_str(), session.records.size(),
              static_cast<double>(session.end_t_ns() - session.start_t_ns()) * 1e-9);
  return 0;
}

}  // namespace

void add_session_command(CLI::App& app, Action& action) {
  CLI::App* cmd =
      app.add_subcommand("session", "convert sessions between binary and text, or generate one");
  cmd->require_subcommand(1);
  struct Sub {
    const char* name;
    const char* help;
    const char* in_help;
    int (*run)(const SessionOptions&);
  };
  for (const Sub& s :
       {Sub{"to-text", "binary session to JSON Lines", "binary session (.scs)", to_text},
        Sub{"from-text", "JSON Lines (or binary) session to binary", "session text (.jsonl)",
            from_text},
        Sub{"generate", "write a bundled scripted session", "short, demo or sheet", generate}}) {
    auto o = std::make_shared<SessionOptions>();
    CLI::App* sub = cmd->add_subcommand(s.name, s.help);
    sub->add_option("input", o->input, s.in_help)->required()->check(input_file());
    sub->add_option("output", o->output, "output file")->required();
    sub->callback([o, run = s.run, &action] { action = [o, run] { return run(*o); }; });
  }
}

}  // namespace sculpt::station::cli
