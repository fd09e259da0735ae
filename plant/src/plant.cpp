// plant.cpp: the truth model (SPEC §5). State vector layout (N joints, M thrusters):
//   [0,3)        r0: vehicle CoM position, inertial [m]
//   [3,7)        attitude quaternion (w, x, y, z), vehicle → inertial
//   [7,10)       v0: CoM velocity, inertial [m/s]
//   [10,13)      ω0: angular velocity, inertial [rad/s]
//   [13,13+N)    θ [rad];  then N θ̇ [rad/s]
//   then M motor speeds ω_j [rad/s], M motor currents I_j [A]
//   then 3 energies: ∫Σmax(V·I,0) dt, ∫ΣV·I dt, ∫Σ|τ·θ̇| dt [J]
//   then N distances travelled by the links' aerodynamic centers through the water [m]
#include "uvms_plant/plant.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "uvms_plant/propulsion.hpp"

namespace uvms::plant {

namespace {
constexpr int kR = 0, kQ = 3, kV = 7, kW = 10, kJ = 13;

ContactMonitor MakeMonitor(const PlantParams &p) {
  // Links meet their neighbours at joints, and links joined by short links touch by
  // construction (the WAM's elbow: links 3 and 5 are folded side by side 0.045 m apart, less
  // than their 0.089 m diameter). A pair of links is ignored when the links strictly between
  // them are together shorter than the two radii; so are the links that meet the hull at the
  // arm mount (the first links up to the first one with length).
  std::vector<std::pair<std::string, std::string>> ignore;
  const int n = static_cast<int>(p.links.size());
  auto len = [&](int i) { return std::hypot(p.links[size_t(i - 1)].a_m, p.links[size_t(i - 1)].d_m); };
  auto radius = [&](int i) { return 0.5 * p.links[size_t(i - 1)].diameter_m; };
  for (int i = 1; i <= n; ++i) {
    double between = 0.0;
    for (int j = i + 1; j <= n; ++j) {
      if (between <= radius(i) + radius(j))
        ignore.emplace_back("link" + std::to_string(i), "link" + std::to_string(j));
      between += len(j);
    }
  }
  for (int j = 1; j <= n; ++j) {
    ignore.emplace_back("hull", "link" + std::to_string(j));
    if (len(j) > 0.0) break;
  }
  return ContactMonitor(p.contact.clearance_m, ignore);
}
}  // namespace

struct Plant::Eval {
  BaseState base;
  FluidState fluid;
  ArmKinematics kin;
  ArmLoads loads;
  Wrench vehicle_w0;
  Mat6 vehicle_M{Mat6::Zero()};
  Vec3 vehicle_drag{Vec3::Zero()};
  Wrench thrust;
  std::vector<double> thrust_N, torque_Nm;
  Vec6 accel{Vec6::Zero()};
  Wrench bias;  ///< thrust wrench (about r0) that would leave the vehicle unaccelerated
  JointWrenches joints;
};

Wrench Plant::HoldingWrench(const PlantInputs &in) const {
  Eval e;
  Evaluate(t_, y_.data(), in, e);
  return e.bias;
}

Plant::Plant(PlantParams params)
    : params_(std::move(params)),
      model_(ArmModel::FromParams(params_)),
      flow_(params_.env.unsteady, params_.env.steady_flow_m_s),
      contact_(MakeMonitor(params_)) {
  ValidatePropulsionParams(params_.propulsion);
  if (params_.thrusters.empty() || params_.thrusters.size() > 16)
    throw std::invalid_argument("plant: need 1..16 thrusters, got " + std::to_string(params_.thrusters.size()));
  for (const auto &t : params_.thrusters)
    if (!t.position_m.allFinite() || !t.direction.allFinite() || t.direction.norm() < 1e-9)
      throw std::invalid_argument("plant: thruster geometry must be finite with a non-zero direction");
  const EnvironmentParams &e = params_.env;
  if (!(e.density_kg_m3 >= 0.0) || !std::isfinite(e.density_kg_m3))
    throw std::invalid_argument("plant: env.density_kg_m3 must be finite and >= 0");
  if (!e.gravity_m_s2.allFinite()) throw std::invalid_argument("plant: env.gravity_m_s2 must be finite");
  if (e.variable_coefficients) {
    if (params_.env.coeff_table.empty()) params_.env.coeff_table = DefaultCoeffTable();
    ValidateCoeffTable(params_.env.coeff_table);
  }
  if (e.trim) ballast_kg_ = TrimBallastKg(params_, e.density_kg_m3, e.trim_payload_kg);
  n_ = model_.n;
  nt_ = static_cast<int>(params_.thrusters.size());
  nx_ = static_cast<size_t>(kJ + 2 * n_ + 2 * nt_ + 3 + n_);
  for (auto &t : params_.thrusters) t.direction.normalize();
  integ_ = std::make_unique<Integrator>(nx_, params_.integrator, [this](double t, const double *y, double *yd) {
    Derivatives(t, y, held_, yd);
    for (size_t i = 0; i < nx_; ++i)
      if (!std::isfinite(yd[i])) return -1;  // fatal: never integrate NaN
    return 0;
  });
  y_.assign(nx_, 0.0);
  scratch_ = std::make_unique<Eval>();
}

Plant::~Plant() = default;

Integrator::Stats Plant::integrator_stats() const { return integ_->GetStats(); }

void Plant::Reset(const InitialState &init) {
  if (static_cast<int>(init.q_rad.size()) != n_)
    throw std::invalid_argument("plant: initial q_rad needs " + std::to_string(n_) + " joint angles");
  if (!init.qd_rad_s.empty() && static_cast<int>(init.qd_rad_s.size()) != n_)
    throw std::invalid_argument("plant: initial qd_rad_s needs " + std::to_string(n_) + " rates (or none)");
  if (!init.r0_m.allFinite() || !init.v0_m_s.allFinite() || !init.w0_rad_s.allFinite() ||
      !init.attitude.coeffs().allFinite() || init.attitude.norm() < 1e-9)
    throw std::invalid_argument("plant: initial vehicle state must be finite with a non-zero quaternion");
  std::fill(y_.begin(), y_.end(), 0.0);
  const Eigen::Quaterniond q = init.attitude.normalized();
  for (int k = 0; k < 3; ++k) {
    y_[size_t(kR + k)] = init.r0_m[k];
    y_[size_t(kV + k)] = init.v0_m_s[k];
    y_[size_t(kW + k)] = init.w0_rad_s[k];
  }
  y_[kQ] = q.w();
  y_[kQ + 1] = q.x();
  y_[kQ + 2] = q.y();
  y_[kQ + 3] = q.z();
  for (int j = 0; j < n_; ++j) {
    y_[size_t(kJ + j)] = init.q_rad[size_t(j)];
    y_[size_t(kJ + n_ + j)] = init.qd_rad_s.empty() ? 0.0 : init.qd_rad_s[size_t(j)];
  }
  t_ = 0.0;
  held_ = PlantInputs{};
  held_.motor_voltage_V.assign(size_t(nt_), 0.0);
  held_.joint_accel_rad_s2.assign(size_t(n_), 0.0);
  FillTruth(held_);
}

void Plant::Evaluate(double t, const double *y, const PlantInputs &in, Eval &e) const {
  const int n = n_, nt = nt_;
  const double *q = y + kJ, *qd = y + kJ + n;
  const double *wm = y + kJ + 2 * n;
  const double *travel = y + kJ + 2 * n + 2 * nt + 3;
  Eigen::Quaterniond quat(y[kQ], y[kQ + 1], y[kQ + 2], y[kQ + 3]);
  quat.normalize();  // the integrator lets |q| drift slightly between ticks
  e.base.r0_m = Vec3(y[kR], y[kR + 1], y[kR + 2]);
  e.base.R0 = quat.toRotationMatrix();
  e.base.v0_m_s = Vec3(y[kV], y[kV + 1], y[kV + 2]);
  e.base.w0_rad_s = Vec3(y[kW], y[kW + 1], y[kW + 2]);

  const EnvironmentParams &env = params_.env;
  e.fluid.density_kg_m3 = env.density_kg_m3;
  e.fluid.flow_m_s = flow_.Velocity(t);  // SPEC §6.1: only the plant sees the unsteady part
  e.fluid.gravity_m_s2 = env.gravity_m_s2;
  e.fluid.angle_of_attack = env.angle_of_attack;
  e.fluid.ballast_kg = ballast_kg_;
  e.fluid.drag_factor.clear();
  e.fluid.added_mass_factor.clear();
  if (env.variable_coefficients) {  // SPEC §6.4: factors by distance travelled, in diameters
    for (int i = 0; i < n; ++i) {
      const double dl = model_.link[size_t(i)].diameter_m;
      const CoeffFactors c = InterpolateCoeffs(env.coeff_table, dl > 0.0 ? travel[i] / dl : 0.0);
      e.fluid.drag_factor.push_back(c.drag_factor);
      e.fluid.added_mass_factor.push_back(c.added_mass_factor);
    }
  }

  const double *qdd = in.joint_accel_rad_s2.data();
  ComputeArmKinematics(model_, e.base, q, qd, qdd, e.kin);
  ComputeArmLoads(model_, e.base, e.fluid, e.kin, e.loads);
  ComputeVehicleLoads(model_, e.base, e.fluid, e.vehicle_w0, e.vehicle_M, e.vehicle_drag);

  // Thrusters [47–52]: thrust along u_j at a_j from the motor speed and advance speed.
  e.thrust = Wrench{};
  e.thrust_N.assign(size_t(nt), 0.0);
  e.torque_Nm.assign(size_t(nt), 0.0);
  for (int j = 0; j < nt; ++j) {
    const ThrusterGeometry &g = params_.thrusters[size_t(j)];
    const double va = AdvanceSpeedMS(g, e.base.R0, e.base.v0_m_s, e.base.w0_rad_s, e.fluid.flow_m_s);
    e.thrust_N[size_t(j)] = ThrustN(params_.propulsion, env.density_kg_m3, wm[j], va);
    e.torque_Nm[size_t(j)] = TorqueNm(params_.propulsion, env.density_kg_m3, wm[j], va);
    const Vec3 F = e.base.R0 * g.direction * e.thrust_N[size_t(j)];
    e.thrust.force_N += F;
    e.thrust.moment_Nm += (e.base.R0 * g.position_m).cross(F);
  }

  // SPEC §5: M_sys·(v̇0, ω̇0) = thrust + disturbance − bias, solved in every evaluation.
  const Mat6 M = e.loads.arm_inertia_r0 + e.vehicle_M;
  Wrench bias{e.loads.arm_wrench0_r0.force_N + e.vehicle_w0.force_N,
              e.loads.arm_wrench0_r0.moment_Nm + e.vehicle_w0.moment_Nm};
  Wrench applied{e.thrust.force_N + in.disturbance_force_N, e.thrust.moment_Nm + in.disturbance_moment_Nm};
  e.bias = bias;
  e.accel = SolveBaseAcceleration(M, bias, applied);
  ComputeJointWrenches(model_, e.base, e.kin, e.loads, e.accel, e.joints);
}

void Plant::Derivatives(double t, const double *y, const PlantInputs &in, double *yd) const {
  Eval &e = *scratch_;  // reused: no allocation per right-hand-side evaluation
  Evaluate(t, y, in, e);
  const int n = n_, nt = nt_;
  for (int k = 0; k < 3; ++k) {
    yd[kR + k] = y[kV + k];
    yd[kV + k] = e.accel[k];
    yd[kW + k] = e.accel[3 + k];
  }
  // q̇ = ½·(0, ω)⊗q for an inertial angular velocity ω and q mapping vehicle → inertial.
  const double w = y[kQ], x = y[kQ + 1], yy = y[kQ + 2], z = y[kQ + 3];
  const double ox = y[kW], oy = y[kW + 1], oz = y[kW + 2];
  yd[kQ] = 0.5 * (-ox * x - oy * yy - oz * z);
  yd[kQ + 1] = 0.5 * (ox * w + oy * z - oz * yy);
  yd[kQ + 2] = 0.5 * (oy * w + oz * x - ox * z);
  yd[kQ + 3] = 0.5 * (oz * w + ox * yy - oy * x);
  for (int j = 0; j < n; ++j) {
    yd[kJ + j] = y[kJ + n + j];
    yd[kJ + n + j] = in.joint_accel_rad_s2[size_t(j)];
  }
  const double *wm = y + kJ + 2 * n, *im = y + kJ + 2 * n + nt;
  double draw = 0.0, signed_p = 0.0;
  for (int j = 0; j < nt; ++j) {
    const double V = in.motor_voltage_V[size_t(j)];
    const MotorDerivatives d = MotorRhs(params_.propulsion, V, im[j], wm[j], e.torque_Nm[size_t(j)]);
    yd[kJ + 2 * n + j] = d.omega_dot_rad_s2;
    yd[kJ + 2 * n + nt + j] = d.current_dot_A_s;
    draw += std::max(V * im[j], 0.0);  // battery draw, no regeneration credited (SPEC §5)
    signed_p += V * im[j];
  }
  const size_t ke = size_t(kJ + 2 * n + 2 * nt);
  double manip = 0.0;
  for (int i = 1; i <= n; ++i) manip += std::abs(e.joints.tau_Nm[size_t(i)] * y[kJ + n + i - 1]);
  yd[ke] = draw;
  yd[ke + 1] = signed_p;
  yd[ke + 2] = manip;
  for (int i = 1; i <= n; ++i)  // distance through the water of each aerodynamic center
    yd[ke + 3 + size_t(i - 1)] = (e.kin.v_mid_m_s[size_t(i)] - e.fluid.flow_m_s).norm();
}

StepStatus Plant::Step(const PlantInputs &in, double dt_s) {
  StepStatus st;
  if (in.motor_voltage_V.size() != size_t(nt_) || in.joint_accel_rad_s2.size() != size_t(n_)) {
    st.code = StepStatus::Code::kBadInput;
    st.message = "plant: inputs need " + std::to_string(nt_) + " voltages and " + std::to_string(n_) +
                 " joint accelerations";
    return st;
  }
  bool finite = std::isfinite(dt_s) && dt_s > 0.0 && in.disturbance_force_N.allFinite() &&
                in.disturbance_moment_Nm.allFinite();
  for (double v : in.motor_voltage_V) finite = finite && std::isfinite(v);
  for (double a : in.joint_accel_rad_s2) finite = finite && std::isfinite(a);
  if (!finite) {
    st.code = StepStatus::Code::kBadInput;
    st.message = "plant: non-finite input or tick length";
    return st;
  }
  held_ = in;
  // Normalise the quaternion at the tick boundary; CVODE restarts cleanly (inputs jumped).
  Eigen::Map<Eigen::Vector4d> qv(y_.data() + kQ);
  qv.normalize();
  integ_->Reset(t_, y_.data());
  const Integrator::Result r = integ_->AdvanceTo(t_ + dt_s, y_.data());
  if (!r.ok) {
    st.code = StepStatus::Code::kIntegratorFailure;
    st.message = "plant: CVODE failed at t = " + std::to_string(r.t_reached) + " s: " + r.flag_name + " " + r.message;
    return st;
  }
  t_ += dt_s;
  FillTruth(in);
  if (truth_.contact_breach) {
    st.code = StepStatus::Code::kContact;
    st.message = "plant: contact: " + truth_.closest_a + " and " + truth_.closest_b + " at distance " +
                 std::to_string(truth_.min_clearance_m) + " m (clearance " +
                 std::to_string(params_.contact.clearance_m) + " m)";
  }
  return st;
}

void Plant::FillTruth(const PlantInputs &in) {
  Eval e;
  Evaluate(t_, y_.data(), in, e);
  const int n = n_, nt = nt_;
  Truth &T = truth_;
  T.time_s = t_;
  T.r0_m = e.base.r0_m;
  T.attitude = Eigen::Quaterniond(y_[kQ], y_[kQ + 1], y_[kQ + 2], y_[kQ + 3]).normalized();
  T.v0_m_s = e.base.v0_m_s;
  T.w0_rad_s = e.base.w0_rad_s;
  T.accel_m_s2 = e.accel.head<3>();
  T.alpha_rad_s2 = e.accel.tail<3>();
  T.q_rad.assign(y_.begin() + kJ, y_.begin() + kJ + n);
  T.qd_rad_s.assign(y_.begin() + kJ + n, y_.begin() + kJ + 2 * n);
  T.motor_speed_rad_s.assign(y_.begin() + kJ + 2 * n, y_.begin() + kJ + 2 * n + nt);
  T.motor_current_A.assign(y_.begin() + kJ + 2 * n + nt, y_.begin() + kJ + 2 * n + 2 * nt);
  T.thrust_N = e.thrust_N;
  T.thrust_force_N = e.thrust.force_N;
  T.thrust_moment_Nm = e.thrust.moment_Nm;
  T.ee_m = e.kin.ee_m;
  T.barycenter_m = e.kin.barycenter_m;
  Vec3 mv = model_.vehicle.mass_kg * e.base.v0_m_s + model_.payload_kg * e.kin.v_payload_m_s;
  for (int i = 1; i <= n; ++i) mv += model_.link[size_t(i - 1)].mass_kg * e.kin.v_com_m_s[size_t(i)];
  T.barycenter_v_m_s = mv / model_.total_mass_kg;
  T.flow_m_s = e.fluid.flow_m_s;
  T.joint_torque_Nm.assign(e.joints.tau_Nm.begin() + 1, e.joints.tau_Nm.end());
  const size_t ke = size_t(kJ + 2 * n + 2 * nt);
  T.thruster_energy_J = y_[ke];
  T.thruster_energy_signed_J = y_[ke + 1];
  T.manipulator_energy_J = y_[ke + 2];
  if (params_.contact.enabled) {
    std::vector<Body> bodies;
    Box hull;
    hull.center_m = e.base.r0_m + e.base.R0 * model_.vehicle.hull_center_m;
    hull.R = e.base.R0;
    hull.half_extent_m = 0.5 * model_.vehicle.hull_size_m;
    bodies.push_back(Body{"hull", hull, -1});
    for (int i = 1; i <= n; ++i) {
      Capsule c;
      c.a = e.kin.p_m[size_t(i - 1)];
      c.b = e.kin.p_m[size_t(i)];
      c.radius_m = 0.5 * model_.link[size_t(i - 1)].diameter_m;
      bodies.push_back(Body{"link" + std::to_string(i), c, params_.contact.self_collision ? -1 : 1});
    }
    for (const CylinderObstacle &o : params_.contact.obstacles) {
      Cylinder cyl;
      cyl.base_center_m = o.base_center_m;
      cyl.axis = Vec3::UnitZ();
      cyl.height_m = o.height_m;
      cyl.radius_m = o.radius_m;
      bodies.push_back(Body{o.name, cyl, 0});  // scene bodies share a group
    }
    const ContactMonitor::Report rep = contact_.Check(bodies);
    T.min_clearance_m = rep.min_distance_m;
    T.closest_a = rep.body_a;
    T.closest_b = rep.body_b;
    T.contact_breach = rep.breach;
  } else {
    T.contact_breach = false;
    T.min_clearance_m = std::numeric_limits<double>::infinity();
  }
}

}  // namespace uvms::plant
