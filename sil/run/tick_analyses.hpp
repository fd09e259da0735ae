// SPDX-License-Identifier: Apache-2.0
// tick_analyses.hpp: analyses accumulated tick by tick during a run, so that summary.json holds
// them without a kept log (docs/MODEL.md §10):
//   - TaskError: the true EE's distance from the maneuver's task-space reference: the target
//     point (metrics.ee_target_m, SPEC §8) for joint and hold maneuvers, the commanded cosine
//     line r(t) [78] for the Cartesian line. ε (SPEC §10) is a different quantity and stays.
//   - PropulsiveSplit: the plant's propulsive energy E_p (SPEC §5) split exactly into
//     feedforward / feedback, position / attitude and thruster groups; and the motors' shaft,
//     friction and copper energies.
// No I/O: pure functions of what they are fed.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "msg/codec.h"
#include "run/summary_writer.hpp"
#include "uvms/controller.h"
#include "uvms_plant/plant.hpp"

namespace uvms::sil {

/// The task-space reference of a maneuver (SPEC §8): a fixed point, or the firmware's cosine
/// line (firmware/src/trajectory.c uvms_cosine_line_eval) with r_start the EE at the start.
struct TaskReference {
  bool line{false};                  ///< true: cartesian_line; false: the fixed target
  plant::Vec3 target_m{plant::Vec3::Zero()};      ///< the fixed point, inertial [m]
  plant::Vec3 line_start_m{plant::Vec3::Zero()};  ///< r_start, inertial [m]
  plant::Vec3 line_unit{plant::Vec3::UnitX()};    ///< line direction, unit, inertial
  double line_distance_m{0.0};       ///< rΔ [m]
  double start_s{0.0};               ///< trajectory.start_s [s]
  double duration_s{1.0};            ///< trajectory.duration_s, tF [s]

  double end_s() const { return start_s + duration_s; }  ///< t_F [s]
  /// The reference point at time t_s (the line: r(t') with t' = t − start, clamped to
  /// [0, tF], exactly as the firmware evaluates it).
  plant::Vec3 At(double t_s) const;
};

/// The reference of a run: the line when the controller's trajectory mode is cartesian_line
/// (r_start = ee_start_m, the EE at t = 0: the firmware's start point, the EE at the captured
/// reference pose and θI), the target point otherwise.
TaskReference MakeTaskReference(const uvms_ctrl_config_t &cfg, const plant::Vec3 &target_m,
                                const plant::Vec3 &ee_start_m);

/// The task-space error |p_EE − p_ref(t)| over the truth samples of a run: each tick's t_k and
/// the run's end.
class TaskError {
 public:
  explicit TaskError(const TaskReference &ref) : ref_(ref) {}
  /// One sample: the true EE at time t_s (a tick's, in order).
  void OnSample(double t_s, const plant::Vec3 &ee_m);
  /// The keys task_error_* into sum, with the run's end (final truth) as the last sample.
  void WriteTo(const plant::Truth &final_truth, RunSummary *sum) const;
  const TaskReference &reference() const { return ref_; }

 private:
  struct Acc {
    double sum{0}, max{0}, at_tf{0}, hold_sum{0};
    long n{0}, hold_n{0};
    bool have_tf{false};
  };
  static void Add(const TaskReference &ref, double t_s, double e, Acc *a);
  TaskReference ref_;
  Acc acc_;
};

/// E_p split and the motor energies. Per tick k, the plant's exact increment ΔE_p over
/// [t_k, t_k+1] (its CVODE integral) is shared among the thrusters by the trapezoid of their
/// powers P_j = |T_j|^1.5/√(2ρA_d) at t_k and t_k+1; thruster j's part is split by the commanded
/// shares of the tick (held over it): ff/fb by T_ff,j/T_cmd,j and T_fb,j/T_cmd,j (T_cmd,j =
/// T_ff,j + T_fb,j, T_ff = H⁺·(R0ᵀF_ff; R0ᵀN_ff)), pos/att by the telemetry's thrust_pos/att.
/// The parts add up to ΔE_p exactly; a tick (or thruster) whose split is not exact goes whole
/// into the "unsplit" energy and is counted.
class PropulsiveSplit {
 public:
  explicit PropulsiveSplit(const plant::PlantParams &p, bool pseudoinverse_allocation);
  /// The truth at t_k, before tick k is integrated.
  void BeginTick(const plant::Truth &t);
  /// The truth at t_k+1, tick k's telemetry (nullptr: none) and the usable-thruster mask the
  /// controller was sent.
  void EndTick(const plant::Truth &t, const uvms_telemetry_t *tl, std::uint32_t usable_mask);
  void WriteTo(RunSummary *sum) const;

  /// The group of thruster j: "x", "y" or "z", the axis of u_j's largest component (vehicle).
  const std::string &group(std::size_t j) const { return group_[j]; }
  /// T_ff, T_fb = H⁺ of the usable set applied to the body-frame wrenches of tick k's
  /// telemetry (attitude R0); false when H⁺ does not exist (rank < 6).
  bool SplitCommand(const uvms_telemetry_t &tl, const Eigen::Matrix3d &R0, std::uint32_t usable_mask,
                    Eigen::VectorXd *t_ff, Eigen::VectorXd *t_fb);

 private:
  struct Sample {
    double time_s{0}, energy_J{0};
    Eigen::Matrix3d R0{Eigen::Matrix3d::Identity()};
    std::vector<double> power_W;      // P_j
    double shaft_W{0}, friction_W{0}, copper_W{0};
  };
  Sample Take(const plant::Truth &t) const;
  const Eigen::MatrixXd *PseudoInverse(std::uint32_t usable_mask);

  plant::PlantParams params_;
  bool pinv_{true};
  Eigen::MatrixXd H_;  // 6×n, body frame: (u_j; a_j × u_j)
  std::map<std::uint32_t, Eigen::MatrixXd> pinv_cache_;  // usable mask → H⁺ (empty: rank < 6)
  std::vector<std::string> group_;
  Sample begin_;
  bool begun_{false};
  Sample last_end_;  // the sample EndTick took, which the next BeginTick starts from
  bool have_last_end_{false};
  std::vector<double> thruster_J_;
  double ff_J_{0}, fb_J_{0}, ff_fb_unsplit_J_{0}, pos_J_{0}, att_J_{0}, pos_att_unsplit_J_{0};
  long ff_fb_inexact_ticks_{0}, pos_att_inexact_ticks_{0};
  double shaft_J_{0}, friction_J_{0}, copper_J_{0};
};

}  // namespace uvms::sil
