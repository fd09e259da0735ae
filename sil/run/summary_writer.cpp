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

void AtomicFile::Write(std::string_view text) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) Fail("writing", n < 0 ? errno : ENOSPC);
    done += size_t(n);
  }
}

void AtomicFile::Commit() {
  if (::fsync(fd_) != 0 && errno != EINVAL) Fail("syncing", errno);
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

void WriteTextFileAtomic(const std::string &text, const std::string &path) {
  AtomicFile f(path);
  f.Write(text);
  f.Commit();
}

void WriteSummaryJson(const RunSummary &s, const std::string &path) {
  nlohmann::ordered_json j;
  j["scenario"] = s.scenario;
  j["name"] = s.name;
  j["session"] = s.session;
  j["transport"] = s.transport;
  j["drive"] = s.drive;
  j["status"] = s.status;
  j["failure"] = s.failure;
  j["reason"] = s.reason;
  j["ticks"] = s.ticks;
  j["ticks_planned"] = s.ticks_planned;
  j["missed_ticks"] = s.missed_ticks;
  j["duration_s"] = s.duration_s;
  j["mean_ee_error_m"] = Metric(s, s.mean_ee_error_m);
  j["max_ee_error_m"] = Metric(s, s.max_ee_error_m);
  j["final_ee_error_m"] = Metric(s, s.final_ee_error_m);
  j["thruster_energy_J"] = Metric(s, s.thruster_energy_J);
  j["thruster_energy_signed_J"] = Metric(s, s.thruster_energy_signed_J);
  j["manipulator_energy_J"] = Metric(s, s.manipulator_energy_J);
  j["propulsive_energy_J"] = Metric(s, s.propulsive_energy_J);
  j["max_attitude_error_rad"] = Metric(s, s.max_attitude_error_rad);
  j["max_vehicle_excursion_m"] = Metric(s, s.max_vehicle_excursion_m);
  j["min_clearance_m"] = Metric(s, s.min_clearance_m);
  j["final_ee_position_m"] = Vec(s.final_ee_position_m);
  j["final_barycenter_m"] = Vec(s.final_barycenter_m);
  j["initial_barycenter_m"] = Vec(s.initial_barycenter_m);
  j["final_vehicle_position_m"] = Vec(s.final_vehicle_position_m);
  j["initial_vehicle_position_m"] = Vec(s.initial_vehicle_position_m);
  j["task_error_reference"] = s.task_error_reference;
  j["task_reference_end_m"] = Vec(s.task_reference_end_m);
  j["task_error_mean_m"] = Metric(s, s.task_error_mean_m);
  j["task_error_max_m"] = Metric(s, s.task_error_max_m);
  j["task_error_final_m"] = Metric(s, s.task_error_final_m);
  j["task_error_at_tf_m"] = Metric(s, s.task_error_at_tf_m);
  j["task_error_hold_mean_m"] = Metric(s, s.task_error_hold_mean_m);
  j["propulsive_energy_ff_J"] = Metric(s, s.propulsive_energy_ff_J);
  j["propulsive_energy_fb_J"] = Metric(s, s.propulsive_energy_fb_J);
  j["propulsive_energy_ff_fb_unsplit_J"] = Metric(s, s.propulsive_energy_ff_fb_unsplit_J);
  j["propulsive_split_inexact_ticks"] = s.propulsive_split_inexact_ticks;
  j["propulsive_energy_pos_J"] = Metric(s, s.propulsive_energy_pos_J);
  j["propulsive_energy_att_J"] = Metric(s, s.propulsive_energy_att_J);
  j["propulsive_energy_pos_att_unsplit_J"] = Metric(s, s.propulsive_energy_pos_att_unsplit_J);
  j["propulsive_pos_att_inexact_ticks"] = s.propulsive_pos_att_inexact_ticks;
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
  j["shaft_energy_J"] = Metric(s, s.shaft_energy_J);
  j["friction_energy_J"] = Metric(s, s.friction_energy_J);
  j["copper_energy_J"] = Metric(s, s.copper_energy_J);
  j["rx_rejected"] = s.rx_rejected;
  j["rx_out_of_sequence"] = s.rx_out_of_sequence;
  j["rx_foreign_session"] = s.rx_foreign_session;
  j["missing_telemetry"] = s.missing_telemetry;
  j["config_retries"] = s.config_retries;
  j["controller_rx_rejected"] = s.controller_rx_rejected;
  j["controller_rx_out_of_sequence"] = s.controller_rx_out_of_sequence;
  j["controller_rx_unconfigured"] = s.controller_rx_unconfigured;
  j["controller_rx_foreign_session"] = s.controller_rx_foreign_session;
  j["controller_error_ticks"] = s.controller_error_ticks;
  j["max_thrust_loss_s"] = Finite(s.max_thrust_loss_s);
  j["controller_flags_seen"] = s.controller_flags_seen;
  j["alloc_min_rank"] = s.alloc_min_rank;
  j["uncontrollable_axes_seen"] = s.uncontrollable_axes_seen;
  j["saturated_ticks"] = s.saturated_ticks;
  j["sensor_held_ticks"] = s.sensor_held_ticks;
  j["sensor_hold_expired_ticks"] = s.sensor_hold_expired_ticks;
  j["max_force_shortfall_N"] = Metric(s, s.max_force_shortfall_N);
  j["max_moment_shortfall_Nm"] = Metric(s, s.max_moment_shortfall_Nm);
  j["target_instructions_median"] = s.target_instructions_median;
  j["target_instructions_max"] = s.target_instructions_max;
  j["integrator_steps"] = s.integrator_steps;
  j["integrator_rhs_evals"] = s.integrator_rhs_evals;
  const FaultCounters &fc = s.faults;
  j["faults"] = {{"sensors_dropped", fc.sensors_dropped},
                 {"sensors_delayed", fc.sensors_delayed},
                 {"sensors_duplicated", fc.sensors_duplicated},
                 {"sensors_corrupted", fc.sensors_corrupted},
                 {"actuators_dropped", fc.actuators_dropped},
                 {"actuators_delayed", fc.actuators_delayed},
                 {"actuators_duplicated", fc.actuators_duplicated},
                 {"actuators_corrupted", fc.actuators_corrupted},
                 {"sensor_samples_perturbed", fc.sensor_samples_perturbed},
                 {"thruster_fault_ticks", fc.thruster_fault_ticks}};
  nlohmann::ordered_json prov = nlohmann::ordered_json::object();
  for (const auto &kv : s.provenance) prov[kv.first] = kv.second;
  j["provenance"] = prov;
  j["wall_time_s"] = Finite(s.wall_time_s);
  j["real_time_factor"] = Finite(s.real_time_factor);
  WriteTextFileAtomic(j.dump(2) + "\n", path);
}

}  // namespace uvms::sil
