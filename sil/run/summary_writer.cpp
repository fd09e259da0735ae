// SPDX-License-Identifier: Apache-2.0
// summary_writer.cpp: summary.json (summary_writer.hpp).
#include "run/summary_writer.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <variant>

#include <nlohmann/json.hpp>

#include "msg/codec.h"

namespace uvms::sil {

const char *FailureName(std::int32_t code) {
  switch (code) {
    case UVMS_RUN_STATUS_T_OK: return "";
    case UVMS_RUN_STATUS_T_CONTROLLER_SILENT: return "controller_silent";
    case UVMS_RUN_STATUS_T_INTEGRATOR_FAILURE: return "integrator_failure";
    case UVMS_RUN_STATUS_T_CONTACT: return "contact";
    case UVMS_RUN_STATUS_T_BAD_INPUT: return "bad_input";
    case UVMS_RUN_STATUS_T_CONFIG_REJECTED: return "config_rejected";
    case UVMS_RUN_STATUS_T_NO_CONTROLLER: return "no_controller";
    case UVMS_RUN_STATUS_T_CONTROLLER_ERRORS: return "controller_errors";
    case UVMS_RUN_STATUS_T_NON_FINITE: return "non_finite";
    case UVMS_RUN_STATUS_T_DIVERGED: return "diverged";
    case UVMS_RUN_STATUS_T_INTERRUPTED: return "interrupted";
    case UVMS_RUN_STATUS_T_HARNESS_ERROR: return "harness_error";
    case UVMS_RUN_STATUS_T_THRUST_LOST: return "thrust_lost";
    default: return "unknown";
  }
}

namespace {

using Json = nlohmann::ordered_json;

// A number, or null when it is not finite.
Json Finite(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

// A metric: null when the run did not finish (its numbers mean nothing) or it is not finite.
Json Metric(const RunSummary &s, double x) { return s.status == "finished" ? Finite(x) : Json(nullptr); }

Json Vec(const std::array<double, 3> &v) { return Json::array({Finite(v[0]), Finite(v[1]), Finite(v[2])}); }

// A member that is a SPEC §10 metric (written with Metric); a plain double is written with Finite.
struct MetricMember {
  double RunSummary::*member;
};

// A summary.json key and the RunSummary member it holds.
struct Field {
  const char *key;
  std::variant<std::string RunSummary::*, long RunSummary::*, int RunSummary::*,
               std::uint32_t RunSummary::*, double RunSummary::*, MetricMember,
               std::array<double, 3> RunSummary::*>
      member;
};

// P: as it is (a double or its 3-vector: null when not finite); M: a metric. The key is the
// member's name, so summary.json and RunSummary cannot drift apart.
#define P(m) Field{#m, &RunSummary::m}
#define M(m) Field{#m, MetricMember{&RunSummary::m}}

// summary.json's keys up to the per-group energies, in order.
const Field kHead[] = {
    P(scenario), P(name), P(session), P(transport), P(drive), P(status), P(failure), P(reason),
    P(ticks), P(ticks_planned), P(missed_ticks), P(duration_s), M(mean_ee_error_m),
    M(max_ee_error_m), M(final_ee_error_m), M(thruster_energy_J), M(thruster_energy_signed_J),
    M(manipulator_energy_J), M(propulsive_energy_J), M(max_attitude_error_rad),
    M(max_vehicle_excursion_m), M(min_clearance_m), P(final_ee_position_m),
    P(final_barycenter_m), P(initial_barycenter_m), P(final_vehicle_position_m),
    P(initial_vehicle_position_m), P(task_error_reference), P(task_reference_end_m),
    M(task_error_mean_m), M(task_error_max_m), M(task_error_final_m), M(task_error_at_tf_m),
    M(task_error_hold_mean_m), M(propulsive_energy_ff_J), M(propulsive_energy_fb_J),
    M(propulsive_energy_ff_fb_unsplit_J), P(propulsive_split_inexact_ticks),
    M(propulsive_energy_pos_J), M(propulsive_energy_att_J),
    M(propulsive_energy_pos_att_unsplit_J), P(propulsive_pos_att_inexact_ticks),
    M(alloc_cost_pinv), M(alloc_cost_optimal), M(alloc_cost_commanded),
    M(alloc_static_potential), M(alloc_realised_saving), P(alloc_potential_unsolved_ticks)};

// From the motor energies to the per-tick counters, in order (before faults and provenance).
const Field kTail[] = {
    M(shaft_energy_J), M(friction_energy_J), M(copper_energy_J), P(rx_rejected),
    P(rx_out_of_sequence), P(rx_foreign_session), P(missing_telemetry), P(config_retries),
    P(controller_rx_rejected), P(controller_rx_out_of_sequence), P(controller_rx_unconfigured),
    P(controller_rx_foreign_session), P(controller_error_ticks), P(max_thrust_loss_s),
    P(controller_flags_seen), P(alloc_min_rank), P(uncontrollable_axes_seen), P(saturated_ticks),
    P(sensor_held_ticks), P(sensor_hold_expired_ticks), M(max_force_shortfall_N),
    M(max_moment_shortfall_Nm), P(target_instructions_median), P(target_instructions_max),
    P(integrator_steps), P(integrator_rhs_evals)};

#undef P
#undef M

// The JSON value of one field of s.
struct FieldValue {
  const RunSummary &s;
  Json operator()(double RunSummary::*m) const { return Finite(s.*m); }
  Json operator()(MetricMember m) const { return Metric(s, s.*(m.member)); }
  Json operator()(std::array<double, 3> RunSummary::*m) const { return Vec(s.*m); }
  template <class T>
  Json operator()(T RunSummary::*m) const {
    return Json(s.*m);
  }
};

void PutFields(const RunSummary &s, const Field *begin, const Field *end, Json &j) {
  for (const Field *f = begin; f != end; ++f) j[f->key] = std::visit(FieldValue{s}, f->member);
}

// summary.json's "faults": what the harness injected, by kind.
Json FaultsJson(const FaultCounters &fc) {
  Json faults = Json::object();
  const std::pair<const char *, const LinkCounters *> dirs[] = {{"sensors", &fc.sensors},
                                                                {"actuators", &fc.actuators}};
  for (const auto &[dir, c] : dirs) {
    const std::string d(dir);
    faults[d + "_dropped"] = c->dropped;
    faults[d + "_delayed"] = c->delayed;
    faults[d + "_duplicated"] = c->duplicated;
    faults[d + "_corrupted"] = c->corrupted;
  }
  faults["sensor_samples_perturbed"] = fc.sensor_samples_perturbed;
  faults["thruster_fault_ticks"] = fc.thruster_fault_ticks;
  return faults;
}

// The E_p split by thruster group and by thruster (between kHead and kTail).
void PutPropulsiveGroups(const RunSummary &s, Json &j) {
  static const char *const kAxes[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a)
    j[std::string("propulsive_energy_group_") + kAxes[a] + "_J"] = Metric(s, s.propulsive_energy_group_J[a]);
  Json groups = Json::object();
  for (int a = 0; a < 3; ++a)
    if (!s.propulsive_energy_groups[a].empty()) groups[kAxes[a]] = s.propulsive_energy_groups[a];
  j["propulsive_energy_groups"] = groups;
  Json per = Json::array();
  for (double e : s.propulsive_energy_thruster_J) per.push_back(Metric(s, e));
  j["propulsive_energy_thruster_J"] = per;
}

[[noreturn]] void WriteFailed(const std::string &what, const std::string &path, int err) {
  throw std::runtime_error(what + " " + path + " failed" + (err != 0 ? std::string(": ") + std::strerror(err) : ""));
}

}  // namespace

// A fresh temporary path.tmp.XXXXXX (mkostemp: a unique name, created exclusively, so two
// processes writing one file, such as the shards of a campaign writing its plan.json from
// several machines or containers that all have pid 1, never share one), mode 0644.
AtomicFile::AtomicFile(const std::string &path) : path_(path), tmp_(path + ".tmp.XXXXXX") {
  fd_ = ::mkostemp(tmp_.data(), O_CLOEXEC);
  if (fd_ < 0) WriteFailed("creating", tmp_, errno);
  if (::fchmod(fd_, 0644) != 0) Fail("setting the mode of", errno);
}

AtomicFile::~AtomicFile() {
  if (fd_ < 0) return;
  ::close(fd_);
  ::unlink(tmp_.c_str());
}

void AtomicFile::Fail(const char *what, int err) {
  ::close(fd_);
  fd_ = -1;
  ::unlink(tmp_.c_str());
  WriteFailed(what, tmp_, err);
}

// All of text to fd, through short writes and signals: 0, or the error (ENOSPC for a write
// that wrote nothing).
static int WriteAll(int fd, std::string_view text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return n < 0 ? errno : ENOSPC;
    done += size_t(n);
  }
  return 0;
}

void AtomicFile::Write(std::string_view text) {
  if (const int e = WriteAll(fd_, text); e != 0) Fail("writing", e);
}

void AtomicFile::Commit(FileSync sync) {
  if (sync == FileSync::kFsync && ::fsync(fd_) != 0 && errno != EINVAL) Fail("syncing", errno);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const int e = errno;
    ::unlink(tmp_.c_str());
    WriteFailed("closing", tmp_, e);
  }
  if (std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    const int e = errno;
    ::unlink(tmp_.c_str());
    WriteFailed("renaming " + tmp_ + " to", path_, e);
  }
}

void WriteTextFileAtomic(const std::string &text, const std::string &path, FileSync sync) {
  AtomicFile f(path);
  f.Write(text);
  f.Commit(sync);
}

void WriteTextFile(const std::string &text, const std::string &path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) WriteFailed("creating", path, errno);
  if (::fchmod(fd, 0644) != 0) {  // 0644 whatever the umask, as AtomicFile
    const int e = errno;
    ::close(fd);
    WriteFailed("setting the mode of", path, e);
  }
  if (const int e = WriteAll(fd, text); e != 0) {
    ::close(fd);
    WriteFailed("writing", path, e);
  }
  if (::close(fd) != 0) WriteFailed("closing", path, errno);
}

void WriteSummaryJson(const RunSummary &s, const std::string &path, FileSync sync) {
  Json j;
  PutFields(s, std::begin(kHead), std::end(kHead), j);
  PutPropulsiveGroups(s, j);
  PutFields(s, std::begin(kTail), std::end(kTail), j);
  j["faults"] = FaultsJson(s.faults);
  Json prov = Json::object();
  for (const auto &kv : s.provenance) prov[kv.first] = kv.second;
  j["provenance"] = prov;
  j["wall_time_s"] = Finite(s.wall_time_s);
  j["real_time_factor"] = Finite(s.real_time_factor);
  j["plant_wall_s"] = Finite(s.plant_wall_s);
  WriteTextFileAtomic(j.dump(2) + "\n", path, sync);
}

}  // namespace uvms::sil
