// SPDX-License-Identifier: Apache-2.0
// summary_writer.hpp: a run's summary (summary.json): its outcome, the SPEC §10 metrics and the
// counters of both nodes, one object with the keys of RunSummary.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "run/faults.hpp"

namespace uvms::sil {

/// The metrics and counters of one run: everything summary.json holds (units in the names).
struct RunSummary {
  std::string scenario;            ///< scenario file
  std::string name;                ///< scenario name
  std::string session;             ///< the run's session, 16 hex digits (sil/msg/session.h)
  std::string transport;           ///< "udpm" or "memq" (set by the caller)
  std::string drive;               ///< motor power stage, "current" or "voltage" (SPEC §5)
  /// Where the numbers come from (set by the caller, sil/run/provenance.hpp): ordered key/value
  /// pairs such as version, git_commit, build_preset, precision, scenario_sha256.
  std::vector<std::pair<std::string, std::string>> provenance;
  std::string status{"failed"};    ///< "finished" or "failed"
  std::string failure;             ///< run_status code name when failed, "harness_error" when the
                                   ///< harness itself failed (plant_node.hpp); "" otherwise
  std::string reason;              ///< readable cause when failed
  long ticks{0};                   ///< ticks integrated
  long ticks_planned{0};           ///< duration / tick
  long missed_ticks{0};            ///< ticks whose actuators did not arrive in time
  long rx_rejected{0};             ///< plant side: undecodable / bad-CRC messages dropped
  long rx_out_of_sequence{0};      ///< plant side: messages of the wrong tick dropped
  long rx_foreign_session{0};      ///< plant side: messages of another session dropped
  long missing_telemetry{0};       ///< ticks without controller telemetry (no EE-error sample)
  long config_retries{0};          ///< config re-sends before the controller answered
  long controller_rx_rejected{0};  ///< controller side, from its last telemetry
  long controller_rx_out_of_sequence{0};
  long controller_rx_unconfigured{0};
  long controller_rx_foreign_session{0};
  long controller_error_ticks{0};  ///< ticks whose controller status was not UVMS_OK
  /// The longest stretch of ticks on which the thrusters produced under 1 % of the thrust the
  /// controller commanded (RunMetrics: thrust lost; the verdict's verdict.max_thrust_loss_s) [s]
  double max_thrust_loss_s{0};
  std::uint32_t controller_flags_seen{0};  ///< OR of every tick's UVMS_FLAG_* bits
  int alloc_min_rank{6};           ///< smallest allocation rank reported (telemetry)
  std::uint32_t uncontrollable_axes_seen{0};  ///< OR of telemetry's lost axes (Fx..Mz bits)
  long saturated_ticks{0};         ///< ticks with THRUST_SATURATED
  long sensor_held_ticks{0};       ///< ticks run on the last good sensor record (SENSOR_HELD)
  long sensor_hold_expired_ticks{0};  ///< ticks with zero thrust after the hold ran out
  double max_force_shortfall_N{0};    ///< max |desired − deliverable| force (telemetry) [N]
  double max_moment_shortfall_Nm{0};  ///< max |desired − deliverable| moment [N·m]
  long target_instructions_median{0};  ///< per-tick instructions of uvms_ctrl_step on the
  long target_instructions_max{0};     ///< target (telemetry; PIL only, 0 on the host)
  double duration_s{0};            ///< simulated time reached [s]
  double mean_ee_error_m{0};       ///< mean of |p_EE − p̂_EE| over the ticks (SPEC §10) [m]
  double max_ee_error_m{0};        ///< its maximum [m]
  double final_ee_error_m{0};      ///< at the last tick [m]
  double thruster_energy_J{0};     ///< ∫ Σ max(V·I, 0) dt (SPEC §5) [J]
  double thruster_energy_signed_J{0};
  double manipulator_energy_J{0};  ///< ∫ Σ |τ·θ̇| dt [J]
  double propulsive_energy_J{0};   ///< ideal actuator-disk ∫ Σ |T|^(3/2)/√(2ρA_d) dt (SPEC §5) [J]
  double max_attitude_error_rad{0};///< max rotation angle of R0 vs its initial value [rad]
  double max_vehicle_excursion_m{0};///< max |r0 − r0(0)| over the ticks [m]
  double min_clearance_m{0};       ///< contact monitor's smallest distance over the run [m]
  std::array<double, 3> final_ee_position_m{}, final_barycenter_m{}, initial_barycenter_m{},
      final_vehicle_position_m{}, initial_vehicle_position_m{};
  // Task-space error (sil/run/tick_analyses.hpp, docs/MODEL.md §10): |p_EE − p_ref(t)| over the
  // truth at every tick and the run's end. p_ref: metrics.ee_target_m ("target") or the
  // commanded cosine line [78] ("line"). NaN (null): not defined for this run.
  std::string task_error_reference;  ///< "target" or "line"
  std::array<double, 3> task_reference_end_m{};  ///< p_ref at t_F (the target, the line's end) [m]
  double task_error_mean_m{0};       ///< mean over the samples [m]
  double task_error_max_m{0};        ///< max over the samples [m]
  double task_error_final_m{0};      ///< at the run's end [m]
  double task_error_at_tf_m{0};      ///< at the first sample t ≥ t_F (null: the run ends before) [m]
  double task_error_hold_mean_m{0};  ///< mean over the samples t > t_F (null: none) [m]
  // The propulsive energy E_p split exactly (tick_analyses.hpp): ff + fb + ff_fb_unsplit =
  // pos + att + pos_att_unsplit = Σ groups = Σ thrusters = propulsive_energy_J.
  double propulsive_energy_ff_J{0}, propulsive_energy_fb_J{0};   ///< feedforward / feedback [J]
  double propulsive_energy_ff_fb_unsplit_J{0};  ///< ticks/thrusters without an exact ff/fb split [J]
  long propulsive_split_inexact_ticks{0};       ///< ticks without an exact ff/fb split
  double propulsive_energy_pos_J{0}, propulsive_energy_att_J{0};  ///< position / attitude [J]
  double propulsive_energy_pos_att_unsplit_J{0};  ///< without an exact pos/att split [J]
  long propulsive_pos_att_inexact_ticks{0};       ///< ticks without an exact pos/att split
  std::vector<double> propulsive_energy_thruster_J;  ///< per thruster j = 1..n [J]
  std::array<double, 3> propulsive_energy_group_J{};  ///< groups x, y, z (axis of u_j) [J]
  std::array<std::vector<int>, 3> propulsive_energy_groups;  ///< thrusters (1-based) of x, y, z
  // The minimum-power allocation's potential on the run's own wrenches (alloc_potential.hpp):
  // ∫Σ|T|^1.5 dt of the pseudoinverse thrusts, of the optimum, of the commanded thrusts.
  double alloc_cost_pinv{0};      ///< C_pinv [N^1.5·s]
  double alloc_cost_optimal{0};   ///< C_opt [N^1.5·s]
  double alloc_cost_commanded{0}; ///< C_cmd [N^1.5·s]
  double alloc_static_potential{0};  ///< 1 − C_opt/C_pinv (null: nothing commanded) [-]
  double alloc_realised_saving{0};   ///< 1 − C_cmd/C_pinv (null: nothing commanded) [-]
  long alloc_potential_unsolved_ticks{0};  ///< ticks the optimum was not found (counted as 0)
  double shaft_energy_J{0};     ///< ∫ Σ Q_j·ω_j dt, trapezoid over the ticks [J]
  double friction_energy_J{0};  ///< ∫ Σ b·ω_j² dt, trapezoid over the ticks [J]
  double copper_energy_J{0};    ///< ∫ Σ Rm·I_j² dt, trapezoid over the ticks [J]
  long integrator_steps{0}, integrator_rhs_evals{0};
  FaultCounters faults;            ///< everything the harness injected (docs/FAULTS.md)
  double wall_time_s{0};           ///< wall time of the run (not in the log) [s]
  double real_time_factor{0};      ///< duration_s / wall_time_s
  double plant_wall_s{0};          ///< of wall_time_s, inside the truth model's Step [s]
};

/// The summary's `failure` name of a run_status_t code ("" for OK).
const char *FailureName(std::int32_t code);

/// Whether an atomic write makes its file durable before renaming it into place.
/// kFsync: fsync first, so the file at the path is whole even after a crash. kNoFsync: no fsync
/// (the kernel writes it back later); after a crash the path may hold an empty or torn file.
/// Only for a caller whose reader takes a torn file for a missing one and that syncs the file
/// system itself: a campaign run's summary.json (the run then runs again; `uvms campaign`
/// calls syncfs once after its runs).
enum class FileSync { kFsync, kNoFsync };

/// Write summary.json (one object, keys as in RunSummary). The metrics (SPEC §10 values) of a
/// run that did not finish are null, and so is any non-finite number. Atomic: written to
/// a fresh path + ".tmp.XXXXXX" (mkostemp), flushed, fsync'd (unless `sync` says not: FileSync),
/// closed and renamed over path; every step is checked.
/// Throws std::runtime_error naming the file and the error (the temporary is removed).
void WriteSummaryJson(const RunSummary &s, const std::string &path,
                      FileSync sync = FileSync::kFsync);

/// Write text to path atomically as WriteSummaryJson does (temp file, fsync, rename; checked).
void WriteTextFileAtomic(const std::string &text, const std::string &path,
                         FileSync sync = FileSync::kFsync);

/// Write text to path in place (created or truncated, mode 0644), every call checked (throws
/// std::runtime_error naming the file and the error); no fsync, no rename. A crash can leave the
/// file torn or empty: only for a file whose reader takes a torn one for a missing one (a
/// campaign run's overrides.json: its run is then run again). Unlike the rename, it writes
/// through a symbolic or hard link at path.
void WriteTextFile(const std::string &text, const std::string &path);

/// A file written piece by piece and then put in place atomically, as WriteTextFileAtomic does
/// (for a file too large to hold in memory: a campaign's results). Every call is checked and
/// throws std::runtime_error naming the file and the error; the temporary is removed on an
/// error, and when the object goes without Commit (nothing is put in place).
class AtomicFile {
 public:
  explicit AtomicFile(const std::string &path);
  AtomicFile(const AtomicFile &) = delete;
  AtomicFile &operator=(const AtomicFile &) = delete;
  ~AtomicFile();
  void Write(std::string_view text);
  void Commit(FileSync sync = FileSync::kFsync);  ///< fsync (FileSync), close, rename over the path

 private:
  [[noreturn]] void Fail(const char *what, int err);
  std::string path_, tmp_;
  int fd_{-1};
};

}  // namespace uvms::sil
