// SPDX-License-Identifier: Apache-2.0
// scenario.hpp: a SIL scenario (TOML, toml++): every setting of SPEC with the paper's values
// as defaults, resolved into the two independent configurations the run needs: the firmware
// controller's (uvms_ctrl_config_t) and the plant's (uvms::plant::PlantParams), plus the
// harness's own settings. The keys, their targets, units, defaults and ranges are one table,
// sil/msg/config_table.h (`uvms scenario schema` prints it; docs/SCENARIOS.md's key tables are
// generated from it).
//
// Errors (unknown keys, wrong types, out-of-range values, contradictory settings, --set
// overrides that do not parse) throw ScenarioError whose message names the file, the line and
// the dotted key: "sil/scenarios/x.toml:12: key \"control.case\": expected one of I..VIII".
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "uvms/controller.h"
#include "uvms_plant/plant.hpp"

namespace uvms::sil {

/// Most [[contact.obstacle]] entries a scenario may have, and the longest obstacle name [bytes]:
/// the scene message of a run (scene_t: every obstacle's name and cylinder) must fit one encoded
/// message of UVMS_MAX_MSG_BYTES (sil/msg/codec.h; checked in tests/sil/test_scene_message.cpp).
inline constexpr size_t kMaxObstacles = 64;
inline constexpr size_t kMaxObstacleName = 48;

class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// How the harness runs the lockstep link.
struct LinkSettings {
  double timeout_s{1.0};      ///< wall-clock wait for the actuators of a tick [s]
  int max_missed{5};          ///< consecutive missed ticks that stop the run
  double realtime_factor{0};  ///< 0: as fast as possible; r > 0: pace at r × real time
  bool publish_truth{false};  ///< true: truth_t is also published on the link (always logged)
  int spin_us{2000};  ///< udpm: busy-poll this long before blocking on the link [µs] (sil/link/lcm_wait.h)
};

/// The busy-poll budget the nodes use [µs]: link.spin_us, except 0 for paced runs
/// (realtime_factor > 0), whose nodes wait most of each tick and would only burn the CPU.
inline int LinkSpinUs(const LinkSettings &link) { return link.realtime_factor > 0.0 ? 0 : link.spin_us; }

/// One [[arm.link]] as a scenario gives it: the plant's link and the joint limits that only the
/// controller has (its sensor plausibility check, uvms_link_params_t).
struct ArmLink : plant::LinkParams {
  /// Joint limits [rad]; by default ±2π, as uvms_arm_params_paper() gives the paper's arm
  /// (its SPEC §8 poses reach 266°).
  double joint_min_rad{-2.0 * M_PI};
  double joint_max_rad{2.0 * M_PI};
};

/// A thruster fault injected by the harness (docs/FAULTS.md).
struct ThrusterFault {
  enum class Mode { kOff, kStuck, kEfficiency };
  int thruster{1};              ///< j, 1-based as in SPEC §3.4
  Mode mode{Mode::kOff};
  double start_s{0.0};          ///< the fault begins at the first tick at or after this [s]
  double stuck_voltage_V{0.0};  ///< kStuck, voltage drive: the motor gets this voltage whatever is commanded [V]
  double stuck_current_A{0.0};  ///< kStuck, current drive: the motor gets this current whatever is commanded [A]
  double efficiency{1.0};       ///< kEfficiency: produced thrust × this, in [0, 1) [-]
  bool reported{true};          ///< the controller is told (thruster_usable_mask bit cleared) ...
  double detect_delay_s{0.0};   ///< ... this long after start_s [s]
};

/// Noise (zero-mean Gaussian, standard deviation) and bias added to one sensor group; each
/// component gets bias + std·N(0, 1) (attitude: a small rotation of that rotation vector).
struct SensorNoise {
  double std{0.0};
  double bias{0.0};
};

/// Sensor faults, per group (units: the group's).
struct SensorFaults {
  SensorNoise position_m, attitude_rad, velocity_m_s, angular_velocity_rad_s, joint_position_rad,
      joint_velocity_rad_s, motor_speed_rad_s, motor_current_A;
  bool any() const;
};

/// Link faults: per message, at most one of drop, delay (by one tick), duplicate, corrupt (one
/// random bit flipped), drawn with these probabilities.
struct LinkFaults {
  double drop_rate{0.0}, delay_rate{0.0}, duplicate_rate{0.0}, corrupt_rate{0.0};
  bool sensors{true};    ///< apply to sensors_t (plant → controller)
  bool actuators{true};  ///< apply to actuators_t (controller → plant)
  bool any() const { return drop_rate + delay_rate + duplicate_rate + corrupt_rate > 0.0; }
};

/// Everything `[faults]` can inject; all off by default. Random draws use the run seed.
struct FaultSettings {
  std::vector<ThrusterFault> thrusters;
  SensorFaults sensors;
  LinkFaults link;
};

/// Limits beyond which a run that completed its ticks is still "failed" (docs/FAULTS.md
/// "Run verdicts"): scenario keys verdict.* (sil/msg/config_table.h), whose defaults these are.
/// Generous for the paper's 842 runs (their largest values: attitude 0.24 rad, vehicle
/// excursion 0.42 m, EE error 0.36 m, no error tick). Thrust loss (sil/run/run_metrics.hpp): at most 0.12 s
/// in the 2,942 runs of the paper's and the beyond campaigns (current drive), 0.48 s at the
/// start of a paper case in the voltage drive (its slow spin-up, docs/MODEL.md §5).
struct VerdictLimits {
  double max_error_tick_share{0.05};    ///< controller status != UVMS_OK on a larger share of ticks fails [-]
  double max_attitude_error_rad{0.5};   ///< max attitude error beyond this: diverged [rad]
  double max_vehicle_excursion_m{5.0};  ///< max |r0 − r0(0)| beyond this: diverged [m]
  double max_ee_error_m{1.0};           ///< max EE error beyond this: diverged [m]
  double max_thrust_loss_s{1.0};        ///< commanded thrust not produced for longer: thrust_lost [s]
};

/// [metrics]: settings of the run's analyses (sil/run/tick_analyses.hpp, docs/MODEL.md §10).
struct MetricsSettings {
  /// The task-space error of joint and hold maneuvers is the EE's distance from this point,
  /// inertial [m]. Default: the paper's target point (2.428, 0.250, 0.404) m (SPEC §8) in this
  /// project's inertial frame, i.e. less the arm-base offset s0 = (0.914, 0, 0.152) m: the
  /// paper's point lies exactly s0 beyond where its "Veh." column puts the EE with the vehicle
  /// at the origin (docs/MODEL.md §10; checked by PaperTargetPointIsVehColumnEePlusBaseOffset
  /// in tests/firmware/test_joint_table.cpp).
  plant::Vec3 ee_target_m{plant::Vec3(1.514, 0.250, 0.252)};
};

/// A fully resolved scenario.
struct Scenario {
  std::string source;       ///< file name it came from ("<string>" when parsed from text)
  std::string name;         ///< [run] name (default: the file's stem)
  double duration_s{60.0};  ///< run length [s] (SPEC §3.5)
  double tick_s{0.03};      ///< controller period = plant tick [s] (SPEC §3.5)
  std::uint64_t seed{1};    ///< the run's seed (unsteady flow, later noise/faults)
  int case_number{0};       ///< 1..8 when a Table X case was named, 0 for explicit switches
  bool density_error{false};///< the controller's model ρ differs from the plant's (SPEC §6.2:
                            ///< environment.density_error gives 1000 vs 1025)
  uvms_ctrl_config_t controller{};   ///< complete firmware configuration
  plant::PlantParams plant{};        ///< complete plant configuration
  plant::InitialState initial{};     ///< vehicle at rest at the origin, joints at θI
  LinkSettings link{};
  FaultSettings faults{};
  VerdictLimits verdict{};           ///< [verdict]: the plant node judges the run by these
  MetricsSettings metrics{};         ///< [metrics]: the run's analyses
  std::vector<std::string> overrides;///< the --set strings applied, in order
};

/// Ticks of a run: duration_s / tick_s, rounded to the nearest integer when within 1e-9 of
/// it, otherwise rounded up (the last tick then ends after duration_s).
std::int64_t ScenarioTicks(const Scenario &scenario);

/// The one line `uvms scenario check` prints: name, case or switches, payload, durations,
/// tick count, flow and density conditions.
std::string ScenarioSummary(const Scenario &scenario);

/// SPEC §8 initial joint angles θI [deg].
std::array<double, 7> PaperThetaStartDeg();

/// SPEC §8 final joint angles [deg]: the "Veh." column for the vehicle reference, the
/// barycenter column of `payload_kg` (exactly 0, 1, 2, 5 or 10) for the barycenter reference.
/// Returns false (and leaves *deg alone) when the table has no such column.
bool PaperThetaFinalDeg(uvms_reference_t reference, double payload_kg, std::array<double, 7> *deg);

/// Parse and validate TOML text. `source` names it in errors. `overrides` are
/// "section.key=value" strings (value in TOML syntax: 10, 1e-6, true, "VII", [1, 0, 0])
/// applied on top of the file before validation.
Scenario ParseScenario(std::string_view toml_text, const std::string &source,
                       const std::vector<std::string> &overrides = {});

/// Read a file and parse it (ScenarioError also when the file cannot be read).
Scenario LoadScenario(const std::string &path, const std::vector<std::string> &overrides = {});


}  // namespace uvms::sil
