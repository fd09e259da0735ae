// SPDX-License-Identifier: Apache-2.0
// run_cli.cpp: `uvms run`, `uvms replay` and `uvms-plant` (run_cli.hpp).
#include "run_cli.hpp"

#include <arpa/inet.h>
#include <lcm/eventlog.h>
#include <lcm/lcm.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <stdexcept>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec.h"
#include "controller_node.h"
#include "plant_node.hpp"
#include "provenance.hpp"
#include "scenario.hpp"
#include "scenario_reader.hpp"
#include "session.h"

namespace uvms::sil {
namespace fs = std::filesystem;
namespace {

const char *kRunHelp =
    "usage: uvms run SCENARIO.toml [--out DIR] [--set section.key=value]...\n"
    "                [--transport udpm|memq] [--url LCM_URL] [--controller host|pil]\n"
    "                [--limit NAME=VALUE]... [--session HEX] [--no-log]\n"
    "                [--scenario-sha256 HEX]\n\n"
    "Runs one scenario: the plant (uvms-plant) and the controller (uvms-controller) exchange\n"
    "LCM messages in lockstep, one tick at a time.\n"
    "  --out DIR      output directory (default runs/<scenario name>); gets run.lcmlog (LCM\n"
    "                 event log: lcm-logplayer, Python lcm.EventLog) and summary.json\n"
    "  --set K=V      override a scenario key (TOML value syntax), repeatable\n"
    "  --transport    udpm (default): two processes on a private UDP multicast port;\n"
    "                 memq: both nodes in this process (fastest; identical results)\n"
    "  --url URL      udpm only: the LCM URL to use instead of a fresh private port\n"
    "  --controller   host (default): the host build of the firmware (uvms-controller);\n"
    "                 pil: the Cortex-M4F image in QEMU (uvms-controller-pil; udpm only)\n"
    "  --limit N=V    a verdict limit (docs/FAULTS.md \"Run verdicts\"): the same as\n"
    "                 --set verdict.N=V (keys and defaults: docs/SCENARIOS.md [verdict]),\n"
    "                 repeatable, in order with the --set overrides\n"
    "  --session HEX  the run's session (1-16 hex digits, not 0), stamped on every message;\n"
    "                 default: drawn at random. Messages of other sessions are dropped and\n"
    "                 counted (docs/FAULTS.md \"Sessions\"). Fix it only to reproduce a log\n"
    "                 byte for byte\n"
    "  --no-log       write no run.lcmlog (summary.json only), e.g. for large campaigns\n"
    "  --scenario-sha256 HEX\n"
    "                 the SHA-256 (64 hex digits) the scenario file's bytes must have: a\n"
    "                 file with other bytes is refused (exit 1) before anything runs; a\n"
    "                 campaign pins its base scenario this way\n"
    "Exit status: 0 the run finished, 1 bad scenario or arguments, 2 usage, 3 the run failed\n"
    "(summary.json says why).\n";

const char *kReplayHelp =
    "usage: uvms replay DIR/run.lcmlog\n\n"
    "Feeds the logged configuration and sensor messages to a fresh controller (host build)\n"
    "and compares its actuator messages with the logged ones bit for bit.\n"
    "It also verifies the log as a whole: consecutive event numbers, every message's CRC and\n"
    "session on every channel (one session: no other run's message), one truth record per tick,\n"
    "the end record (the final run_status_t) last, and no truncated or trailing bytes; and that\n"
    "every tick whose sensors are logged has its actuators and telemetry logged too, but for the\n"
    "ticks the run missed (no more ticks without actuators than the end record's missed ticks:\n"
    "link faults, a late controller). Otherwise the log is incomplete, and the ticks with their\n"
    "sensors but not their actuators or telemetry are named (the first 10, and the count).\n"
    "Exit status: 0 identical and complete, 1 a difference (the first tick and field are\n"
    "printed), 2 usage, 3 unreadable, truncated, corrupt or incomplete log, 4 an intact log of\n"
    "an interrupted run (SIGTERM/SIGINT: identical as far as it goes).\n";

// A free UDP port on this machine (the kernel's choice), for a run's private LCM URL.
int FreeUdpPort() {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return -1;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_ANY);
  a.sin_port = 0;
  socklen_t len = sizeof a;
  int port = -1;
  if (bind(fd, reinterpret_cast<sockaddr *>(&a), sizeof a) == 0 &&
      getsockname(fd, reinterpret_cast<sockaddr *>(&a), &len) == 0) {
    port = ntohs(a.sin_port);
  }
  close(fd);
  return port;
}

// A private udpm URL: a kernel-chosen free port and a group derived from this process.
std::string PrivateUdpmUrl() {
  const int port = FreeUdpPort();
  if (port <= 0) throw std::runtime_error("no free UDP port for the run's LCM URL");
  const unsigned pid = unsigned(getpid());
  std::ostringstream url;
  url << "udpm://239.255." << ((pid >> 8) & 0xFFu) << '.' << std::max(1u, pid & 0xFFu) << ':'
      << port << "?ttl=0";
  return url.str();
}

fs::path SelfDir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path(".") : exe.parent_path();
}

// fork + exec; the child dies with its parent (PR_SET_PDEATHSIG).
pid_t Spawn(const std::vector<std::string> &argv) {
  std::vector<char *> cargs;
  for (const auto &a : argv) cargs.push_back(const_cast<char *>(a.c_str()));
  cargs.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(127);
    execv(cargs[0], cargs.data());
    std::fprintf(stderr, "uvms: error: cannot execute %s: %s\n", cargs[0], std::strerror(errno));
    _exit(127);
  }
  return pid;
}

int WaitExit(pid_t pid) {
  int st = 0;
  while (waitpid(pid, &st, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  if (WIFEXITED(st)) return WEXITSTATUS(st);
  return 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
}

struct RunArgs {
  std::string scenario, out_dir, transport{"udpm"}, url, transport_label, controller{"host"};
  std::vector<std::string> sets;  ///< --set overrides, and --limit ones as verdict.NAME=VALUE
  std::int64_t session{UVMS_SESSION_NONE};  ///< --session (sil/session.h); NONE: drawn
  std::string scenario_sha256;  ///< --scenario-sha256: the bytes the scenario must have ("": any)
  bool help{false};
  bool no_log{false};  ///< --no-log: no run.lcmlog, summary.json only
};

// --limit NAME=VALUE: the override verdict.NAME=VALUE of the scenario key (sil/config_table.h
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

std::string SessionText(std::int64_t session) {
  char text[UVMS_SESSION_TEXT_BYTES];
  uvms_session_format(session, text);
  return text;
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

// Parses the options shared by `uvms run` and `uvms-plant`. Throws std::invalid_argument.
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
    else if (a == "--transport-label") r.transport_label = value("--transport-label");
    else if (a == "--controller") r.controller = value("--controller");
    else if (a == "--session") r.session = ParseSession(value("--session"));
    else if (a == "--limit") r.sets.push_back(VerdictLimitOverride(value("--limit")));
    else if (a == "--no-log") r.no_log = true;
    else if (a == "--scenario-sha256") r.scenario_sha256 = ParseSha256(value("--scenario-sha256"));
    else if (!a.empty() && a[0] == '-') throw std::invalid_argument("unknown option " + a);
    else if (r.scenario.empty()) r.scenario = a;
    else throw std::invalid_argument("unexpected argument " + a);
  }
  if (!r.help && r.scenario.empty()) throw std::invalid_argument("missing SCENARIO.toml");
  if (r.transport != "udpm" && r.transport != "memq")
    throw std::invalid_argument("--transport must be udpm or memq, got " + r.transport);
  if (r.controller != "host" && r.controller != "pil")
    throw std::invalid_argument("--controller must be host or pil, got " + r.controller);
  if (r.controller == "pil" && r.transport == "memq")
    throw std::invalid_argument("--controller pil needs --transport udpm (QEMU is a process)");
  return r;
}

// Reads the scenario file once: the same bytes are parsed (as LoadScenario would) and hashed
// for the summary's provenance. Throws ScenarioError.
Scenario LoadScenarioWithProvenance(const RunArgs &ra, Provenance *prov) {
  const std::string bytes = ReadTomlFile(ra.scenario);  // regular file, bounded size
  *prov = RunProvenance(bytes, ra.sets, ra.controller == "pil");
  const std::string sha = Sha256Hex(bytes);
  if (!ra.scenario_sha256.empty() && sha != ra.scenario_sha256)
    throw ScenarioError(ra.scenario + ": its bytes have SHA-256 " + sha + ", not the " +
                        ra.scenario_sha256 + " given by --scenario-sha256 (the file changed "
                        "since it was pinned); nothing was run");
  return ParseScenario(bytes, ra.scenario, ra.sets);
}

void PrintSummaryLine(const RunSummary &s, const fs::path &dir, bool logged, std::ostream &out) {
  out << std::setprecision(4);
  out << "uvms run: " << s.name << ": " << s.status;
  if (!s.failure.empty()) out << " (" << s.failure << ": " << s.reason << ")";
  out << "; " << s.ticks << "/" << s.ticks_planned << " ticks, missed " << s.missed_ticks;
  if (s.status == "finished")  // a failed run's metrics are null (docs/FAULTS.md "Run verdicts")
    out << "; mean EE error " << s.mean_ee_error_m * 1e3 << " mm, thruster energy "
        << s.thruster_energy_J << " J";
  out << "; " << s.wall_time_s << " s wall (" << std::setprecision(1)
      << std::fixed << s.real_time_factor << "x real time, " << s.transport << ")\n"
      << std::defaultfloat << "  " << (dir / "summary.json").string();
  if (logged) out << ", " << (dir / "run.lcmlog").string();
  out << '\n';
}

// Write summary.json; the run's exit status: 0 finished, 3 failed or the summary could not be
// written (the error is printed; a stale summary is not left behind: the write is atomic and
// `uvms run` removes the old one first).
int WriteSummaryOrFail(const RunSummary &s, const fs::path &path, const char *who, std::ostream &err) {
  if (s.status != "finished") err << who << ": run failed: " << s.failure << ": " << s.reason << '\n';
  try {
    WriteSummaryJson(s, path.string());
  } catch (const std::exception &e) {
    err << who << ": error: harness_error: cannot write the summary: " << e.what() << '\n';
    return kRunFailed;
  }
  return s.status == "finished" ? kRunOk : kRunFailed;
}

}  // namespace

int RunPlantProcess(const std::vector<std::string> &args, std::ostream &out, std::ostream &err) {
  RunArgs ra;
  try {
    ra = ParseRunArgs(args);
  } catch (const std::invalid_argument &e) {
    err << "uvms-plant: error: " << e.what() << '\n';
    return kRunUsage;
  }
  if (ra.help || ra.url.empty() || ra.out_dir.empty()) {
    (ra.help ? out : err) << "usage: uvms-plant SCENARIO.toml --url LCM_URL --out DIR "
                             "[--set k=v]... [--controller host|pil] [--session HEX] [--no-log]\n"
                             "       [--scenario-sha256 HEX]\n"
                             "       uvms-plant --version\n"
                             "(normally started by `uvms run`; without --session, one is drawn)\n";
    return ra.help ? kRunOk : kRunUsage;
  }
  Scenario sc;
  Provenance prov;
  try {
    sc = LoadScenarioWithProvenance(ra, &prov);
  } catch (const ScenarioError &e) {
    err << "uvms-plant: error: " << e.what() << '\n';
    return kRunBadInput;
  }
  lcm_t *lcm = lcm_create(ra.url.c_str());
  if (lcm == nullptr) {
    err << "uvms-plant: error: cannot start LCM on " << ra.url
        << " (no multicast route? `ip route add 224.0.0.0/4 dev lo`)\n";
    return kRunFailed;
  }
  PlantNodeOptions opt;
  if (!ra.no_log) opt.log_path = (fs::path(ra.out_dir) / "run.lcmlog").string();
  opt.spin_us = LinkSpinUs(sc.link);
  opt.session = ra.session;  // NONE (started by hand): RunPlantNode draws one
  InstallPlantStopHandlers();
  RunSummary s;
  try {
    s = RunPlantNode(sc, lcm, opt);
  } catch (const std::exception &e) {
    lcm_destroy(lcm);
    err << "uvms-plant: error: " << e.what() << '\n';
    return kRunFailed;
  }
  lcm_destroy(lcm);
  s.transport = ra.transport_label.empty() ? "udpm" : ra.transport_label;
  s.provenance = prov;
  return WriteSummaryOrFail(s, fs::path(ra.out_dir) / "summary.json", "uvms-plant", err);
}

namespace {

// `uvms run --transport memq`: both nodes in this process, on one memq LCM.
int RunInProcess(const Scenario &sc, const Provenance &prov, const RunArgs &ra,
                 const fs::path &dir, std::ostream &out, std::ostream &err) {
  const std::int64_t session = ra.session;
  lcm_t *lcm = lcm_create("memq://");
  if (lcm == nullptr) {
    err << "uvms run: error: cannot start LCM memq://\n";
    return kRunFailed;
  }
  auto node = std::make_unique<uvms_ctrl_node_t>();
  uvms_ctrl_node_init(node.get());
  uvms_ctrl_node_set_session(node.get(), session);
  if (uvms_ctrl_node_attach(node.get(), lcm) != 0) {
    lcm_destroy(lcm);
    err << "uvms run: error: LCM subscription failed\n";
    return kRunFailed;
  }
  PlantNodeOptions opt;
  if (!ra.no_log) opt.log_path = (dir / "run.lcmlog").string();
  opt.session = session;
  InstallPlantStopHandlers();
  RunSummary s;
  try {  // a backstop: RunPlantNode reports run-time failures in the summary
    s = RunPlantNode(sc, lcm, opt);
    lcm_handle_timeout(lcm, 0);  // deliver the final status to the controller node
  } catch (const std::exception &e) {
    lcm_destroy(lcm);
    err << "uvms run: error: " << e.what() << '\n';
    return kRunFailed;
  }
  lcm_destroy(lcm);
  s.transport = "memq";
  s.provenance = prov;
  const int rc = WriteSummaryOrFail(s, dir / "summary.json", "uvms run", err);
  if (fs::exists(dir / "summary.json")) PrintSummaryLine(s, dir, !ra.no_log, out);
  return rc;
}

// Wait for the controller process after the plant's: it exits on the final run status; if the
// plant died first, stop it. Returns its exit status.
int WaitController(pid_t ctrl) {
  for (int i = 0; i < 50; ++i) {
    int st = 0;
    const pid_t r = waitpid(ctrl, &st, WNOHANG);
    if (r == ctrl) return WIFEXITED(st) ? WEXITSTATUS(st) : 128;
    if (i == 49) {
      kill(ctrl, SIGTERM);
      return WaitExit(ctrl);
    }
    usleep(20000);
  }
  return 0;
}

// The summary line's fields from the plant process's summary.json.
// Throws std::runtime_error when it does not parse.
RunSummary ReadSummaryLine(const fs::path &dir) {
  std::ifstream f(dir / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(f, nullptr, false);
  if (j.is_discarded() || !j.is_object())
    throw std::runtime_error((dir / "summary.json").string() + " is not a JSON object");
  RunSummary s;
  s.name = j.value("name", "");
  s.status = j.value("status", "");
  s.failure = j.value("failure", "");
  s.reason = j.value("reason", "");
  s.ticks = j.value("ticks", 0L);
  s.ticks_planned = j.value("ticks_planned", 0L);
  s.missed_ticks = j.value("missed_ticks", 0L);
  const auto num = [&](const char *k) {
    return j.contains(k) && j[k].is_number() ? j[k].get<double>() : std::nan("");
  };
  s.mean_ee_error_m = num("mean_ee_error_m");
  s.thruster_energy_J = num("thruster_energy_J");
  s.wall_time_s = num("wall_time_s");
  s.real_time_factor = num("real_time_factor");
  s.transport = "udpm";
  return s;
}

// `uvms run` over udpm: uvms-plant and the controller as two processes on a private URL.
int RunTwoProcesses(const RunArgs &ra, const Scenario &sc, const fs::path &dir, std::ostream &out,
                    std::ostream &err) {
  std::string url;
  try {
    url = ra.url.empty() ? PrivateUdpmUrl() : ra.url;
  } catch (const std::exception &e) {
    err << "uvms run: error: " << e.what() << '\n';
    return kRunFailed;
  }
  const fs::path self = SelfDir();
  std::vector<std::string> plant_argv = {(self / "uvms-plant").string(), ra.scenario, "--url",
                                         url, "--out", dir.string(), "--transport-label", "udpm",
                                         "--controller", ra.controller, "--session",
                                         SessionText(ra.session)};
  if (ra.no_log) plant_argv.push_back("--no-log");
  if (!ra.scenario_sha256.empty()) {
    plant_argv.push_back("--scenario-sha256");
    plant_argv.push_back(ra.scenario_sha256);
  }
  for (const auto &s : ra.sets) {
    plant_argv.push_back("--set");
    plant_argv.push_back(s);
  }
  const std::string idle = std::to_string(std::max(10.0, 3.0 * sc.link.timeout_s + 5.0));
  const char *ctrl_exe = ra.controller == "pil" ? "uvms-controller-pil" : "uvms-controller";
  const pid_t ctrl = Spawn({(self / ctrl_exe).string(), "--url", url, "--session",
                           SessionText(ra.session), "--idle-timeout-s", idle,
                           "--spin-us", std::to_string(LinkSpinUs(sc.link))});
  const pid_t plant = Spawn(plant_argv);
  if (ctrl < 0 || plant < 0) {
    err << "uvms run: error: cannot start the nodes\n";
    if (ctrl > 0) kill(ctrl, SIGTERM);
    if (plant > 0) kill(plant, SIGTERM);
    return kRunFailed;
  }
  const int plant_rc = WaitExit(plant);
  const int ctrl_rc = WaitController(ctrl);
  if (!fs::exists(dir / "summary.json")) {
    err << "uvms run: error: the plant node exited with status " << plant_rc
        << " without a summary (see its messages above)\n";
    return plant_rc == kRunBadInput ? kRunBadInput : kRunFailed;
  }
  if (ctrl_rc != 0) err << "uvms run: warning: " << ctrl_exe << " exited with status " << ctrl_rc << '\n';
  try {
    PrintSummaryLine(ReadSummaryLine(dir), dir, !ra.no_log, out);
  } catch (const std::exception &e) {
    err << "uvms run: error: harness_error: " << e.what() << '\n';
    return kRunFailed;
  }
  return plant_rc == kRunOk ? kRunOk : kRunFailed;
}

}  // namespace

int RunRunCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err) {
  RunArgs ra;
  try {
    ra = ParseRunArgs(args);
  } catch (const std::invalid_argument &e) {
    err << "uvms run: error: " << e.what() << "\n(see uvms run --help)\n";
    return kRunUsage;
  }
  if (ra.help) {
    out << kRunHelp;
    return kRunOk;
  }
  Scenario sc;
  Provenance prov;
  try {
    sc = LoadScenarioWithProvenance(ra, &prov);  // validated here, before anything starts
  } catch (const ScenarioError &e) {
    err << "uvms run: error: " << e.what() << '\n';
    return kRunBadInput;
  }
  const fs::path dir = ra.out_dir.empty() ? fs::path("runs") / sc.name : fs::path(ra.out_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    err << "uvms run: error: cannot create " << dir << ": " << ec.message() << '\n';
    return kRunBadInput;
  }
  fs::remove(dir / "summary.json", ec);
  // --no-log: a log of an earlier run in DIR would pass for this run's; it goes.
  if (ra.no_log) fs::remove(dir / "run.lcmlog", ec);
  if (ra.no_log && ec) {
    err << "uvms run: error: cannot remove the old " << (dir / "run.lcmlog") << ": " << ec.message()
        << '\n';
    return kRunBadInput;
  }
  if (ra.session == UVMS_SESSION_NONE && uvms_session_draw(&ra.session) != 0) {
    err << "uvms run: error: harness_error: cannot draw a session: " << std::strerror(errno) << '\n';
    return kRunFailed;
  }
  return ra.transport == "memq" ? RunInProcess(sc, prov, ra, dir, out, err)
                                : RunTwoProcesses(ra, sc, dir, out, err);
}

namespace {

// The whole-log checks of `uvms replay`, fed every event in order.
struct LogCheck {
  long next_eventnum{0};           // the recorder numbers events 0, 1, 2, ...
  long truth{0};                   // one truth_t per tick and one at the end
  int64_t last_truth_utime{-1};
  std::int64_t session{UVMS_SESSION_NONE};  // the run's: the first message's
  bool have_end{false};            // the end record: the final run_status_t (FINISHED/FAILED)
  uvms_run_status_t end{};
  long bad_sensors_crc{0};         // sensors_t failing its CRC (a recorded link fault, or damage)
  std::string error;               // the first damage found ("" none)
  // Per tick k, what its window (from truth k to truth k+1) holds of tick k's own messages:
  // kTickSensors (intact), kTickActuators, kTickTelemetry. The plant records them in that window
  // or not at all (sil/lockstep_link.hpp).
  std::vector<std::uint8_t> tick_msgs;
};

constexpr std::uint8_t kTickSensors = 1, kTickActuators = 2, kTickTelemetry = 4;

// A message's CRC and decoding on its channel; "" when it checks out.
std::string CheckMessage(const std::string &ch, const uint8_t *d, int n, LogCheck &lc) {
  if (ch == UVMS_CH_SENSORS) {  // a link fault records corrupted sensors: the comparison decides
    if (!uvms_crc_check(d, n)) ++lc.bad_sensors_crc;
    return "";
  }
  if (ch == UVMS_CH_TRUTH || ch == UVMS_CH_SCENE) return uvms_crc_check(d, n) ? "" : "fails its CRC";
  if (ch == UVMS_CH_CONFIG) {
    auto m = std::make_unique<uvms_controller_config_t>();
    return uvms_controller_config_t_decode_checked(d, n, m.get()) < 0 ? "does not decode or fails its CRC" : "";
  }
  if (ch == UVMS_CH_ACTUATORS) {
    uvms_actuators_t m;
    return uvms_actuators_t_decode_checked(d, n, &m) < 0 ? "does not decode or fails its CRC" : "";
  }
  if (ch == UVMS_CH_TELEMETRY) {
    uvms_telemetry_t m;
    return uvms_telemetry_t_decode_checked(d, n, &m) < 0 ? "does not decode or fails its CRC" : "";
  }
  if (ch == UVMS_CH_STATUS) {
    uvms_run_status_t m;
    if (uvms_run_status_t_decode_checked(d, n, &m) < 0) return "does not decode or fails its CRC";
    if (m.state == UVMS_RUN_STATUS_T_FINISHED || m.state == UVMS_RUN_STATUS_T_FAILED) {
      lc.have_end = true;
      lc.end = m;
    }
    return "";
  }
  return "is on an unknown channel";
}

// Every message of a run carries its session (sil/session.h): another one in the log is a
// foreign message that should never have been recorded. "" when it checks out.
std::string CheckSession(const uint8_t *d, int n, LogCheck &lc) {
  if (!uvms_crc_check(d, n)) return "";  // a recorded, corrupted sensors message: not judged
  std::int64_t session = UVMS_SESSION_NONE;
  if (!uvms_msg_session(d, n, &session)) return "is too short to carry a session";
  if (lc.session == UVMS_SESSION_NONE) lc.session = session;
  if (session == UVMS_SESSION_NONE || session != lc.session)
    return "carries session " + SessionText(session) + ", the run's is " + SessionText(lc.session) +
           " (a message of another run)";
  return "";
}

// One event against the whole-log checks; false (lc.error set) on damage.
bool CheckEvent(const lcm_eventlog_event_t &ev, LogCheck &lc) {
  const std::string ch(ev.channel, size_t(ev.channellen));
  std::string what;
  if (lc.have_end) what = "follows the end record";
  else if (ev.eventnum != lc.next_eventnum)
    what = "has number " + std::to_string(ev.eventnum) + ", expected " + std::to_string(lc.next_eventnum) +
           " (events missing)";
  else what = CheckMessage(ch, static_cast<const uint8_t *>(ev.data), ev.datalen, lc);
  if (what.empty()) what = CheckSession(static_cast<const uint8_t *>(ev.data), ev.datalen, lc);
  if (what.empty() && ch == UVMS_CH_TRUTH) {
    if (ev.timestamp <= lc.last_truth_utime) what = "goes back in time (a tick repeated)";
    lc.last_truth_utime = ev.timestamp;
    ++lc.truth;
  }
  ++lc.next_eventnum;
  if (what.empty()) return true;
  lc.error = "event " + std::to_string(ev.eventnum) + " on " + ch + " " + what;
  return false;
}

// Notes an intact event's tick in LogCheck::tick_msgs when it is its window's own tick.
void NoteTickMessage(const std::string &ch, const uint8_t *d, int n, LogCheck &lc) {
  if (lc.truth == 0) return;  // before truth 0: the configuration and its answer
  const long window = lc.truth - 1;
  std::int64_t tick = -1;
  std::uint8_t bit = 0;
  if (ch == UVMS_CH_SENSORS) {
    uvms_sensors_t m;
    if (uvms_sensors_t_decode_checked(d, n, &m) < 0) return;  // corrupted: the controller drops it
    tick = m.tick;
    bit = kTickSensors;
  } else if (ch == UVMS_CH_ACTUATORS) {
    uvms_actuators_t m;
    if (uvms_actuators_t_decode_checked(d, n, &m) < 0) return;
    tick = m.tick;
    bit = kTickActuators;
  } else if (ch == UVMS_CH_TELEMETRY) {
    uvms_telemetry_t m;
    if (uvms_telemetry_t_decode_checked(d, n, &m) < 0) return;
    tick = m.tick;
    bit = kTickTelemetry;
  }
  if (bit == 0 || tick != window) return;  // another channel, or late / early: out of sequence
  if (lc.tick_msgs.size() <= size_t(window)) lc.tick_msgs.resize(size_t(window) + 1, 0);
  lc.tick_msgs[size_t(window)] |= bit;
}

// What a tick's window holds (LogCheck::tick_msgs), 0 past its end.
std::uint8_t TickMessages(const LogCheck &lc, long k) {
  return k >= 0 && size_t(k) < lc.tick_msgs.size() ? lc.tick_msgs[size_t(k)] : 0;
}

// The ticks of the run (0 .. end.tick - 1) whose actuators are not in their window: the ticks
// the plant took no actuators on, which it counts as missed (link faults, a late controller).
long UnansweredTicks(const LogCheck &lc) {
  long n = 0;
  for (long k = 0; k < lc.end.tick; ++k) n += (TickMessages(lc, k) & kTickActuators) == 0;
  return n;
}

// After a complete log: every tick whose sensors are logged has its actuators and telemetry
// logged too, except the ticks the run itself missed. More ticks without actuators than the end
// record's missed_ticks, or a tick with its actuators but without its telemetry, means the log
// lacks messages the run had: every tick with its sensors but not its actuators or telemetry is
// then named (the first few, and the count). "" when it checks out.
std::string CheckTicks(const LogCheck &lc) {
  const long unanswered = UnansweredTicks(lc);
  bool telemetry_lost = false;
  for (long k = 0; k < lc.end.tick; ++k) {
    const std::uint8_t b = TickMessages(lc, k);
    telemetry_lost = telemetry_lost || ((b & kTickActuators) && !(b & kTickTelemetry));
  }
  if (unanswered <= lc.end.missed_ticks && !telemetry_lost) return "";
  constexpr long kListed = 10;  // the first ticks named, then the count
  std::string list;
  long lacking = 0;
  for (long k = 0; k < long(lc.tick_msgs.size()); ++k) {
    const std::uint8_t b = TickMessages(lc, k);
    if (!(b & kTickSensors) || ((b & kTickActuators) && (b & kTickTelemetry))) continue;
    if (++lacking > kListed) continue;
    list += (lacking > 1 ? ", " : "") + std::to_string(k) + " (no " +
            (!(b & kTickActuators) ? ((b & kTickTelemetry) ? "actuators" : "actuators, no telemetry")
                                   : "telemetry") + ")";
  }
  if (lacking > kListed) list += ", ...";
  return "incomplete: " + std::to_string(lacking) + " tick" + (lacking == 1 ? "" : "s") +
         " with the sensors logged but not the actuators or telemetry: " + list + "; " +
         std::to_string(unanswered) + " ticks without actuators, the end record counts " +
         std::to_string(lc.end.missed_ticks) + " missed";
}

// After the last event: the file must have been read to its end (else it is truncated or has
// trailing bytes), end with the end record, and hold one truth per tick. "" when complete.
std::string CheckEnd(lcm_eventlog_t *log, const std::string &path, const LogCheck &lc) {
  struct stat st {};
  const long pos = std::ftell(log->f);
  if (stat(path.c_str(), &st) == 0 && pos >= 0 && pos != long(st.st_size))
    return "truncated or damaged: events end at byte " + std::to_string(pos) + " of " +
           std::to_string(long(st.st_size));
  if (!lc.have_end) return "incomplete: no end record (the final run_status_t): truncated or cut short";
  if (lc.truth != lc.end.tick + 1)
    return "incomplete: " + std::to_string(lc.truth) + " truth records for " + std::to_string(lc.end.tick) +
           " ticks (expected one per tick and one at the end)";
  return CheckTicks(lc);
}

// The end record's verdict in words: "finished" or "failed: <reason>".
std::string EndWords(const uvms_run_status_t &st) {
  if (st.state == UVMS_RUN_STATUS_T_FINISHED) return "finished";
  std::string reason(reinterpret_cast<const char *>(st.reason), strnlen(reinterpret_cast<const char *>(st.reason), sizeof st.reason));
  return std::string("failed (") + FailureName(st.code) + "): " + reason;
}

}  // namespace

int RunReplayCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err) {
  if (args.size() == 1 && (args[0] == "-h" || args[0] == "--help")) {
    out << kReplayHelp;
    return 0;
  }
  if (args.size() != 1) {
    err << "uvms replay: error: expected exactly one log file\n" << kReplayHelp;
    return 2;
  }
  lcm_eventlog_t *log = lcm_eventlog_create(args[0].c_str(), "r");
  if (log == nullptr) {
    err << "uvms replay: error: cannot open " << args[0] << '\n';
    return 3;
  }
  auto node = std::make_unique<uvms_ctrl_node_t>();
  uvms_ctrl_node_init(node.get());
  auto out_msgs = std::make_unique<uvms_ctrl_node_out_t>();
  std::map<int64_t, uvms_actuators_t> produced;  // by tick
  long configs = 0, sensors = 0, compared = 0;
  int rc = 0;
  LogCheck lc;
  for (lcm_eventlog_event_t *ev; rc == 0 && (ev = lcm_eventlog_read_next_event(log)) != nullptr;
       lcm_eventlog_free_event(ev)) {
    if (!CheckEvent(*ev, lc)) {
      err << "uvms replay: error: corrupt log: " << lc.error << '\n';
      rc = 3;
      continue;
    }
    const std::string ch(ev->channel, size_t(ev->channellen));
    const auto *data = static_cast<const uint8_t *>(ev->data);
    NoteTickMessage(ch, data, ev->datalen, lc);
    if (ch == UVMS_CH_CONFIG) {
      ++configs;
      uvms_ctrl_node_on_config(node.get(), data, ev->datalen, out_msgs.get());
      produced.clear();
    } else if (ch == UVMS_CH_SENSORS) {
      ++sensors;
      uvms_ctrl_node_on_sensors(node.get(), data, ev->datalen, out_msgs.get());
      if (out_msgs->has_actuators) produced[out_msgs->actuators.tick] = out_msgs->actuators;
    } else if (ch == UVMS_CH_ACTUATORS) {
      uvms_actuators_t logged;
      (void)uvms_actuators_t_decode_checked(data, ev->datalen, &logged);  // checked above
      const auto it = produced.find(logged.tick);
      if (it == produced.end()) {
        out << "uvms replay: DIFFERENT at tick " << logged.tick
            << ": the log has actuators the fresh controller did not produce\n";
        rc = 1;
        continue;
      }
      int index = -1;
      const char *field = uvms_actuators_first_difference(&it->second, &logged, &index);
      if (field != nullptr) {
        out << "uvms replay: DIFFERENT at tick " << logged.tick << ", field " << field;
        if (index >= 0) out << "[" << index << "]";
        out << std::setprecision(17) << '\n';
        rc = 1;
        continue;
      }
      ++compared;  // kept: a link fault may have duplicated the logged message
    }
  }
  const std::string incomplete = rc == 0 ? CheckEnd(log, args[0], lc) : "";
  lcm_eventlog_destroy(log);
  if (rc != 0) return rc;
  if (!incomplete.empty()) {
    err << "uvms replay: error: " << args[0] << ": " << incomplete << '\n';
    return 3;
  }
  if (configs == 0 || compared == 0) {
    err << "uvms replay: error: " << args[0] << " has " << configs << " configuration and "
        << compared << " actuator messages: nothing to compare\n";
    return 3;
  }
  out << "uvms replay: identical: " << compared << " actuator messages bit for bit (" << sensors
      << " sensor messages replayed); log complete: " << lc.end.tick << " ticks, "
      << lc.next_eventnum << " events, every CRC and session checked";
  if (lc.bad_sensors_crc > 0) out << " (" << lc.bad_sensors_crc << " corrupted sensor messages: recorded link faults)";
  if (const long unanswered = UnansweredTicks(lc); unanswered > 0)
    out << "; " << unanswered << " ticks without actuators, all missed by the run (end record: "
        << lc.end.missed_ticks << " missed)";
  out << "; the run " << EndWords(lc.end) << '\n';
  if (lc.end.code == UVMS_RUN_STATUS_T_INTERRUPTED) {
    err << "uvms replay: the run is incomplete: it was interrupted (the log is intact)\n";
    return 4;
  }
  return 0;
}

}  // namespace uvms::sil
