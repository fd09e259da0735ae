// SPDX-License-Identifier: Apache-2.0
// campaign_exec.cpp: the runs of a campaign executed on this machine (campaign_exec.hpp).
#include "campaign/campaign_exec.hpp"

#include <fcntl.h>
#include <malloc.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <iomanip>
#include <map>
#include <ostream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "campaign/campaign_results.hpp"
#include "campaign/summary_sync.hpp"
#include "msg/codec.h"
#include "run/provenance.hpp"
#include "run/summary_writer.hpp"

namespace uvms::sil {
namespace fs = std::filesystem;

std::vector<std::string> RunArgs(const RunInputs &in, const CampaignRun &r, bool log) {
  std::vector<std::string> argv = {"run",
                                   in.base_pinned,
                                   "--scenario-sha256",
                                   in.base_sha256,
                                   "--out",
                                   ".",
                                   "--transport",
                                   in.campaign->transport,
                                   "--session",
                                   RunSession(in.base_bytes, r.overrides, in.generation),
                                   "--name",
                                   in.campaign->name + "/" + r.id};
  if (!log) argv.push_back("--no-log");
  for (const auto &o : r.overrides) {
    argv.push_back("--set");
    argv.push_back(o);
  }
  return argv;
}

std::string OverridesText(const CampaignRun &r) {
  return nlohmann::ordered_json(r.overrides).dump(2) + "\n";
}

RunIdentity IdentityOf(const RunInputs &in, const CampaignRun &r) {
  return RunIdentity{RunSession(in.base_bytes, r.overrides, in.generation), in.base_sha256,
                     JoinLines(r.overrides), in.version};
}

RunState StateOf(const fs::path &root, const RunInputs &in, const CampaignRun &r,
                 const RunOptions &o) {
  const Prior prior =
      o.force_new ? Prior::kNone : PriorRun(root / "runs" / r.id, r, IdentityOf(in, r));
  if (prior == Prior::kNone || (prior == Prior::kFailed && o.retry_failed)) return RunState::kTodo;
  if (prior == Prior::kFailed) return RunState::kFailedKept;
  if (!o.logs_given || !o.logs.KeepsFinished(r.id)) return RunState::kDone;
  std::error_code ec;  // the policy keeps this run's log: looked for only then
  return fs::exists(root / "runs" / r.id / "run.lcmlog", ec) ? RunState::kDone : RunState::kTodo;
}

std::string ApplyLogPolicy(const LogPolicy &policy, const CampaignRun &r, int rc,
                           const fs::path &dir) {
  if (rc != 0 || !policy.Writes() || policy.KeepsFinished(r.id)) return "";
  std::error_code ec;
  fs::remove(dir / "run.lcmlog", ec);  // no error when there is none
  return ec ? "cannot remove " + (dir / "run.lcmlog").string() + ": " + ec.message() : "";
}

std::string IdList(const std::vector<std::string> &ids) {
  std::string s;
  for (size_t i = 0; i < ids.size() && i < 5; ++i) s += (i ? ", " : "") + ids[i];
  return ids.size() > 5 ? s + ", ..." : s;
}

namespace {

// Starts run `run_args` (RunArgs: "run" and `uvms run`'s arguments) in the run's directory
// `dir`: a fork of this process that calls `run_here` (RunOptions::run_here) with the
// arguments after "run", stdin /dev/null, its output (stdout and stderr) into `log_fd` (run.out,
// opened by the caller), and exits with its status. Returns the child's pid, or -1 (errno set).
pid_t SpawnRun(const std::vector<std::string> &run_args, const fs::path &dir, int log_fd,
               const std::function<int(const std::vector<std::string> &)> &run_here) {
  const std::vector<std::string> args(run_args.begin() + 1, run_args.end());  // after "run"
  const pid_t parent = getpid();
  std::cout.flush();  // nothing buffered in this process may be written again by the child
  std::cerr.flush();
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(127);
    // stdin /dev/null, stdout and stderr run.out; every other descriptor of the campaign's
    // process (its lock on DIR among them) closed, as an exec would have closed them. Both
    // sources are first moved above 2 so that no dup2 overwrites the other.
    const int devnull = open("/dev/null", O_RDONLY | O_CLOEXEC);
    const int in_fd = devnull < 0 ? -1 : fcntl(devnull, F_DUPFD_CLOEXEC, 3);
    const int out_fd = fcntl(log_fd, F_DUPFD_CLOEXEC, 3);
    if (in_fd < 0 || out_fd < 0 || dup2(in_fd, 0) < 0 || dup2(out_fd, 1) < 0 || dup2(out_fd, 2) < 0)
      _exit(127);
    close_range(3, ~0U, 0);
    if (chdir(dir.c_str()) != 0) {
      const char *why = std::strerror(errno);
      if (write(2, "uvms campaign: cannot enter the run directory: ", 47) < 0 ||
          write(2, why, std::strlen(why)) < 0 || write(2, "\n", 1) < 0) {
      }
      _exit(127);
    }
    int rc = 127;
    try {
      rc = run_here(args);
    } catch (const std::exception &e) {  // as the uvms program's own backstop (uvms_main.cpp)
      std::cerr << "uvms: error: " << e.what() << '\n';
      rc = 1;
    } catch (...) {
      std::cerr << "uvms: error: unknown exception\n";
      rc = 1;
    }
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
    _exit(rc);  // no exit handlers or destructors: they belong to the campaign's process
  }
  return pid;
}

std::string Clock(double seconds) {
  const long t = long(seconds + 0.5);
  std::ostringstream o;
  o << std::setfill('0') << std::setw(2) << t / 60 << ':' << std::setw(2) << t % 60;
  return o.str();
}

// Directories under runs/ that are no run of this plan (an older id scheme, a removed value).
void NoteStrayDirs(const Campaign &c, const fs::path &runs, std::ostream &out) {
  std::set<std::string> ids;
  for (const CampaignRun &r : c.runs) ids.insert(r.id);
  std::vector<std::string> stray;
  std::error_code ec;
  for (const auto &e : fs::directory_iterator(runs, ec))
    if (e.is_directory() && ids.count(e.path().filename().string()) == 0)
      stray.push_back(e.path().filename().string());
  if (stray.empty()) return;
  std::sort(stray.begin(), stray.end());
  out << "uvms campaign: note: " << stray.size() << " director" << (stray.size() == 1 ? "y" : "ies")
      << " under " << runs.string() << " belong to no run of this plan (left alone, not in the "
      << "results): " << stray.front() << (stray.size() > 1 ? ", ..." : "") << '\n' << std::flush;
}

// Makes a run's directory ready for a new run: the directory exists, no summary.json of an
// earlier run is left, overrides.json holds the run's overrides. Returns the descriptor of a
// fresh run.out (close-on-exec). Every step is checked: throws OutputError naming the path.
// overrides.json is written in place, not atomically: the summary is removed first, and a run
// counts as done only with both files intact and matching (PriorRun), so a torn overrides.json
// makes its run run again. That saves a file, a rename and an fsync per run.
int PrepareRunDir(const fs::path &dir, const CampaignRun &r) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!ec && !fs::is_directory(dir, ec) && !ec)
    ec = std::make_error_code(std::errc::not_a_directory);
  if (ec)
    throw OutputError("cannot create the run directory " + dir.string() + ": " + ec.message());
  const fs::path summary = dir / "summary.json";
  fs::remove(summary, ec);  // no error when there is none
  if (ec) throw OutputError("cannot remove the old " + summary.string() + ": " + ec.message());
  try {
    WriteTextFile(OverridesText(r), (dir / "overrides.json").string());
  } catch (const std::exception &e) {
    throw OutputError(e.what());
  }
  const fs::path log = dir / "run.out";
  const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw OutputError("cannot create " + log.string() + ": " + std::strerror(errno));
  return fd;
}

struct Triage {
  std::vector<const CampaignRun *> todo;
  std::vector<std::string> kept_failed;  // failed earlier, kept (no --retry-failed)
  std::vector<std::string> retried;      // failed earlier, run again (--retry-failed)
};

Triage TriageRuns(const RunInputs &in, const std::vector<const CampaignRun *> &mine,
                  const fs::path &root, const RunOptions &o) {
  Triage t;
  for (const CampaignRun *r : mine) {
    const RunState s = StateOf(root, in, *r, o);
    if (s == RunState::kTodo) t.todo.push_back(r);
    if (s == RunState::kFailedKept) t.kept_failed.push_back(r->id);
    if (s == RunState::kTodo && !o.force_new &&
        PriorRun(root / "runs" / r->id, *r, IdentityOf(in, *r)) == Prior::kFailed)
      t.retried.push_back(r->id);
  }
  return t;
}

// The first lines of an execution: the run count, kept failed runs, retried ones, stray dirs.
void PrintRunsHeader(const Campaign &c, const std::vector<const CampaignRun *> &mine,
                     const Triage &t, const fs::path &root, const RunOptions &o,
                     std::ostream &out) {
  const size_t total = mine.size(), skipped = total - t.todo.size();
  out << "uvms campaign: " << c.name << ": " << total << (total == 1 ? " run" : " runs");
  if (o.shard_count != 0)
    out << " of shard " << o.shard_index << "/" << o.shard_count << " (" << c.runs.size()
        << " in the plan)";
  out << " (" << skipped << " already done), " << o.jobs << " at a time, transport "
      << c.transport << ", logs " << o.logs.Text() << '\n' << std::flush;
  const size_t kept = t.kept_failed.size();
  if (kept != 0)
    out << "uvms campaign: note: " << kept << " of the done runs failed and "
        << (kept == 1 ? "is kept as it is" : "are kept as they are")
        << " (--retry-failed runs failed runs again): " << IdList(t.kept_failed) << '\n'
        << std::flush;
  if (!t.retried.empty())
    out << "uvms campaign: --retry-failed: " << t.retried.size() << " failed run"
        << (t.retried.size() == 1 ? "" : "s") << " run again: " << IdList(t.retried) << '\n'
        << std::flush;
  NoteStrayDirs(c, root / "runs", out);
}

// The progress of the runs to do: a line per finished run (one line rewritten on a terminal).
class Progress {
 public:
  Progress(size_t total, size_t skipped, size_t todo, std::ostream &out)
      : total_(total), skipped_(skipped), todo_(todo), out_(out),
        tty_(isatty(fileno(stdout)) != 0), t0_(std::chrono::steady_clock::now()) {}

  void Finished(const CampaignRun &r, int rc) {
    ++done_;
    const double elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    const double eta_s = elapsed_s / double(done_) * double(todo_ - done_);
    std::ostringstream line;
    line << "[" << (skipped_ + done_) << "/" << total_ << "] elapsed " << Clock(elapsed_s)
         << ", ETA " << Clock(eta_s);
    if (tty_)
      out_ << "\r" << line.str() << "   " << std::flush;
    else
      out_ << line.str() << "  " << r.id << (rc == 0 ? " finished" : " FAILED") << '\n'
           << std::flush;
  }

  void End() {
    if (tty_) out_ << '\n' << std::flush;
  }

 private:
  size_t total_, skipped_, todo_, done_{0};
  std::ostream &out_;
  bool tty_;
  std::chrono::steady_clock::time_point t0_;
};

// A run whose directory is prepared (PrepareRunDir), not started yet.
struct PreparedRun {
  const CampaignRun *run{nullptr};
  int log_fd{-1};
};

// Prepares run `r`'s directory; false with `why` set when it cannot be.
bool PrepareRun(const CampaignRun &r, const fs::path &root, PreparedRun &p, std::string &why) {
  try {
    p.log_fd = PrepareRunDir(root / "runs" / r.id, r);
    p.run = &r;
    return true;
  } catch (const OutputError &e) {
    why = "run " + r.id + ": " + e.what();
    return false;
  }
}

// Starts a prepared run; returns its pid, or -1 with `why` set. The run.out descriptor is closed.
// With `unsynced_summary` the run puts its summary.json in place without an fsync: a
// synchronous write per run held each run's CPU idle for about a millisecond at its end
// (docs/BENCHMARKS.md, "Campaigns past one machine"). The campaign then syncs the file system
// once after its runs (SummarySync); a summary a system crash leaves empty or torn reads as no
// summary (PriorRun), and its run runs again. A run's log, when written, is still synced
// before its summary.
pid_t StartRun(const RunInputs &in, PreparedRun &p, const fs::path &root, const RunOptions &o,
               bool unsynced_summary, std::string &why) {
  const CampaignRun &r = *p.run;
  std::vector<std::string> args = RunArgs(in, r, o.logs.Writes());
  if (unsynced_summary) args.push_back("--no-summary-fsync");
  const pid_t pid = SpawnRun(args, root / "runs" / r.id, p.log_fd, o.run_here);
  const int spawn_errno = errno;
  close(p.log_fd);
  p = PreparedRun{};
  if (pid < 0) why = "cannot start run " + r.id + ": " + std::strerror(spawn_errno);
  return pid;
}

// The exit status of a waited-for run (128 + signal when it was killed).
int ExitOf(int wait_status) {
  if (WIFEXITED(wait_status)) return WEXITSTATUS(wait_status);
  return 128 + (WIFSIGNALED(wait_status) ? WTERMSIG(wait_status) : 0);
}

}  // namespace

bool ExecuteRuns(const RunInputs &in, const std::vector<const CampaignRun *> &mine,
                 const fs::path &root, const RunOptions &o, std::ostream &out,
                 std::ostream &err) {
  if (!o.run_here) throw std::logic_error("ExecuteRuns: RunOptions::run_here is not set");
  const Triage t = TriageRuns(in, mine, root, o);
  // Every run is a fork of this process: each copies its page tables and unmaps them all when it
  // exits. The heap the plan's checks freed (every run's scenario parsed once) goes back to the
  // system first: with 10,000 runs it was 40 of the process's 52 MB, a third of the kernel's
  // time in the campaign.
  malloc_trim(0);
  // ISA-L picks its CRC routine on the first call (CPUID, which a hypervisor traps, and a write
  // to a data page): once here, not in every child.
  const std::uint8_t probe = 0;
  (void)uvms_crc32(&probe, 1);
  const SummarySync summaries(root / "runs");  // opened before the first run (SummarySync)
  if (!summaries.OpenError().empty()) {
    err << "uvms campaign: error: " << summaries.OpenError() << "; no run was started\n";
    return false;
  }
  PrintRunsHeader(*in.campaign, mine, t, root, o, out);
  Progress progress(mine.size(), mine.size() - t.todo.size(), t.todo.size(), out);
  std::map<pid_t, const CampaignRun *> running;
  std::vector<std::string> started_ids;  // the runs started here: their summaries to sync
  size_t next = 0;  // t.todo[next] is the next to prepare
  std::string stop;  // why the campaign stopped starting runs ("" while it goes on)
  // The next run's directory is prepared while the others run: a finished run's slot is filled
  // at once, not after the file system calls of a preparation (about a millisecond).
  PreparedRun ready;
  auto prepare_next = [&] {
    if (ready.run != nullptr || !stop.empty() || next >= t.todo.size()) return;
    if (PrepareRun(*t.todo[next], root, ready, stop)) {
      ++next;
    } else {
      err << "uvms campaign: error: " << stop << '\n';  // at once, not after the running runs
    }
  };
  auto fill_slots = [&] {
    for (prepare_next(); stop.empty() && ready.run != nullptr && running.size() < o.jobs; prepare_next()) {
      const CampaignRun *r = ready.run;
      const pid_t pid = StartRun(in, ready, root, o, summaries.Deferred(), stop);
      if (pid < 0) {
        err << "uvms campaign: error: " << stop << '\n';
        break;
      }
      running[pid] = r;
      started_ids.push_back(r->id);
    }
  };
  fill_slots();
  while (!running.empty()) {
    int st = 0;
    const pid_t pid = waitpid(-1, &st, 0);
    if (pid < 0 && errno == EINTR) continue;
    if (pid < 0) break;
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const CampaignRun *done = it->second;
    running.erase(it);
    fill_slots();  // before the finished run's bookkeeping
    const int rc = ExitOf(st);
    progress.Finished(*done, rc);
    const std::string why = ApplyLogPolicy(o.logs, *done, rc, root / "runs" / done->id);
    if (!why.empty() && stop.empty()) {
      stop = "run " + done->id + ": " + why;
      err << "uvms campaign: error: " << stop << '\n';
    }
  }
  if (ready.run != nullptr) close(ready.log_fd);  // prepared, never started (the campaign stopped)
  progress.End();
  if (const std::string why = summaries.Sync(started_ids, out); !why.empty()) {
    err << "uvms campaign: error: " << why << '\n';
    if (stop.empty()) {
      err << "uvms campaign: the campaign stopped: results not written\n";
      return false;
    }
  }
  if (stop.empty()) return true;
  err << "uvms campaign: the campaign stopped: " << t.todo.size() - started_ids.size() << " of "
      << t.todo.size()
      << " runs to do were not started (the started ones ran to their end); results not "
         "written\n";
  return false;
}

}  // namespace uvms::sil
