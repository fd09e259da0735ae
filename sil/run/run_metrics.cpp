// SPDX-License-Identifier: Apache-2.0
// run_metrics.cpp: the metrics accumulator of a run (run_metrics.hpp).
#include "run/run_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace uvms::sil {
namespace {

std::array<double, 3> Arr3(const plant::Vec3 &v) { return {v[0], v[1], v[2]}; }

// A maximum that keeps NaN: once a sample is NaN the maximum is NaN (std::max would drop it).
double MaxKeepNan(double m, double x) {
  if (std::isnan(m) || std::isnan(x)) return std::nan("");
  return std::max(m, x);
}

// A minimum that keeps NaN, as MaxKeepNan.
double MinKeepNan(double m, double x) {
  if (std::isnan(m) || std::isnan(x)) return std::nan("");
  return std::min(m, x);
}

// Tick k lost its thrust (RunMetrics::OnTickIntegrated): answered with status UVMS_OK, more than
// kMinCommandedThrust_N commanded in total, less than kLostThrustShare of it produced at t_k+1.
bool ThrustLost(const uvms_telemetry_t *tl, const plant::Truth &after) {
  if (tl == nullptr || tl->status != 0) return false;  // no command known, or the safe output
  double commanded_N = 0.0, produced_N = 0.0;
  for (const double p : tl->thrust_des_N) commanded_N += std::abs(p);
  for (const double t : after.thrust_N) produced_N += std::abs(t);
  return commanded_N > RunMetrics::kMinCommandedThrust_N &&
         produced_N < RunMetrics::kLostThrustShare * commanded_N;
}

std::string Num(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

}  // namespace

RunMetrics::RunMetrics(const plant::Truth &initial)
    : initial_barycenter_m_(Arr3(initial.barycenter_m)),
      initial_vehicle_position_m_(Arr3(initial.r0_m)),
      q_initial_(initial.attitude) {}

RunMetrics::RunMetrics(const Scenario &sc, const plant::PlantParams &p, const plant::Truth &initial)
    : RunMetrics(initial) {
  task_error_.emplace(MakeTaskReference(sc.controller, sc.metrics.ee_target_m, initial.ee_m));
  propulsive_split_.emplace(p, sc.controller.alloc_mode == UVMS_ALLOC_PSEUDOINVERSE);
  alloc_potential_.emplace(sc.controller);
}

void RunMetrics::OnActuators(const uvms_actuators_t &a) {
  if (a.status != 0) ++controller_error_ticks_;
  controller_flags_seen_ |= uint32_t(a.flags);
}

void RunMetrics::OnTruth(const plant::Truth &t) {
  last_truth_time_s_ = t.time_s;
  max_attitude_error_rad_ = MaxKeepNan(max_attitude_error_rad_, t.attitude.angularDistance(q_initial_));
  const double dx = t.r0_m[0] - initial_vehicle_position_m_[0], dy = t.r0_m[1] - initial_vehicle_position_m_[1],
               dz = t.r0_m[2] - initial_vehicle_position_m_[2];
  max_vehicle_excursion_m_ = MaxKeepNan(max_vehicle_excursion_m_, std::hypot(dx, dy, dz));
  min_clearance_m_ = MinKeepNan(min_clearance_m_, t.min_clearance_m);
  if (task_error_) task_error_->OnSample(t.time_s, t.ee_m);
  if (propulsive_split_) propulsive_split_->BeginTick(t);
}

void RunMetrics::OnTickIntegrated(const plant::Truth &after, const uvms_telemetry_t *tl,
                                  std::uint32_t usable_mask) {
  if (propulsive_split_) propulsive_split_->EndTick(after, tl, usable_mask);
  if (alloc_potential_) alloc_potential_->OnTick(tl, usable_mask);
  if (ThrustLost(tl, after)) {
    thrust_loss_s_ += after.time_s - last_truth_time_s_;
    max_thrust_loss_s_ = std::max(max_thrust_loss_s_, thrust_loss_s_);
  } else {
    thrust_loss_s_ = 0.0;
  }
}

// SPEC §10: truth at t_k against the controller's estimate at t_k.
void RunMetrics::OnTelemetry(const plant::Vec3 &ee_truth_m, const uvms_telemetry_t *tl) {
  if (tl == nullptr) {
    ++missing_telemetry_;
    return;
  }
  const plant::Vec3 est(tl->ee_estimate_m[0], tl->ee_estimate_m[1], tl->ee_estimate_m[2]);
  const double e = (ee_truth_m - est).norm();
  ee_err_sum_ += e;
  ++ee_samples_;
  max_ee_error_m_ = MaxKeepNan(max_ee_error_m_, e);
  final_ee_error_m_ = e;
  alloc_min_rank_ = std::min(alloc_min_rank_, int(tl->alloc_rank));
  uncontrollable_axes_seen_ |= uint32_t(tl->uncontrollable_axes);
  const uint32_t fl = uint32_t(tl->flags);
  saturated_ticks_ += (fl & UVMS_FLAG_THRUST_SATURATED) != 0;
  sensor_held_ticks_ += (fl & UVMS_FLAG_SENSOR_HELD) != 0;
  sensor_hold_expired_ticks_ += (fl & UVMS_FLAG_SENSOR_HOLD_EXPIRED) != 0;
  double df = 0.0, dm = 0.0;
  for (int a = 0; a < 3; ++a) {
    df += std::pow(tl->force_des_N[a] - tl->force_deliverable_N[a], 2);
    dm += std::pow(tl->moment_des_Nm[a] - tl->moment_deliverable_Nm[a], 2);
  }
  if (tl->status == 0) {  // a failed tick delivers nothing by design: not a shortfall
    max_force_shortfall_N_ = MaxKeepNan(max_force_shortfall_N_, std::sqrt(df));
    max_moment_shortfall_Nm_ = MaxKeepNan(max_moment_shortfall_Nm_, std::sqrt(dm));
  }
  controller_rx_rejected_ = tl->rx_rejected;
  controller_rx_out_of_sequence_ = tl->rx_out_of_sequence;
  controller_rx_unconfigured_ = tl->rx_unconfigured;
  controller_rx_foreign_session_ = tl->rx_foreign_session;
  target_instructions_.push_back(tl->target_instructions);
}

void RunMetrics::WriteTo(const plant::Truth &t, RunSummary *sum) const {
  sum->missed_ticks = missed_ticks_;
  sum->missing_telemetry = missing_telemetry_;
  sum->controller_rx_rejected = controller_rx_rejected_;
  sum->controller_rx_out_of_sequence = controller_rx_out_of_sequence_;
  sum->controller_rx_unconfigured = controller_rx_unconfigured_;
  sum->controller_rx_foreign_session = controller_rx_foreign_session_;
  sum->controller_error_ticks = controller_error_ticks_;
  sum->max_thrust_loss_s = max_thrust_loss_s_;
  sum->controller_flags_seen = controller_flags_seen_;
  sum->alloc_min_rank = alloc_min_rank_;
  sum->uncontrollable_axes_seen = uncontrollable_axes_seen_;
  sum->saturated_ticks = saturated_ticks_;
  sum->sensor_held_ticks = sensor_held_ticks_;
  sum->sensor_hold_expired_ticks = sensor_hold_expired_ticks_;
  sum->max_force_shortfall_N = max_force_shortfall_N_;
  sum->max_moment_shortfall_Nm = max_moment_shortfall_Nm_;
  sum->mean_ee_error_m = ee_samples_ > 0 ? ee_err_sum_ / double(ee_samples_) : 0.0;
  sum->max_ee_error_m = max_ee_error_m_;
  sum->final_ee_error_m = final_ee_error_m_;
  sum->max_attitude_error_rad = max_attitude_error_rad_;
  sum->max_vehicle_excursion_m = max_vehicle_excursion_m_;
  if (!target_instructions_.empty()) {  // median: the lower middle element (an integer count)
    std::vector<std::int64_t> sorted = target_instructions_;
    std::sort(sorted.begin(), sorted.end());
    sum->target_instructions_median = long(sorted[(sorted.size() - 1) / 2]);
    sum->target_instructions_max = long(sorted.back());
  }
  sum->thruster_energy_J = t.thruster_energy_J;
  sum->thruster_energy_signed_J = t.thruster_energy_signed_J;
  sum->manipulator_energy_J = t.manipulator_energy_J;
  sum->propulsive_energy_J = t.propulsive_energy_J;
  sum->min_clearance_m = MinKeepNan(min_clearance_m_, t.min_clearance_m);  // every tick and the end
  sum->final_ee_position_m = Arr3(t.ee_m);
  sum->final_barycenter_m = Arr3(t.barycenter_m);
  sum->final_vehicle_position_m = Arr3(t.r0_m);
  sum->initial_barycenter_m = initial_barycenter_m_;
  sum->initial_vehicle_position_m = initial_vehicle_position_m_;
  if (task_error_) task_error_->WriteTo(t, sum);
  if (propulsive_split_) propulsive_split_->WriteTo(sum);
  if (alloc_potential_) alloc_potential_->WriteTo(sum);
}

Verdict RunMetrics::Judge(const VerdictLimits &lim, long ticks, const plant::Truth &t) const {
  if (ticks > 0 && double(controller_error_ticks_) > lim.max_error_tick_share * double(ticks))
    return {UVMS_RUN_STATUS_T_CONTROLLER_ERRORS,
            "the controller returned an error status on " + std::to_string(controller_error_ticks_) +
                " of " + std::to_string(ticks) + " ticks (limit: a share of " +
                Num(lim.max_error_tick_share) + ")"};
  const std::pair<const char *, double> values[] = {
      {"mean_ee_error_m", ee_samples_ > 0 ? ee_err_sum_ / double(ee_samples_) : 0.0},
      {"max_ee_error_m", max_ee_error_m_},
      {"final_ee_error_m", final_ee_error_m_},
      {"max_attitude_error_rad", max_attitude_error_rad_},
      {"max_vehicle_excursion_m", max_vehicle_excursion_m_},
      {"max_force_shortfall_N", max_force_shortfall_N_},
      {"max_moment_shortfall_Nm", max_moment_shortfall_Nm_},
      {"thruster_energy_J", t.thruster_energy_J},
      {"thruster_energy_signed_J", t.thruster_energy_signed_J},
      {"manipulator_energy_J", t.manipulator_energy_J},
      {"propulsive_energy_J", t.propulsive_energy_J}};
  for (const auto &[name, v] : values)
    if (!std::isfinite(v)) return {UVMS_RUN_STATUS_T_NON_FINITE, std::string(name) + " is " + Num(v)};
  // Before the divergence it usually causes: a vehicle that cannot push is the cause.
  if (max_thrust_loss_s_ > lim.max_thrust_loss_s)
    return {UVMS_RUN_STATUS_T_THRUST_LOST,
            "max_thrust_loss_s " + Num(max_thrust_loss_s_) + " exceeds its limit " +
                Num(lim.max_thrust_loss_s) + ": for that long the thrusters produced under 1 % of " +
                "the thrust the controller commanded"};
  const std::pair<const char *, std::pair<double, double>> limits[] = {
      {"max_attitude_error_rad", {max_attitude_error_rad_, lim.max_attitude_error_rad}},
      {"max_vehicle_excursion_m", {max_vehicle_excursion_m_, lim.max_vehicle_excursion_m}},
      {"max_ee_error_m", {max_ee_error_m_, lim.max_ee_error_m}}};
  for (const auto &[name, vl] : limits)
    if (vl.first > vl.second)
      return {UVMS_RUN_STATUS_T_DIVERGED,
              std::string(name) + " " + Num(vl.first) + " exceeds its limit " + Num(vl.second)};
  return {};
}

}  // namespace uvms::sil
