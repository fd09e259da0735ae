// SPDX-License-Identifier: Apache-2.0
// run_cmd.cpp: `uvms run` (run_cmd.hpp): one scenario, both nodes in lockstep over LCM.
#include "cli/run_cmd.hpp"

#include "cli/exit_status.hpp"

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

#include "link/controller_node.h"
#include "msg/codec.h"
#include "msg/session.h"
#include "run/inprocess_bus.hpp"
#include "run/plant_node.hpp"
#include "run/run_options.hpp"
#include "scenario/scenario.hpp"

namespace uvms::sil {
namespace fs = std::filesystem;
static_assert(kRunOk == kExitOk && kRunBadInput == kExitBadInput && kRunUsage == kExitUsage &&
              kRunFailed == kExitFailed, "the run layer's statuses are the commands' statuses");
namespace {

const char *kRunHelp =
    "usage: uvms run SCENARIO.toml [--out DIR] [--set section.key=value]...\n"
    "                [--transport udpm|memq] [--url LCM_URL [--publish-url LCM_URL]]\n"
    "                [--controller host|pil]\n"
    "                [--limit NAME=VALUE]... [--session HEX] [--no-log]\n"
    "                [--no-summary-fsync]\n"
    "                [--scenario-sha256 HEX] [--name NAME]\n\n"
    "Runs one scenario: the plant (uvms-plant) and the controller (uvms-controller) exchange\n"
    "LCM messages in lockstep, one tick at a time.\n"
    "  --out DIR      output directory (default runs/<scenario name>); gets run.lcmlog (LCM\n"
    "                 event log: lcm-logplayer, Python lcm.EventLog) and summary.json\n"
    "  --set K=V      override a scenario key (TOML value syntax), repeatable\n"
    "  --transport    udpm (default): two processes on a private UDP multicast port;\n"
    "                 memq: both nodes in this process, the messages (the same bytes)\n"
    "                 passed in memory with LCM memq's delivery rules (fastest; the\n"
    "                 same log byte for byte)\n"
    "  --url URL      udpm only: the LCM URL to use instead of a private link, e.g. to\n"
    "                 listen with lcm-logger or lcm-spy; a private link gives each\n"
    "                 direction its own port (neither process then receives its own\n"
    "                 datagrams: about half the link's cost)\n"
    "  --publish-url URL\n"
    "                 with --url: the plant publishes on URL and the controller on --url\n"
    "                 (each direction on a URL of its own)\n"
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
    "  --no-summary-fsync\n"
    "                 put summary.json in place without an fsync (the log, if any, is still\n"
    "                 synced first): after a system crash or power loss it may be empty or\n"
    "                 torn. For a caller that syncs the file system itself and takes a\n"
    "                 torn summary for a missing one, as `uvms campaign` does (it runs that\n"
    "                 run again)\n"
    "  --scenario-sha256 HEX\n"
    "                 the SHA-256 (64 hex digits) the scenario file's bytes must have: a\n"
    "                 file with other bytes is refused (exit 1) before anything runs; a\n"
    "                 campaign pins its base scenario this way\n"
    "  --name NAME    the run's name in summary.json and the default DIR, instead of the\n"
    "                 scenario's `name` (a campaign names each run <campaign>/<run id>)\n"
    "Exit status: 0 the run finished, 1 bad scenario or arguments, 2 usage, 3 the run failed\n"
    "(summary.json says why).\n";


// Two free UDP ports on this machine (the kernel's choice), for a run's private LCM URLs:
// both sockets are held until both are bound, so the ports differ. false if there are none.
bool FreeUdpPorts(int *port_a, int *port_b) {
  int fds[2] = {-1, -1}, ports[2] = {-1, -1};
  for (int i = 0; i < 2; ++i) {
    fds[i] = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fds[i] < 0) break;
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_ANY);
    a.sin_port = 0;
    socklen_t len = sizeof a;
    if (bind(fds[i], reinterpret_cast<sockaddr *>(&a), sizeof a) == 0 &&
        getsockname(fds[i], reinterpret_cast<sockaddr *>(&a), &len) == 0)
      ports[i] = ntohs(a.sin_port);
  }
  for (const int fd : fds)
    if (fd >= 0) close(fd);
  *port_a = ports[0];
  *port_b = ports[1];
  return ports[0] > 0 && ports[1] > 0 && ports[0] != ports[1];
}

// A udpm URL on this process's private group (derived from its pid) and the given port.
std::string PrivateUdpmUrl(int port) {
  const unsigned pid = unsigned(getpid());
  std::ostringstream url;
  url << "udpm://239.255." << ((pid >> 8) & 0xFFu) << '.' << std::max(1u, pid & 0xFFu) << ':'
      << port << "?ttl=0";
  return url.str();
}

// The two URLs of a link: what the plant listens on (the controller publishes there), and
// what the plant publishes on (the controller listens there).
struct LinkUrls {
  std::string plant_rx, plant_tx;
};

// A private link: two kernel-chosen free ports on the private group, one per direction. A
// receiving socket gets every datagram sent to its port, its own process's too: on one shared
// port each process would also wake for everything it sends (docs/BENCHMARKS.md, "SIL: the
// lockstep link").
LinkUrls PrivateLink() {
  int rx = -1, tx = -1;
  if (!FreeUdpPorts(&rx, &tx))
    throw std::runtime_error("no two free UDP ports for the run's LCM URLs");
  return {PrivateUdpmUrl(rx), PrivateUdpmUrl(tx)};
}

// A node's URL options: it listens on `listen` and, when that is another URL, publishes on
// `publish`.
void AppendUrls(std::vector<std::string> &argv, const std::string &listen,
                const std::string &publish) {
  argv.insert(argv.end(), {"--url", listen});
  if (publish != listen) argv.insert(argv.end(), {"--publish-url", publish});
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

// `uvms run --transport memq`: both nodes in this process, the controller node behind the
// in-process queue (sil/run/inprocess_bus.hpp: LCM's memq delivery, without its system calls).
int RunInProcess(const Scenario &sc, const Provenance &prov, const RunArgs &ra,
                 const fs::path &dir, std::ostream &out, std::ostream &err) {
  const std::int64_t session = ra.session;
  auto node = std::make_unique<uvms_ctrl_node_t>();
  uvms_ctrl_node_init(node.get());
  uvms_ctrl_node_set_session(node.get(), session);
  InProcessBus bus(*node);
  PlantNodeOptions opt;
  if (!ra.no_log) opt.log_path = (dir / "run.lcmlog").string();
  opt.session = session;
  InstallPlantStopHandlers();
  RunSummary s;
  try {  // a backstop: RunPlantNode reports run-time failures in the summary
    s = RunPlantNode(sc, bus, opt);
    bus.Drain();  // deliver the final status to the controller node
  } catch (const std::exception &e) {
    err << "uvms run: error: " << e.what() << '\n';
    return kRunFailed;
  }
  s.transport = "memq";
  s.provenance = prov;
  const int rc = WriteSummaryOrFail(s, dir / "summary.json", "uvms run", err, SummaryFileSync(ra));
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

// `uvms run` over udpm: uvms-plant and the controller as two processes on a private link (or
// the URL(s) given).
int RunTwoProcesses(const RunArgs &ra, const Scenario &sc, const fs::path &dir, std::ostream &out,
                    std::ostream &err) {
  LinkUrls urls;
  try {
    urls = ra.url.empty() ? PrivateLink()
                          : LinkUrls{ra.url, ra.publish_url.empty() ? ra.url : ra.publish_url};
  } catch (const std::exception &e) {
    err << "uvms run: error: " << e.what() << '\n';
    return kRunFailed;
  }
  const fs::path self = SelfDir();
  std::vector<std::string> plant_argv = {(self / "uvms-plant").string(), ra.scenario, "--out",
                                         dir.string(), "--transport-label", "udpm",
                                         "--controller", ra.controller, "--session",
                                         SessionText(ra.session)};
  AppendUrls(plant_argv, urls.plant_rx, urls.plant_tx);
  if (ra.no_log) plant_argv.push_back("--no-log");
  if (!ra.summary_fsync) plant_argv.push_back("--no-summary-fsync");
  if (!ra.name.empty()) {
    plant_argv.push_back("--name");
    plant_argv.push_back(ra.name);
  }
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
  std::vector<std::string> ctrl_argv = {(self / ctrl_exe).string(), "--session",
                                        SessionText(ra.session), "--idle-timeout-s", idle,
                                        "--spin-us", std::to_string(LinkSpinUs(sc.link))};
  AppendUrls(ctrl_argv, urls.plant_tx, urls.plant_rx);
  const pid_t ctrl = Spawn(ctrl_argv);
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
  const std::optional<RunArgs> parsed =
      ParseRunArgsOrSay(args, "uvms run", "\n(see uvms run --help)", err);
  if (!parsed) return kRunUsage;
  RunArgs ra = *parsed;
  if (ra.help) {
    out << kRunHelp;
    return kRunOk;
  }
  Provenance prov;  // the scenario is validated here, before anything starts
  const std::optional<Scenario> loaded = LoadScenarioOrSay(ra, &prov, "uvms run", err);
  if (!loaded) return kRunBadInput;
  const Scenario &sc = *loaded;
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

}  // namespace uvms::sil
