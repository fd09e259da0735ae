// SPDX-License-Identifier: Apache-2.0
// run_metrics.hpp: the metrics accumulator of a run (SPEC §10): EE error (mean, max, final),
// attitude error, force/moment shortfalls, the controller's flags and counters, target
// instruction counts. Fed once per tick by the plant node; written into the RunSummary at the
// end. No I/O: a pure function of what it is fed.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "msg/codec.h"
#include "run/alloc_potential.hpp"
#include "run/summary_writer.hpp"
#include "run/tick_analyses.hpp"
#include "scenario/scenario.hpp"  // VerdictLimits
#include "uvms_plant/plant.hpp"

namespace uvms::sil {

/// The verdict on a run that completed its ticks: code OK (run_status_t) or the failure code
/// (CONTROLLER_ERRORS, NON_FINITE, THRUST_LOST, DIVERGED) and a reason naming the value and its
/// limit.
struct Verdict {
  std::int32_t code{0};
  std::string reason;
};

class RunMetrics {
 public:
  /// Starts from the truth at t = 0 (initial positions, the reference attitude).
  explicit RunMetrics(const plant::Truth &initial);
  /// As above, with the tick analyses (tick_analyses.hpp) of scenario sc on the plant of
  /// parameters p: the task-space error and the split of the propulsive energy.
  RunMetrics(const Scenario &sc, const plant::PlantParams &p, const plant::Truth &initial);

  /// The controller's actuators of a tick arrived (status, flags).
  void OnActuators(const uvms_actuators_t &a);
  /// A tick without actuators (missed: the last command was held).
  void OnMissedTick() { ++missed_ticks_; }
  /// The truth at t_k (attitude error against t = 0).
  void OnTruth(const plant::Truth &t);
  /// Tick k's telemetry against the truth's EE at t_k; nullptr: none arrived.
  void OnTelemetry(const plant::Vec3 &ee_truth_m, const uvms_telemetry_t *tl);
  /// Tick k was integrated: the truth at t_k+1, tick k's telemetry (nullptr: none) and the
  /// usable-thruster mask the controller was sent (call after OnTruth of t_k). Measures the
  /// thrust loss: tick k lost its thrust when the controller answered it (status UVMS_OK)
  /// commanding more than kMinCommandedThrust_N in total (Σ_j |P_j|, telemetry thrust_des_N)
  /// and the plant produced less than kLostThrustShare of that total at t_k+1 (Σ_j |T_j|, truth
  /// thrust_N): motor faults (MOTOR_FAULT: V_j = 0), propellers that cannot push, thrusters off.
  /// The longest run of consecutive such ticks, in seconds, is max_thrust_loss_s.
  void OnTickIntegrated(const plant::Truth &after, const uvms_telemetry_t *tl, std::uint32_t usable_mask);

  /// Below this total commanded thrust the controller asks for nothing that could be lost: the
  /// paper's runs without gravity command 0.1 to 0.3 N in total at most, case I exactly 0. [N]
  static constexpr double kMinCommandedThrust_N = 1e-3;
  /// A tick whose produced thrust is under this share of the commanded one lost its thrust
  /// ("≈ 0"): motors spinning up from rest reach it within four ticks in the current drive and
  /// within 0.48 s in the voltage drive, whose speed loop is ≈ 20× slower (docs/MODEL.md §5;
  /// thrust ∝ ω², so 1 % of the thrust is 10 % of the speed). [-]
  static constexpr double kLostThrustShare = 0.01;

  long missed_ticks() const { return missed_ticks_; }
  /// Judge the run against limits (call after the last tick; ticks = ticks integrated).
  Verdict Judge(const VerdictLimits &limits, long ticks, const plant::Truth &final_truth) const;
  /// The metrics into sum, with the final truth (energies, positions, clearance).
  void WriteTo(const plant::Truth &final_truth, RunSummary *sum) const;

 private:
  std::array<double, 3> initial_barycenter_m_, initial_vehicle_position_m_;
  Eigen::Quaterniond q_initial_;
  double ee_err_sum_{0.0};
  long ee_samples_{0};
  long missed_ticks_{0}, missing_telemetry_{0}, controller_error_ticks_{0};
  std::uint32_t controller_flags_seen_{0}, uncontrollable_axes_seen_{0};
  int alloc_min_rank_{6};
  long saturated_ticks_{0}, sensor_held_ticks_{0}, sensor_hold_expired_ticks_{0};
  double max_ee_error_m_{0}, final_ee_error_m_{0}, max_attitude_error_rad_{0};
  double max_vehicle_excursion_m_{0};
  double last_truth_time_s_{0};    ///< t_k of the last OnTruth [s]
  double thrust_loss_s_{0}, max_thrust_loss_s_{0};  ///< current and longest thrust loss [s]
  double min_clearance_m_{std::numeric_limits<double>::infinity()};  // contact monitor, over the run [m]
  double max_force_shortfall_N_{0}, max_moment_shortfall_Nm_{0};
  long controller_rx_rejected_{0}, controller_rx_out_of_sequence_{0},
      controller_rx_unconfigured_{0}, controller_rx_foreign_session_{0};
  std::vector<std::int64_t> target_instructions_;  // per tick (PIL; 0 on the host)
  std::optional<TaskError> task_error_;             // the tick analyses (second constructor)
  std::optional<PropulsiveSplit> propulsive_split_;
  std::optional<AllocationPotential> alloc_potential_;
};

}  // namespace uvms::sil
