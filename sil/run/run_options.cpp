// SPDX-License-Identifier: Apache-2.0
// run_options.cpp: the options shared by `uvms run` and `uvms-plant` (run_options.hpp).
#include "run/run_options.hpp"

#include <algorithm>
#include <cctype>
#include <iomanip>
#include <iostream>
#include <stdexcept>

#include "scenario/scenario_reader.hpp"

namespace uvms::sil {
namespace fs = std::filesystem;
namespace {

// --limit NAME=VALUE: the override verdict.NAME=VALUE of the scenario key (sil/msg/config_table.h
// [verdict]; the scenario reader checks the name and the value). Throws std::invalid_argument.
std::string VerdictLimitOverride(const std::string &name_value) {
  const size_t eq = name_value.find('=');
  if (eq == std::string::npos || eq == 0)
    throw std::invalid_argument("--limit " + name_value +
                                ": expected NAME=VALUE, the same as --set verdict.NAME=VALUE");
  return "verdict." + name_value;
}

// --session HEX. Throws std::invalid_argument.
std::int64_t ParseSession(const std::string &text) {
  std::int64_t session = UVMS_SESSION_NONE;
  if (!uvms_session_parse(text.c_str(), &session))
    throw std::invalid_argument("--session " + text + ": expected 1-16 hex digits, not 0");
  return session;
}

// --scenario-sha256 HEX: 64 hex digits, returned in lowercase. Throws std::invalid_argument.
std::string ParseSha256(std::string text) {
  const bool hex = text.size() == 64 && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isxdigit(static_cast<unsigned char>(c)) != 0;
  });
  if (!hex) throw std::invalid_argument("--scenario-sha256 " + text + ": expected 64 hex digits");
  for (char &c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace

RunArgs ParseRunArgs(const std::vector<std::string> &args) {
  RunArgs r;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string &a = args[i];
    auto value = [&](const char *opt) -> std::string {
      if (i + 1 >= args.size()) throw std::invalid_argument(std::string(opt) + " needs a value");
      return args[++i];
    };
    if (a == "-h" || a == "--help") r.help = true;
    else if (a == "--out") r.out_dir = value("--out");
    else if (a == "--set") r.sets.push_back(value("--set"));
    else if (a.rfind("--set=", 0) == 0) r.sets.push_back(a.substr(6));
    else if (a == "--transport") r.transport = value("--transport");
    else if (a == "--url") r.url = value("--url");
    else if (a == "--publish-url") r.publish_url = value("--publish-url");
    else if (a == "--transport-label") r.transport_label = value("--transport-label");
    else if (a == "--controller") r.controller = value("--controller");
    else if (a == "--session") r.session = ParseSession(value("--session"));
    else if (a == "--limit") r.sets.push_back(VerdictLimitOverride(value("--limit")));
    else if (a == "--no-log") r.no_log = true;
    else if (a == "--no-summary-fsync") r.summary_fsync = false;
    else if (a == "--name") r.name = value("--name");
    else if (a == "--scenario-sha256") r.scenario_sha256 = ParseSha256(value("--scenario-sha256"));
    else if (!a.empty() && a[0] == '-') throw std::invalid_argument("unknown option " + a);
    else if (r.scenario.empty()) r.scenario = a;
    else throw std::invalid_argument("unexpected argument " + a);
  }
  if (!r.help && r.scenario.empty()) throw std::invalid_argument("missing SCENARIO.toml");
  if (r.name.find_first_of("\n\r") != std::string::npos)
    throw std::invalid_argument("--name: a run name is one line");
  if (r.transport != "udpm" && r.transport != "memq")
    throw std::invalid_argument("--transport must be udpm or memq, got " + r.transport);
  if (r.controller != "host" && r.controller != "pil")
    throw std::invalid_argument("--controller must be host or pil, got " + r.controller);
  if (!r.publish_url.empty() && (r.url.empty() || r.transport != "udpm"))
    throw std::invalid_argument("--publish-url needs --url and --transport udpm");
  if (r.controller == "pil" && r.transport == "memq")
    throw std::invalid_argument("--controller pil needs --transport udpm (QEMU is a process)");
  return r;
}

Scenario LoadScenarioWithProvenance(const RunArgs &ra, Provenance *prov) {
  const std::string bytes = ReadTomlFile(ra.scenario);  // regular file, bounded size
  *prov = RunProvenance(bytes, ra.sets, ra.controller == "pil");
  const std::string sha = Sha256Hex(bytes);
  if (!ra.scenario_sha256.empty() && sha != ra.scenario_sha256)
    throw ScenarioError(ra.scenario + ": its bytes have SHA-256 " + sha + ", not the " +
                        ra.scenario_sha256 + " given by --scenario-sha256 (the file changed "
                        "since it was pinned); nothing was run");
  Scenario sc = ParseScenario(bytes, ra.scenario, ra.sets);
  if (!ra.name.empty()) sc.name = ra.name;  // the run's own name (a campaign's <name>/<id>)
  return sc;
}

std::optional<RunArgs> ParseRunArgsOrSay(const std::vector<std::string> &args, const char *who,
                                         const char *hint, std::ostream &err) {
  try {
    return ParseRunArgs(args);
  } catch (const std::invalid_argument &e) {
    err << who << ": error: " << e.what() << hint << '\n';
    return std::nullopt;
  }
}

std::optional<Scenario> LoadScenarioOrSay(const RunArgs &ra, Provenance *prov, const char *who,
                                          std::ostream &err) {
  try {
    return LoadScenarioWithProvenance(ra, prov);
  } catch (const ScenarioError &e) {
    err << who << ": error: " << e.what() << '\n';
    return std::nullopt;
  }
}

// Write summary.json; the run's exit status: 0 finished, 3 failed or the summary could not be
// written (the error is printed; a stale summary is not left behind: the write is atomic and
// `uvms run` removes the old one first).
int WriteSummaryOrFail(const RunSummary &s, const fs::path &path, const char *who,
                       std::ostream &err, FileSync sync) {
  if (s.status != "finished") err << who << ": run failed: " << s.failure << ": " << s.reason << '\n';
  try {
    WriteSummaryJson(s, path.string(), sync);
  } catch (const std::exception &e) {
    err << who << ": error: harness_error: cannot write the summary: " << e.what() << '\n';
    return kRunFailed;
  }
  return s.status == "finished" ? kRunOk : kRunFailed;
}

std::string SessionText(std::int64_t session) {
  char text[UVMS_SESSION_TEXT_BYTES];
  uvms_session_format(session, text);
  return text;
}

}  // namespace uvms::sil
