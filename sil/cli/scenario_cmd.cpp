// SPDX-License-Identifier: Apache-2.0
// scenario_cmd.cpp: `uvms scenario check|schema` (scenario_cmd.hpp).
#include "cli/scenario_cmd.hpp"

#include "cli/exit_status.hpp"

#include <algorithm>
#include <fstream>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "run/summary_writer.hpp"
#include "scenario/config_schema.hpp"
#include "scenario/scenario.hpp"

namespace uvms::sil {

namespace {

const char kPrefix[] = "uvms scenario: error: ";

const char kUsageLine[] =
    "usage: uvms scenario check FILE [--set section.key=value]... | uvms scenario schema "
    "[--markdown [--update DOC]]  (see uvms scenario --help)";

const char kHelp[] = R"(usage: uvms scenario check FILE [--set section.key=value]...
       uvms scenario schema [--markdown [--update DOC]]

check: read a scenario (TOML), apply the overrides, validate everything (unknown keys, types,
ranges, contradictions, then the firmware's uvms_ctrl_init and the plant's own checks) and print
a one-line summary: name, case, payload, duration, tick count, flow, density error.

schema: print every scenario key as JSON, from the table of configuration fields
(sil/msg/config_table.h): {"schema_version": 1, "keys": [{"key", "type", "unit", "default",
"range", "firmware", "lcm", "plant", "harness", "doc"}, ...]}. Defaults are those of the
firmware's, the plant's and the harness's own default configurations.

Options:
  --set KEY=VALUE   (check) override one setting before validation; KEY is dotted
                    (run.duration_s, environment.unsteady_flow.enabled), VALUE is TOML: 10,
                    1e-6, true, "VII", [1, 0, 0]. Repeatable; applied in order.
  --markdown        (schema) print the key tables of docs/SCENARIOS.md instead, one block per
                    section between its generated-block markers
  --update DOC      (schema --markdown) rewrite the generated blocks of DOC in place
                    (uvms scenario schema --markdown --update docs/SCENARIOS.md)
  -h, --help        print this help and exit

Errors name the place and the key: FILE:LINE: key "section.key": what is wrong (expected ...)
Keys, units, defaults and ranges: docs/SCENARIOS.md. Paper scenarios: sil/scenarios/paper/.
Exit status: 0 valid; 1 invalid scenario or DOC (one error line on stderr); 2 usage error.
)";

int Usage(std::ostream &err, const std::string &msg) {
  err << kPrefix << msg << '\n' << kUsageLine << '\n';
  return kExitUsage;
}

/// `uvms scenario check FILE [--set k=v]...`
int RunCheck(const std::vector<std::string> &args, std::ostream &out, std::ostream &err) {
  std::string file;
  bool have_file = false;
  std::vector<std::string> sets;
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string &a = args[i];
    if (a == "--set") {
      if (i + 1 >= args.size()) return Usage(err, "--set needs a KEY=VALUE argument");
      sets.push_back(args[++i]);
    } else if (a.rfind("--set=", 0) == 0) {
      sets.push_back(a.substr(6));
    } else if (a.size() > 1 && a[0] == '-') {
      return Usage(err, "unknown option \"" + a + "\"");
    } else {
      if (have_file) return Usage(err, "more than one FILE (\"" + file + "\", \"" + a + "\")");
      file = a;
      have_file = true;
    }
  }
  if (!have_file) return Usage(err, "missing FILE");
  try {
    const Scenario s = LoadScenario(file, sets);
    out << "ok: " << ScenarioSummary(s) << '\n';
    return kExitOk;
  } catch (const ScenarioError &e) {
    std::string msg = e.what();
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    err << kPrefix << msg << '\n';
    return kExitBadInput;
  }
}

/// Rewrite DOC's generated blocks (only when they changed).
int UpdateDoc(const std::string &doc, std::ostream &out, std::ostream &err) {
  std::ifstream in(doc, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) {
    err << kPrefix << doc << ": cannot read the file\n";
    return kExitBadInput;
  }
  try {
    const std::string updated = UpdateGeneratedBlocks(text.str());
    if (updated != text.str()) WriteTextFileAtomic(updated, doc);  // checked; throws
    out << doc << (updated != text.str() ? ": generated key tables updated\n" : ": up to date\n");
    return kExitOk;
  } catch (const std::runtime_error &e) {  // a bad block, or the write failed
    err << kPrefix << doc << ": " << e.what() << '\n';
    return kExitBadInput;
  }
}

/// `uvms scenario schema [--markdown [--update DOC]]`
int RunSchema(const std::vector<std::string> &args, std::ostream &out, std::ostream &err) {
  bool markdown = false;
  std::string doc;
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string &a = args[i];
    if (a == "--markdown") {
      markdown = true;
    } else if (a == "--update" && i + 1 < args.size()) {
      doc = args[++i];
    } else {
      return Usage(err, a == "--update" ? "--update needs a DOC argument"
                                        : "unexpected argument \"" + a + "\"");
    }
  }
  if (!doc.empty() && !markdown) return Usage(err, "--update goes with --markdown");
  if (!doc.empty()) return UpdateDoc(doc, out, err);
  if (markdown) out << SchemaMarkdown();
  else out << SchemaJson().dump(2) << '\n';
  return kExitOk;
}

}  // namespace

int RunScenarioCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err) {
  if (args.empty()) return Usage(err, "missing action (expected: check, schema)");
  // -h or --help anywhere (uvms scenario --help, uvms scenario check --help ...): help only.
  if (std::any_of(args.begin(), args.end(), [](const std::string &a) { return a == "-h" || a == "--help"; })) {
    out << kHelp;
    return kExitOk;
  }
  if (args[0] == "check") return RunCheck(args, out, err);
  if (args[0] == "schema") return RunSchema(args, out, err);
  return Usage(err, "unknown action \"" + args[0] + "\" (expected: check, schema)");
}

}  // namespace uvms::sil
