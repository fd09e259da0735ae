// SPDX-License-Identifier: Apache-2.0
// plant.hpp: the truth model as one object (SPEC §5): state, right-hand side, tick stepping
// with CVODE, truth outputs, energy integrals, contact monitoring.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "uvms_plant/contact.hpp"
#include "uvms_plant/environment.hpp"
#include "uvms_plant/integrator.hpp"
#include "uvms_plant/multibody.hpp"
#include "uvms_plant/params.hpp"
#include "uvms_plant/propulsion.hpp"

namespace uvms::plant {

/// Where each quantity sits in the plant's state vector (SPEC §5), for n joints and nt
/// thrusters: computed once by Make(), the only place the layout is written down.
///   r0 (3) | quaternion w, x, y, z (4) | v0 (3) | ω0 (3) | motor speeds ω_j (nt) | energies:
///   draw, signed, manipulator, propulsive (4) | distances travelled by the links' aerodynamic
///   centers (n) | motor currents I_j (nt) | θ (n) | θ̇ (n)
/// CVODE integrates a prefix of it (Integrated): within a tick θ and θ̇ follow the held joint
/// acceleration in closed form, and so do the current drive's motor currents their commanded
/// ramp, so they come last and are not integrated.
struct StateLayout {
  std::size_t r0_m{0};             ///< vehicle CoM position, inertial [m]
  std::size_t attitude{0};         ///< quaternion (w, x, y, z), vehicle → inertial
  std::size_t v0_m_s{0};           ///< CoM velocity, inertial [m/s]
  std::size_t w0_rad_s{0};         ///< angular velocity, inertial [rad/s]
  std::size_t motor_speed_rad_s{0};  ///< motor speeds ω_j [rad/s]
  std::size_t energy_draw_J{0};    ///< ∫ Σ max(V·I, 0) dt [J]
  std::size_t energy_signed_J{0};  ///< ∫ Σ V·I dt [J]
  std::size_t energy_manip_J{0};   ///< ∫ Σ |τ·θ̇| dt [J]
  std::size_t energy_prop_J{0};    ///< ∫ Σ |T|^(3/2)/√(2ρA_d) dt [J]
  std::size_t travel_m{0};         ///< distance of each link's aerodynamic center [m]
  std::size_t motor_current_A{0};  ///< motor currents I_j [A]
  std::size_t q_rad{0};            ///< joint angles θ [rad]
  std::size_t qd_rad_s{0};         ///< joint rates θ̇ [rad/s]
  std::size_t size{0};             ///< length of the state vector

  static StateLayout Make(std::size_t joints, std::size_t thrusters) {
    StateLayout l;
    std::size_t at = 0;
    auto take = [&at](std::size_t count) {
      const std::size_t first = at;
      at += count;
      return first;
    };
    l.r0_m = take(3);
    l.attitude = take(4);
    l.v0_m_s = take(3);
    l.w0_rad_s = take(3);
    l.motor_speed_rad_s = take(thrusters);
    l.energy_draw_J = take(1);
    l.energy_signed_J = take(1);
    l.energy_manip_J = take(1);
    l.energy_prop_J = take(1);
    l.travel_m = take(joints);
    l.motor_current_A = take(thrusters);
    l.q_rad = take(joints);
    l.qd_rad_s = take(joints);
    l.size = at;
    return l;
  }
  /// How many leading states CVODE integrates: all but θ, θ̇ and, in the current drive, the
  /// motor currents.
  std::size_t Integrated(bool current_drive) const {
    return current_drive ? motor_current_A : q_rad;
  }
};

/// Initial conditions of a run (motors start at rest: ω = 0, I = 0; energies 0).
struct InitialState {
  Vec3 r0_m{Vec3::Zero()};
  Eigen::Quaterniond attitude{Eigen::Quaterniond::Identity()};  ///< vehicle → inertial
  Vec3 v0_m_s{Vec3::Zero()};
  Vec3 w0_rad_s{Vec3::Zero()};
  std::vector<double> q_rad;      ///< N joint angles (θI)
  std::vector<double> qd_rad_s;   ///< N joint rates (empty: zeros)
};

/// Inputs held constant over one tick (zero-order hold, SPEC §5). The drive
/// (PropulsionParams::drive) decides which motor inputs are used: the voltage drive holds
/// motor_voltage_V; the current drive makes I_j(t) = motor_current_cmd_A[j] +
/// motor_current_rate_A_s[j]·(t − t_k). The vectors of the drive in use need one value per
/// thruster; the other drive's may be empty.
struct PlantInputs {
  std::vector<double> motor_voltage_V;       ///< one per thruster [V]
  std::vector<double> motor_current_cmd_A;   ///< I*_j at the start of the tick [A]
  std::vector<double> motor_current_rate_A_s;  ///< İ*_j over the tick [A/s]
  std::vector<double> joint_accel_rad_s2;    ///< commanded θ̈, one per joint [rad/s²]
  Vec3 disturbance_force_N{Vec3::Zero()};    ///< extra force at the vehicle CoM, inertial [N]
  Vec3 disturbance_moment_Nm{Vec3::Zero()};  ///< extra moment about the CoM, inertial [N·m]
  /// Per thruster, multiplies the thrust the propeller law [47–52] produces (fault model
  /// "efficiency loss": a damaged propeller or duct; the shaft torque is unchanged, so the lost
  /// thrust still costs power). Empty: all 1. Each in [0, 1]. [-]
  std::vector<double> thrust_factor;
};

/// Truth at one instant (SPEC §5). Inertial frame unless named otherwise.
struct Truth {
  double time_s{0.0};
  Vec3 r0_m{Vec3::Zero()};
  Eigen::Quaterniond attitude{Eigen::Quaterniond::Identity()};
  Vec3 v0_m_s{Vec3::Zero()}, w0_rad_s{Vec3::Zero()};
  Vec3 accel_m_s2{Vec3::Zero()}, alpha_rad_s2{Vec3::Zero()};  ///< vehicle accelerations
  std::vector<double> q_rad, qd_rad_s;
  std::vector<double> motor_speed_rad_s, motor_current_A;
  std::vector<double> motor_voltage_V;  ///< terminal voltage [53] at this instant [V]
  std::vector<double> thrust_N;       ///< produced thrust per thruster along u_j [N]
  Vec3 thrust_force_N{Vec3::Zero()};  ///< net produced thrust force [N]
  Vec3 thrust_moment_Nm{Vec3::Zero()};///< net produced thrust moment about the CoM [N·m]
  Vec3 ee_m{Vec3::Zero()}, barycenter_m{Vec3::Zero()}, barycenter_v_m_s{Vec3::Zero()};
  Vec3 flow_m_s{Vec3::Zero()};        ///< v∞(t)
  std::vector<double> joint_torque_Nm;  ///< τ_i of the last held θ̈ [N·m]
  double thruster_energy_J{0.0};        ///< ∫ Σ max(V·I, 0) dt
  double thruster_energy_signed_J{0.0}; ///< ∫ Σ V·I dt
  double manipulator_energy_J{0.0};     ///< ∫ Σ |τ·θ̇| dt
  double propulsive_energy_J{0.0};      ///< ∫ Σ |T|^(3/2)/√(2ρ·A_d) dt, A_d = πD²/4 (SPEC §5)
  double min_clearance_m{0.0};          ///< contact monitor (inf when disabled)
  std::string closest_a, closest_b;     ///< the closest checked pair
  bool contact_breach{false};           ///< closer than the clearance, or touching
};

/// Outcome of a tick.
struct StepStatus {
  enum class Code { kOk, kIntegratorFailure, kContact, kBadInput };
  Code code{Code::kOk};
  std::string message;  ///< empty when ok; otherwise names the cause (flag, bodies, input)
  bool ok() const { return code == Code::kOk; }
};

class Plant {
 public:
  /// Validates the parameters; throws std::invalid_argument naming the problem.
  explicit Plant(PlantParams params);
  ~Plant();
  Plant(const Plant &) = delete;
  Plant &operator=(const Plant &) = delete;

  /// Start a run at t = 0 (throws std::invalid_argument on a bad initial state).
  void Reset(const InitialState &init);
  /// Integrate one tick of length dt_s with inputs held; truth() then holds the new state.
  StepStatus Step(const PlantInputs &in, double dt_s);
  /// Checks the inputs of one tick (sizes, finiteness, thrust factors); empty when usable.
  std::string CheckInputs(const PlantInputs &in, double dt_s) const;

  const Truth &truth() const { return truth_; }
  const PlantParams &params() const { return params_; }
  const ArmModel &model() const { return model_; }
  double ballast_kg() const { return ballast_.mass_kg; }
  /// The ballast the plant carries (SPEC §6.3): TrimBallast() displaced by env.ballast_error_m
  /// when trim is on; none otherwise.
  const Ballast &ballast() const { return ballast_; }
  Integrator::Stats integrator_stats() const;
  std::size_t state_size() const { return lay_.size; }
  const StateLayout &state_layout() const { return lay_; }

  /// The external wrench on the vehicle (force; moment about its CoM, inertial) that would
  /// leave it unaccelerated at the current state with inputs in: the "steady thrust" needed.
  Wrench HoldingWrench(const PlantInputs &in) const;
  /// Right-hand side (public for tests): dy/dt at (t, y) with the given held inputs.
  void Derivatives(double t, const double *y, const PlantInputs &in, double *ydot) const;
  /// The state vector of the current instant (layout: state_layout()).
  const std::vector<double> &state() const { return y_; }

 private:
  struct Eval;  // everything one evaluation computes
  struct MotorTick;  // integrating-factor constants of the current tick (plant.cpp)
  void Evaluate(double t, const double *y, const PlantInputs &in, Eval &e) const;
  struct MotorState;  // one motor's derivatives, current and terminal voltage (plant.cpp)
  /// Motor j at (t, y) in the configured drive (SPEC §5 "Motors"), with propeller torque Q.
  /// Σ_j |T_j|^1.5/√(2ρ·A_d,j) (PropulsivePowerW), each thruster with its own disk [W].
  double PropulsivePower(const std::vector<double> &thrust_N) const;
  MotorState MotorTerms(double t, const double *y, const PlantInputs &in, size_t j,
                        double torque_Nm) const;
  void FillTruth(const PlantInputs &in);
  /// CVODE's right-hand side in the integrator's variables (integrating-factor motor states
  /// and energies when MotorTick is active, else the physical state itself).
  int IntegratorRhs(double t, const double *w, double *wd);
  /// The physical state y at time t of the current tick from the integrator's variables w.
  void ToPhysical(double t, const double *w, double *y) const;
  /// The closed-form states at τ after the tick's start (StateLayout::Integrated) from their
  /// values y_k at the start: θ, θ̇ under the held joint acceleration, the current drive's
  /// currents on their ramp. y may be y_k.
  void ClosedFormStates(double tau_s, const double *y_k, double *y) const;

  PlantParams params_;
  ArmModel model_;
  UnsteadyFlow flow_;
  ContactMonitor contact_;
  Ballast ballast_{};
  int n_{0}, nt_{0};
  StateLayout lay_;  ///< state-vector offsets for n_ joints and nt_ thrusters
  std::unique_ptr<Integrator> integ_;
  std::unique_ptr<Eval> scratch_;  ///< workspace of Derivatives (the plant is single-threaded)
  std::unique_ptr<MotorTick> motor_;    ///< integrating-factor constants of the current tick
  bool thruster_types_{false};          ///< HasThrusterTypes(params_)
  std::vector<PropellerCoeffs> propeller_;  ///< thruster j's propeller laws at env.density_kg_m3
  std::size_t n_int_{0};                ///< states CVODE integrates (StateLayout::Integrated)
  std::vector<double> w_;               ///< the integrator's variables (n_int_ values)
  std::vector<double> y_rhs_, yd_rhs_;  ///< physical state / derivative inside the rhs
  std::vector<double> load_torque_Nm_;  ///< propeller torque Q_j at (t_, y_), from FillTruth
  std::vector<Body> contact_bodies_;  ///< hull, links, obstacles: built once, moved per tick
  std::vector<ContactPair> contact_pairs_;  ///< contact_.CheckedPairs(contact_bodies_), once
  double next_step_s_{0.0};  ///< CVODE's next step at the end of the last tick [s]; 0: none
  PlantInputs held_;
  double t_{0.0};
  std::vector<double> y_;
  Truth truth_;
};

}  // namespace uvms::plant
