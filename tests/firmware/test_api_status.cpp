// SPDX-License-Identifier: Apache-2.0
// Safety of the public API (issue 17 item 6): every status a public function documents with an
// @retval line (firmware/include/uvms/*.h) is reached here by an input built to trigger it, and
// the output the function writes on that path is the documented one (exact values: zeroed
// records, the hold, the safe actuator command, flags).
//
// One TEST_CASE per (function, status) pair, named "<function> returns <STATUS>" (optionally
// ": <which trigger>"). check_api_retval.py (ctest firmware.api_status_retval_coverage) fails
// when a documented pair has no case here or a case names an undocumented pair.
//
// Expected outputs are those the doc comments state (the safe outputs are exact: 0, the hold,
// the untouched record); expected results of the OK paths are derived from the documented
// formula or physics, never copied from a run.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>

#include "fw_test_util.hpp"
#include "uvms/alloc_power.h"
#include "uvms/allocation.h"
#include "uvms/arm_model.h"
#include "uvms/controller.h"
#include "uvms/dynamics.h"
#include "uvms/feedback.h"
#include "uvms/feedforward.h"
#include "uvms/kinematics.h"
#include "uvms/linalg.h"
#include "uvms/thruster.h"
#include "uvms/trajectory.h"
#include "uvms/types.h"

// Defensive branches no input is known to reach (check_api_retval.py lists them on every run):
// API-STATUS-UNTESTABLE: uvms_sym_eig UVMS_ERR_SINGULAR: cyclic Jacobi converges quadratically;
//   a finite input whose ‖A‖_F² is finite never needs UVMS_SYM_EIG_MAX_SWEEPS = 16 sweeps, and
//   the function takes no iteration count that a test could lower.

namespace {

using R = uvms_real_t;
const R kNaN = std::numeric_limits<R>::quiet_NaN();
const R kInf = std::numeric_limits<R>::infinity();
const R kMax = std::numeric_limits<R>::max();
// A value no function computes: an output still holding it was not written.
const R kJunk = R(123.25);
// Relative tolerance of a short operation chain in the real type.
const double kTol = fwtest::kFloat ? 2e-5 : 1e-11;
// Absolute tolerance of positions of order metres computed along two FK chains [m].
const double kPosTol = fwtest::kFloat ? 1e-4 : 1e-10;

void Fill(R *a, size_t n, R v) {
  for (size_t i = 0; i < n; ++i) a[i] = v;
}
bool AllEq(const R *a, size_t n, R v) {
  for (size_t i = 0; i < n; ++i)
    if (!(a[i] == v)) return false;
  return true;
}
bool AllFinite(const R *a, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(double(a[i]))) return false;
  return true;
}
// A record whose every byte is zero (what memset/uvms_clear_record leave).
bool ZeroBytes(const void *p, size_t n) {
  const unsigned char *b = static_cast<const unsigned char *>(p);
  for (size_t i = 0; i < n; ++i)
    if (b[i] != 0u) return false;
  return true;
}
template <class T>
void Junk(T *x) {
  std::memset(x, 0xAB, sizeof *x);
}
template <class T>
bool SameBytes(const T &a, const T &b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// An output array of N reals, every entry kJunk until the function writes it. It passes as
// an R* (and indexes like the array it holds).
template <size_t N>
struct JunkReals {
  R v[N];
  JunkReals() { Fill(v, N, kJunk); }
  operator R *() { return v; }
  operator const R *() const { return v; }
};
// An output record of type T, every byte 0xAB (Junk) until the function writes it. It passes
// as a T* and has exactly T's bytes, so ZeroBytes(&x, sizeof x) checks the record itself.
template <class T>
struct Junked : T {
  Junked() {
    static_assert(sizeof(Junked) == sizeof(T), "no bytes beyond the record");
    Junk(static_cast<T *>(this));
  }
};

// R0 = I (what uvms_m3_identity writes).
const R kI3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
const R kQ1[4] = {1, 0, 0, 0};  // identity quaternion (w, x, y, z)

uvms_arm_params_t PaperParams() {
  uvms_arm_params_t p;
  uvms_arm_params_paper(&p);
  return p;
}
// A model that is not ready (what a failed or missing init leaves).
uvms_arm_model_t UnreadyModel() {
  uvms_arm_model_t m;
  std::memset(&m, 0, sizeof m);
  return m;
}
// Σ m_i + payload: the mass the vehicle carries on link 1 [kg].
double ArmMass(const uvms_arm_params_t &p) {
  double m = double(p.payload_kg);
  for (size_t i = 0; i < p.num_joints; ++i) m += double(p.link[i].mass_kg);
  return m;
}
uvms_base_state_t RestBase() {
  uvms_base_state_t b;
  std::memset(&b, 0, sizeof b);
  uvms_m3_identity(b.R0);
  return b;
}
uvms_fluid_t GravityOnly() {
  uvms_fluid_t f;
  std::memset(&f, 0, sizeof f);
  f.gravity_m_s2[2] = R(-9.81);
  return f;
}
const R kZero7[UVMS_MAX_JOINTS] = {0, 0, 0, 0, 0, 0, 0};
// A zero 3-vector (still water, no rotation).
const R kZero3[3] = {0, 0, 0};

// The arguments of the kinematics and dynamics functions: the paper model (or a model that is
// not ready), data filled with junk, the vehicle at rest at the origin (R0 = I), gravity only.
enum ModelState { kReadyModel, kUnreadyModel };
struct ArmCall {
  fwtest::OwnedModel m{PaperParams()};
  Junked<uvms_arm_data_t> d;
  const uvms_base_state_t b = RestBase();
  const uvms_fluid_t fl = GravityOnly();
  explicit ArmCall(ModelState s = kReadyModel) {
    if (s == kUnreadyModel) static_cast<uvms_arm_model_t &>(m) = UnreadyModel();
  }
};

uvms_thruster_geometry_t PaperGeometry() {
  uvms_thruster_geometry_t g;
  uvms_thruster_geometry_paper(&g);
  return g;
}
uvms_alloc_t PaperAlloc() {
  const uvms_thruster_geometry_t g = PaperGeometry();
  uvms_alloc_t a;
  REQUIRE(uvms_alloc_init(&a, &g) == UVMS_OK);
  return a;
}
uvms_alloc_t ZeroAlloc() {
  uvms_alloc_t a;
  std::memset(&a, 0, sizeof a);
  return a;
}
// The refused state of uvms_alloc_init (allocation.h).
void CheckRefused(const uvms_alloc_t &a, uvms_status_t st) {
  CHECK(a.initialised == 0);
  CHECK(a.ready == 0);
  CHECK(a.usable_mask == 0u);
  CHECK(a.rank == 0u);
  CHECK(a.pinv_status == st);
  CHECK(a.uncontrollable_axes == UVMS_AXIS_ALL);
  CHECK(AllEq(a.H_pinv, UVMS_MAX_THRUSTERS * UVMS_ALLOC_WRENCH_DIM, 0));
  CHECK(ZeroBytes(&a.geom, sizeof a.geom));
}
// An initialised instance whose H⁺ could not be computed: a NaN written into the geometry
// after init (a corrupted instance), then a new usable set.
uvms_alloc_t SingularAlloc() {
  uvms_alloc_t a = PaperAlloc();
  a.geom.position_m[0][0] = kNaN;
  REQUIRE(uvms_alloc_set_usable(&a, 0x7Fu) == UVMS_ERR_SINGULAR);
  return a;
}
// 1 N on thruster 1 alone.
const R kThrust1[8] = {1, 0, 0, 0, 0, 0, 0, 0};

// The arguments of uvms_alloc_step: R0 = I, the wrench (F; N) = (1, 2, 3; 0, 0, 0) and the
// three thrust outputs P, P_pos, P_att filled with junk.
struct AllocStepCall {
  R F[3] = {1, 2, 3};
  const R N[3] = {0, 0, 0};
  JunkReals<8> P, Pp, Pa;
  // The error output: P = P_pos = P_att = 0.
  void CheckZeroed() const {
    CHECK(AllEq(P, 8, 0));
    CHECK(AllEq(Pp, 8, 0));
    CHECK(AllEq(Pa, 8, 0));
  }
};

// The arguments of uvms_alloc_saturate: P_pos and P_att every entry `input`, the output P and
// both scales s_pos, s_att filled with junk.
struct SaturateCall {
  R Pp[8], Pa[8];
  JunkReals<8> P;
  R sp = kJunk, sa = kJunk;
  explicit SaturateCall(R input = kJunk) {
    Fill(Pp, 8, input);
    Fill(Pa, 8, input);
  }
  // The error output, but for s_pos: P_pos = P_att = P = 0, s_att = 0.
  void CheckZeroed() const {
    CHECK(AllEq(Pp, 8, 0));
    CHECK(AllEq(Pa, 8, 0));
    CHECK(AllEq(P, 8, 0));
    CHECK(sa == R(0));
  }
};

uvms_thruster_params_t PaperThruster() {
  uvms_thruster_params_t p;
  uvms_thruster_params_paper(&p);
  return p;
}
uvms_motor_t ReadyMotor() {
  uvms_motor_t m;
  static const uvms_thruster_params_t p = PaperThruster();  // outlives the instance (not copied)
  REQUIRE(uvms_motor_init(&m, &p, R(1025.0), R(0.03)) == UVMS_OK);
  return m;
}

// θI of SPEC §8's table [rad].
void StartPose(R q[UVMS_MAX_JOINTS]) {
  const R *deg = uvms_joint_table_deg(UVMS_JOINT_TABLE_START);
  for (int j = 0; j < UVMS_MAX_JOINTS; ++j) q[j] = deg[j] * (UVMS_PI / R(180.0));
}

// The arguments of the calls on a Cartesian line: model, workspace, the line, the measured
// joints q0, and every output filled with junk (q, qd, qdd of uvms_cart_traj_step; qd, r of
// uvms_cart_traj_rate). `before` is the line as the constructor left it (bytes, padding
// included).
struct CartCall {
  uvms_arm_params_t arm_params{};  // what model points to
  uvms_arm_model_t model{};
  uvms_arm_data_t work{};
  uvms_cart_traj_t traj{};
  uvms_cart_traj_t before{};
  R q0[UVMS_MAX_JOINTS] = {};
  JunkReals<UVMS_MAX_JOINTS> q, qd, qdd;
  JunkReals<3> r;
  void Remember() { std::memcpy(&before, &traj, sizeof before); }
  // uvms_cart_traj_rate(traj, model, work, t_s, q_rad, → qd, r).
  uvms_status_t Rate(R t_s, const R *q_rad) {
    return uvms_cart_traj_rate(&traj, &model, &work, t_s, q_rad, qd, r);
  }
  // uvms_cart_traj_step(traj, model, work, t_s, dt_s, → q, qd, qdd).
  uvms_status_t Step(R t_s, R dt_s) {
    return uvms_cart_traj_step(&traj, &model, &work, t_s, dt_s, q, qd, qdd);
  }
  // The error output of uvms_cart_traj_rate: q̇ = 0 (UVMS_MAX_JOINTS), r̂ = 0.
  void CheckRateZero() const {
    CHECK(AllEq(qd, UVMS_MAX_JOINTS, 0));
    CHECK(AllEq(r, 3, 0));
  }
  // The hold of uvms_cart_traj_step: θ_ref = the stored reference, θ̇_ref = θ̈_ref = 0, state
  // unchanged.
  void CheckHold() const {
    CHECK(SameBytes(before, traj));
    for (size_t j = 0; j < before.n; ++j) CHECK(q[j] == before.q_ref_rad[j]);
    CHECK(AllEq(qd, UVMS_MAX_JOINTS, 0));
    CHECK(AllEq(qdd, UVMS_MAX_JOINTS, 0));
  }
};
// A Cartesian line started at θI on the paper model (defaults, vehicle reference); not
// started, the line is junk until a call writes it.
enum LineState { kStarted, kNotStarted };
struct CartFixture : CartCall {
  R r0d[3] = {0, 0, 0};
  R R0d[9] = {};
  uvms_cart_traj_params_t params{};
  explicit CartFixture(LineState s = kStarted) {
    arm_params = PaperParams();
    REQUIRE(uvms_arm_model_init(&arm_params, &model) == UVMS_OK);
    StartPose(q0);
    uvms_m3_identity(R0d);
    uvms_cart_traj_params_default(&params);
    if (s == kStarted)
      REQUIRE(Init() == UVMS_OK);
    else
      Junk(&traj);
    Remember();
  }
  // uvms_cart_traj_init(→ traj, params, model, work, q0, r0d, R0d).
  uvms_status_t Init() {
    return uvms_cart_traj_init(&traj, &params, &model, &work, q0, r0d, R0d);
  }
};
// One revolute joint with a 0.5 m link (DH a): its linear Jacobian has rank 1, so with a
// damping λ = 1e-8 m, J·Jᵀ + λ²I has pivots λ² = 1e-16 against a largest diagonal 0.25 m²,
// below the Cholesky's relative pivot tolerance in both real types (float 1e-6, double 1e-12).
struct SingularCartFixture : CartCall {
  SingularCartFixture() {
    arm_params = PaperParams();
    arm_params.num_joints = 1;
    arm_params.link[0].a_m = R(0.5);
    arm_params.link[0].d_m = R(0.0);
    REQUIRE(uvms_arm_model_init(&arm_params, &model) == UVMS_OK);
    uvms_cart_traj_params_t prm;
    uvms_cart_traj_params_default(&prm);
    prm.damping_m = R(1e-8);
    const R r0d[3] = {0, 0, 0};
    REQUIRE(uvms_cart_traj_init(&traj, &prm, &model, &work, q0, r0d, kI3) == UVMS_OK);
    Remember();
  }
};

uvms_ctrl_config_t PaperConfig(int case_number = 4) {
  uvms_ctrl_config_t c;
  REQUIRE(uvms_ctrl_config_paper(&c, case_number) == UVMS_OK);
  return c;
}
// The first record of a run at rest in the start pose (tick 0, t = 0).
uvms_ctrl_sensors_t RestSensors(const uvms_ctrl_config_t &cfg) {
  uvms_ctrl_sensors_t s;
  std::memset(&s, 0, sizeof s);
  s.quaternion_wxyz[0] = 1;
  for (int j = 0; j < UVMS_MAX_JOINTS; ++j) s.joint_position_rad[j] = cfg.theta_start_rad[j];
  s.thruster_usable_mask = 0xFFu;
  return s;
}
// The refused instance of uvms_ctrl_init: all zero except config_error.
void CheckRefusedCtrl(const uvms_ctrl_t &ctrl, uvms_cfg_field_t field) {
  CHECK(ctrl.config_error == field);
  uvms_ctrl_t copy = ctrl;
  copy.config_error = UVMS_CFG_OK;
  CHECK(ZeroBytes(&copy, sizeof copy));
}
// The arguments of uvms_ctrl_step: a controller initialised with case IV's configuration c
// (or, not initialised, all zero), the first record s at rest, and both outputs filled with
// junk.
enum CtrlState { kInitialised, kNotInitialised };
struct CtrlStepCall {
  const uvms_ctrl_config_t c = PaperConfig();
  uvms_ctrl_t ctrl;
  uvms_ctrl_sensors_t s = RestSensors(c);
  Junked<uvms_ctrl_command_t> cmd;
  Junked<uvms_ctrl_telemetry_t> t;
  explicit CtrlStepCall(CtrlState st = kInitialised) {
    if (st == kInitialised)
      REQUIRE(uvms_ctrl_init(&ctrl, &c) == UVMS_OK);
    else
      std::memset(&ctrl, 0, sizeof ctrl);
  }
};
// The safe output of uvms_ctrl_step (controller.h): every motor voltage, current command and
// rate 0, θ̈_cmd = θ̇_ref = θ̈_ref = 0, θ_ref = q_ref_expected.
void CheckSafeCommand(const uvms_ctrl_command_t &c, const R *q_ref_expected) {
  CHECK(AllEq(c.motor_voltage_V, UVMS_MAX_THRUSTERS, 0));
  CHECK(AllEq(c.motor_current_cmd_A, UVMS_MAX_THRUSTERS, 0));
  CHECK(AllEq(c.motor_current_rate_A_s, UVMS_MAX_THRUSTERS, 0));
  CHECK(AllEq(c.joint_acceleration_rad_s2, UVMS_MAX_JOINTS, 0));
  CHECK(AllEq(c.joint_ref_rate_rad_s, UVMS_MAX_JOINTS, 0));
  CHECK(AllEq(c.joint_ref_accel_rad_s2, UVMS_MAX_JOINTS, 0));
  for (int j = 0; j < UVMS_MAX_JOINTS; ++j) CHECK(c.joint_ref_rad[j] == q_ref_expected[j]);
}
// Every real of the telemetry record is finite (controller.h).
bool TelemetryFinite(const uvms_ctrl_telemetry_t &t) {
  const R *first = &t.force_ff_N[0];
  const R *last = &t.thrust_scale_att;
  return AllFinite(first, size_t(last - first) + 1u) && std::isfinite(double(t.time_s));
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// linalg.h

TEST_CASE("uvms_quat_to_rot returns UVMS_OK", "[api_status]") {
  // q = 2·(1, 0, 0, 1): a quarter turn about z with |q| = 2√2 (normalised first).
  const R q[4] = {2, 0, 0, 2};
  JunkReals<9> Rm;
  REQUIRE(uvms_quat_to_rot(q, Rm) == UVMS_OK);
  const R expected[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
  for (int i = 0; i < 9; ++i) CHECK(double(Rm[i]) == Approx(double(expected[i])).margin(kTol));
}

TEST_CASE("uvms_quat_to_rot returns UVMS_ERR_NONFINITE", "[api_status]") {
  const R q[4] = {kNaN, 0, 0, 0};
  JunkReals<9> Rm;
  REQUIRE(uvms_quat_to_rot(q, Rm) == UVMS_ERR_NONFINITE);
  for (int i = 0; i < 9; ++i) CHECK(Rm[i] == kI3[i]);
}

TEST_CASE("uvms_quat_to_rot returns UVMS_ERR_RANGE", "[api_status]") {
  const R q[4] = {0, R(1e-7), 0, 0};  // |q| = 1e-7 < 1e-6
  JunkReals<9> Rm;
  REQUIRE(uvms_quat_to_rot(q, Rm) == UVMS_ERR_RANGE);
  for (int i = 0; i < 9; ++i) CHECK(Rm[i] == kI3[i]);
}

TEST_CASE("uvms_spd_solve returns UVMS_OK", "[api_status]") {
  const R A[4] = {4, 0, 0, 9}, B[2] = {8, 27};  // X = (8/4, 27/9)
  R X[2] = {kJunk, kJunk};
  REQUIRE(uvms_spd_solve(2, A, 1, B, X, R(1e-12)) == UVMS_OK);
  CHECK(double(X[0]) == Approx(2.0).epsilon(kTol));
  CHECK(double(X[1]) == Approx(3.0).epsilon(kTol));
}

TEST_CASE("uvms_spd_solve returns UVMS_ERR_ARG", "[api_status]") {
  const R B[2] = {8, 27};
  R X[2] = {kJunk, kJunk};
  REQUIRE(uvms_spd_solve(2, nullptr, 1, B, X, R(1e-12)) == UVMS_ERR_ARG);
  CHECK(AllEq(X, 2, 0));
}

TEST_CASE("uvms_spd_solve returns UVMS_ERR_SINGULAR", "[api_status]") {
  const R A[4] = {1, 1, 1, 1}, B[2] = {1, 1};  // rank 1
  R X[2] = {kJunk, kJunk};
  REQUIRE(uvms_spd_solve(2, A, 1, B, X, R(1e-6)) == UVMS_ERR_SINGULAR);
  CHECK(AllEq(X, 2, 0));
}

// The outputs of uvms_sym_eig for n = 2, filled with junk.
struct EigOut {
  JunkReals<2> ev;
  JunkReals<4> V;
  uint32_t sweeps = 99u;
  // The error output: eigenvalues, eigenvectors and sweep count 0.
  void CheckZeroed() const {
    CHECK(AllEq(ev, 2, 0));
    CHECK(AllEq(V, 4, 0));
    CHECK(sweeps == 0u);
  }
};

TEST_CASE("uvms_sym_eig returns UVMS_OK", "[api_status]") {
  const R A[4] = {3, 0, 0, 1};  // diagonal: already converged, V = I
  EigOut o;
  REQUIRE(uvms_sym_eig(2, A, o.ev, o.V, &o.sweeps) == UVMS_OK);
  CHECK(o.ev[0] == R(3));
  CHECK(o.ev[1] == R(1));
  CHECK(o.V[0] == R(1));
  CHECK(o.V[1] == R(0));
  CHECK(o.V[2] == R(0));
  CHECK(o.V[3] == R(1));
  CHECK(o.sweeps == 0u);
}

TEST_CASE("uvms_sym_eig returns UVMS_ERR_ARG", "[api_status]") {
  EigOut o;
  REQUIRE(uvms_sym_eig(2, nullptr, o.ev, o.V, &o.sweeps) == UVMS_ERR_ARG);
  o.CheckZeroed();
}

TEST_CASE("uvms_sym_eig returns UVMS_ERR_NONFINITE", "[api_status]") {
  const R A[4] = {1, kNaN, kNaN, 1};
  EigOut o;
  REQUIRE(uvms_sym_eig(2, A, o.ev, o.V, &o.sweeps) == UVMS_ERR_NONFINITE);
  o.CheckZeroed();
}

// ---------------------------------------------------------------------------------------------
// arm_model.h

TEST_CASE("uvms_arm_model_init returns UVMS_OK", "[api_status]") {
  const uvms_arm_params_t p = PaperParams();
  Junked<uvms_arm_model_t> m;
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_OK);
  CHECK(m.ready == 1);
  // m_T = m0 + Σ m_i + m_{N+1} [5]
  CHECK(double(m.total_mass_kg) ==
        Approx(double(p.vehicle.mass_kg) + ArmMass(p)).epsilon(kTol));
}

TEST_CASE("uvms_arm_model_init returns UVMS_ERR_ARG", "[api_status]") {
  Junked<uvms_arm_model_t> m;
  REQUIRE(uvms_arm_model_init(nullptr, &m) == UVMS_ERR_ARG);
  CHECK(ZeroBytes(&m, sizeof m));
}

TEST_CASE("uvms_arm_model_init returns UVMS_ERR_SIZE", "[api_status]") {
  uvms_arm_params_t p = PaperParams();
  p.num_joints = UVMS_MAX_JOINTS + 1;
  Junked<uvms_arm_model_t> m;
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_ERR_SIZE);
  CHECK(ZeroBytes(&m, sizeof m));
}

TEST_CASE("uvms_arm_model_init returns UVMS_ERR_NONFINITE", "[api_status]") {
  uvms_arm_params_t p = PaperParams();
  p.link[2].mass_kg = kNaN;
  Junked<uvms_arm_model_t> m;
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_ERR_NONFINITE);
  CHECK(ZeroBytes(&m, sizeof m));
  p = PaperParams();
  p.link[3].inertia_products_kg_m2[2] = kNaN;
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_ERR_NONFINITE);
  CHECK(ZeroBytes(&m, sizeof m));
  p = PaperParams();
  p.vehicle.quadratic_damping[5] = kNaN;
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_ERR_NONFINITE);
  CHECK(ZeroBytes(&m, sizeof m));
}

TEST_CASE("uvms_arm_model_init returns UVMS_ERR_RANGE", "[api_status]") {
  uvms_arm_params_t p = PaperParams();
  p.vehicle.mass_kg = 0;
  Junked<uvms_arm_model_t> m;
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_ERR_RANGE);
  CHECK(ZeroBytes(&m, sizeof m));
  p = PaperParams();
  p.vehicle.linear_damping[3] = -1;  // damping must take energy out, never put it in
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_ERR_RANGE);
  CHECK(ZeroBytes(&m, sizeof m));
  p = PaperParams();  // link 1's I_xy² > I_xx·I_yy: no rigid body's tensor
  p.link[0].inertia_products_kg_m2[0] = uvms_real_t(0.2);
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_ERR_RANGE);
  CHECK(ZeroBytes(&m, sizeof m));
}

// ---------------------------------------------------------------------------------------------
// kinematics.h

TEST_CASE("uvms_arm_fk returns UVMS_OK", "[api_status]") {
  ArmCall f;
  const R r0[3] = {1, 2, 3};
  REQUIRE(uvms_arm_fk(&f.m, &f.d, r0, f.b.R0, kZero7) == UVMS_OK);
  // Base frame: R[0] = R0, origin r0 + R0·s0 (SPEC §2).
  for (int k = 0; k < 9; ++k) CHECK(f.d.R[0][k] == f.b.R0[k]);
  for (int k = 0; k < 3; ++k)
    CHECK(double(f.d.p_m[0][k]) ==
          Approx(double(r0[k] + f.m.p->vehicle.base_offset_m[k])).epsilon(kTol));
  CHECK(AllFinite(f.d.ee_m, 3));
}

TEST_CASE("uvms_arm_fk returns UVMS_ERR_ARG", "[api_status]") {
  ArmCall f;
  REQUIRE(uvms_arm_fk(&f.m, &f.d, f.b.position_m, f.b.R0, nullptr) == UVMS_ERR_ARG);
  CHECK(ZeroBytes(&f.d, sizeof f.d));
}

TEST_CASE("uvms_arm_fk returns UVMS_ERR_STATE", "[api_status]") {
  ArmCall f(kUnreadyModel);
  REQUIRE(uvms_arm_fk(&f.m, &f.d, f.b.position_m, f.b.R0, kZero7) == UVMS_ERR_STATE);
  CHECK(ZeroBytes(&f.d, sizeof f.d));
}

TEST_CASE("uvms_arm_jacobian returns UVMS_OK", "[api_status]") {
  ArmCall f;
  REQUIRE(uvms_arm_fk(&f.m, &f.d, f.b.position_m, f.b.R0, kZero7) == UVMS_OK);
  JunkReals<6 * UVMS_MAX_JOINTS> J;
  REQUIRE(uvms_arm_jacobian(&f.m, &f.d, J) == UVMS_OK);
  const size_t n = 7;
  // Column 1 = (z_1 × (p_EE − p_0*); z_1), z_1 = R0·e_z = e_z with R0 = I.
  CHECK(J[3 * n] == R(0));
  CHECK(J[4 * n] == R(0));
  CHECK(J[5 * n] == R(1));
  CHECK(J[2 * n] == R(0));  // e_z × d has no z component
  CHECK(AllFinite(J, 6 * n));
}

TEST_CASE("uvms_arm_jacobian returns UVMS_ERR_ARG", "[api_status]") {
  const auto m = fwtest::PaperModel();
  JunkReals<6 * UVMS_MAX_JOINTS> J;
  REQUIRE(uvms_arm_jacobian(&m, nullptr, J) == UVMS_ERR_ARG);
  CHECK(AllEq(J, 6 * UVMS_MAX_JOINTS, 0));
}

TEST_CASE("uvms_arm_jacobian returns UVMS_ERR_STATE", "[api_status]") {
  const uvms_arm_model_t m = UnreadyModel();
  uvms_arm_data_t d{};
  JunkReals<6 * UVMS_MAX_JOINTS> J;
  REQUIRE(uvms_arm_jacobian(&m, &d, J) == UVMS_ERR_STATE);
  CHECK(AllEq(J, 6 * UVMS_MAX_JOINTS, 0));
}

TEST_CASE("uvms_arm_barycenter_jacobian returns UVMS_OK", "[api_status]") {
  ArmCall f;
  REQUIRE(uvms_arm_fk(&f.m, &f.d, f.b.position_m, f.b.R0, kZero7) == UVMS_OK);
  JunkReals<3 * UVMS_MAX_JOINTS> Jcm;
  REQUIRE(uvms_arm_barycenter_jacobian(&f.m, &f.d, Jcm) == UVMS_OK);
  CHECK(AllFinite(Jcm, 3 * UVMS_MAX_JOINTS));
  CHECK(Jcm[2 * 7 + 0] == R(0));  // column 1 = e_z × (...)/m_T: no z component
}

TEST_CASE("uvms_arm_barycenter_jacobian returns UVMS_ERR_ARG", "[api_status]") {
  JunkReals<3 * UVMS_MAX_JOINTS> Jcm;
  uvms_arm_data_t d{};
  REQUIRE(uvms_arm_barycenter_jacobian(nullptr, &d, Jcm) == UVMS_ERR_ARG);
  CHECK(AllEq(Jcm, 3 * UVMS_MAX_JOINTS, 0));
}

TEST_CASE("uvms_arm_barycenter_jacobian returns UVMS_ERR_STATE", "[api_status]") {
  const uvms_arm_model_t m = UnreadyModel();
  uvms_arm_data_t d{};
  JunkReals<3 * UVMS_MAX_JOINTS> Jcm;
  REQUIRE(uvms_arm_barycenter_jacobian(&m, &d, Jcm) == UVMS_ERR_STATE);
  CHECK(AllEq(Jcm, 3 * UVMS_MAX_JOINTS, 0));
}

TEST_CASE("uvms_arm_ee_minus_barycenter returns UVMS_OK", "[api_status]") {
  // [4]: p_EE − p_cm does not depend on the vehicle position: compare with FK at another r0.
  ArmCall f;
  JunkReals<3> rel;
  REQUIRE(uvms_arm_ee_minus_barycenter(&f.m, &f.d, f.b.R0, kZero7, rel) == UVMS_OK);
  const R r0[3] = {5, -3, 2};
  REQUIRE(uvms_arm_fk(&f.m, &f.d, r0, f.b.R0, kZero7) == UVMS_OK);
  for (int k = 0; k < 3; ++k)
    CHECK(double(rel[k]) == Approx(double(f.d.ee_m[k] - f.d.barycenter_m[k])).margin(kPosTol));
}

TEST_CASE("uvms_arm_ee_minus_barycenter returns UVMS_ERR_ARG", "[api_status]") {
  ArmCall f;
  JunkReals<3> rel;
  REQUIRE(uvms_arm_ee_minus_barycenter(&f.m, &f.d, f.b.R0, nullptr, rel) == UVMS_ERR_ARG);
  CHECK(AllEq(rel, 3, 0));
  CHECK(ZeroBytes(&f.d, sizeof f.d));
}

TEST_CASE("uvms_arm_ee_minus_barycenter returns UVMS_ERR_STATE", "[api_status]") {
  ArmCall f(kUnreadyModel);
  JunkReals<3> rel;
  REQUIRE(uvms_arm_ee_minus_barycenter(&f.m, &f.d, f.b.R0, kZero7, rel) == UVMS_ERR_STATE);
  CHECK(AllEq(rel, 3, 0));
  CHECK(ZeroBytes(&f.d, sizeof f.d));
}

// ---------------------------------------------------------------------------------------------
// dynamics.h

TEST_CASE("uvms_arm_forward returns UVMS_OK", "[api_status]") {
  // At rest (v0 = ω0 = 0, θ̇ = θ̈ = 0) every rate and acceleration is exactly 0.
  ArmCall f;
  REQUIRE(uvms_arm_forward(&f.m, &f.d, &f.b, kZero7, kZero7, kZero7) == UVMS_OK);
  for (int i = 0; i <= 7; ++i) {
    CHECK(AllEq(f.d.omega_rad_s[i], 3, 0));
    CHECK(AllEq(f.d.ac_m_s2[i], 3, 0));
  }
  CHECK(AllEq(f.d.barycenter_v_m_s, 3, 0));
}

TEST_CASE("uvms_arm_forward returns UVMS_ERR_ARG", "[api_status]") {
  ArmCall f;
  REQUIRE(uvms_arm_forward(&f.m, &f.d, nullptr, kZero7, kZero7, kZero7) == UVMS_ERR_ARG);
  CHECK(ZeroBytes(&f.d, sizeof f.d));
}

TEST_CASE("uvms_arm_forward returns UVMS_ERR_STATE", "[api_status]") {
  ArmCall f(kUnreadyModel);
  REQUIRE(uvms_arm_forward(&f.m, &f.d, &f.b, kZero7, kZero7, kZero7) == UVMS_ERR_STATE);
  CHECK(ZeroBytes(&f.d, sizeof f.d));
}

// The backward-pass outputs of data (drag_N, f_N, n_Nm, tau_Nm) are all zero.
static bool BackwardFieldsZero(const uvms_arm_data_t &d) {
  return ZeroBytes(d.drag_N, sizeof d.drag_N) && ZeroBytes(d.f_N, sizeof d.f_N) &&
         ZeroBytes(d.n_Nm, sizeof d.n_Nm) && ZeroBytes(d.tau_Nm, sizeof d.tau_Nm);
}

TEST_CASE("uvms_arm_backward returns UVMS_OK", "[api_status]") {
  // Arm at rest in a fluid of density 0 under gravity: link 1 carries the weight of the arm
  // and payload, f_1 = −(Σ m_i + m_payload)·g [24].
  const uvms_arm_params_t p = PaperParams();
  ArmCall f;
  REQUIRE(uvms_arm_forward(&f.m, &f.d, &f.b, kZero7, kZero7, kZero7) == UVMS_OK);
  REQUIRE(uvms_arm_backward(&f.m, &f.d, &f.fl) == UVMS_OK);
  CHECK(double(f.d.f_N[1][2]) == Approx(ArmMass(p) * 9.81).epsilon(kTol));
  CHECK(double(f.d.f_N[1][0]) == Approx(0.0).margin(kTol));
  CHECK(AllEq(f.d.drag_N[0], 3, 0));  // at rest: no drag
}

TEST_CASE("uvms_arm_backward returns UVMS_ERR_ARG", "[api_status]") {
  // Documented: drag_N, f_N, n_Nm, tau_Nm zeroed (not the previous call's loads).
  ArmCall f;
  REQUIRE(uvms_arm_backward(&f.m, &f.d, nullptr) == UVMS_ERR_ARG);
  CHECK(BackwardFieldsZero(f.d));
}

TEST_CASE("uvms_arm_backward returns UVMS_ERR_STATE", "[api_status]") {
  // As above: the backward outputs zeroed.
  ArmCall f(kUnreadyModel);
  REQUIRE(uvms_arm_backward(&f.m, &f.d, &f.fl) == UVMS_ERR_STATE);
  CHECK(BackwardFieldsZero(f.d));
}

TEST_CASE("uvms_arm_rnea returns UVMS_OK", "[api_status]") {
  // = forward then backward: the same weight on link 1 as above, and τ_1 = n_1·z_1 = 0 for
  // the vertical joint 1 (gravity along its axis exerts no torque about it).
  const uvms_arm_params_t p = PaperParams();
  ArmCall f;
  REQUIRE(uvms_arm_rnea(&f.m, &f.d, &f.b, &f.fl, kZero7, kZero7, kZero7) == UVMS_OK);
  CHECK(double(f.d.f_N[1][2]) == Approx(ArmMass(p) * 9.81).epsilon(kTol));
  CHECK(double(f.d.tau_Nm[1]) == Approx(0.0).margin(kPosTol));
}

TEST_CASE("uvms_arm_rnea returns UVMS_ERR_ARG: joint rates NULL", "[api_status]") {
  ArmCall f;
  REQUIRE(uvms_arm_rnea(&f.m, &f.d, &f.b, &f.fl, kZero7, nullptr, kZero7) == UVMS_ERR_ARG);
  CHECK(ZeroBytes(&f.d, sizeof f.d));
}

TEST_CASE("uvms_arm_rnea returns UVMS_ERR_ARG: fluid NULL",
          "[api_status]") {
  // Documented: *data all zero (no forward-pass result or earlier load left in it).
  ArmCall f;
  REQUIRE(uvms_arm_rnea(&f.m, &f.d, &f.b, nullptr, kZero7, kZero7, kZero7) == UVMS_ERR_ARG);
  CHECK(ZeroBytes(&f.d, sizeof f.d));
}

TEST_CASE("uvms_arm_rnea returns UVMS_ERR_STATE", "[api_status]") {
  ArmCall f(kUnreadyModel);
  REQUIRE(uvms_arm_rnea(&f.m, &f.d, &f.b, &f.fl, kZero7, kZero7, kZero7) == UVMS_ERR_STATE);
  CHECK(ZeroBytes(&f.d, sizeof f.d));
}

// ---------------------------------------------------------------------------------------------
// feedback.h, feedforward.h

TEST_CASE("uvms_attitude_feedback returns UVMS_OK", "[api_status]") {
  // q0d = q0 (identity): φ·e = 0, so N_fb = −K_DN·ω0 [40] with K_DN = 100 N·m·s/rad.
  uvms_pd_gains_t g;
  uvms_pd_gains_paper(&g);
  const R w[3] = {1, 2, 3};
  JunkReals<3> n, phi;
  REQUIRE(uvms_attitude_feedback(&g, kQ1, kQ1, w, n, phi) == UVMS_OK);
  CHECK(AllEq(phi, 3, 0));
  CHECK(double(n[0]) == Approx(-100.0));
  CHECK(double(n[1]) == Approx(-200.0));
  CHECK(double(n[2]) == Approx(-300.0));
}

TEST_CASE("uvms_attitude_feedback returns UVMS_ERR_ARG", "[api_status]") {
  const R w[3] = {1, 2, 3};
  JunkReals<3> n, phi;
  REQUIRE(uvms_attitude_feedback(nullptr, kQ1, kQ1, w, n, phi) == UVMS_ERR_ARG);
  CHECK(AllEq(n, 3, 0));
  CHECK(AllEq(phi, 3, 0));
  uvms_pd_gains_t g;
  uvms_pd_gains_paper(&g);
  JunkReals<3> n2, phi2, n3, phi3;
  REQUIRE(uvms_attitude_feedback(&g, nullptr, kQ1, w, n2, phi2) == UVMS_ERR_ARG);
  CHECK(AllEq(n2, 3, 0));
  CHECK(AllEq(phi2, 3, 0));
  REQUIRE(uvms_attitude_feedback(&g, kQ1, nullptr, w, n3, phi3) == UVMS_ERR_ARG);
  CHECK(AllEq(n3, 3, 0));
  CHECK(AllEq(phi3, 3, 0));
}

TEST_CASE("uvms_position_feedback returns UVMS_OK", "[api_status]") {
  // F_fb = K_PF·(r_d − r) + K_DF·(v_d − v) [45], K_PF = 10 N/m, K_DF = 100 N·s/m.
  uvms_pd_gains_t g;
  uvms_pd_gains_paper(&g);
  const R rd[3] = {1, 0, 0}, r[3] = {0, 0, 0}, vd[3] = {0, 0, 0}, v[3] = {0, 0, 1};
  R f[3] = {kJunk, kJunk, kJunk};
  REQUIRE(uvms_position_feedback(&g, rd, r, vd, v, f) == UVMS_OK);
  CHECK(double(f[0]) == Approx(10.0));
  CHECK(double(f[1]) == Approx(0.0).margin(kTol));
  CHECK(double(f[2]) == Approx(-100.0));
}

TEST_CASE("uvms_position_feedback returns UVMS_ERR_ARG", "[api_status]") {
  uvms_pd_gains_t g;
  uvms_pd_gains_paper(&g);
  const R z[3] = {0, 0, 0};
  R f[3] = {kJunk, kJunk, kJunk};
  REQUIRE(uvms_position_feedback(&g, z, z, nullptr, z, f) == UVMS_ERR_ARG);
  CHECK(AllEq(f, 3, 0));
}

TEST_CASE("uvms_feedforward returns UVMS_OK", "[api_status]") {
  // At rest, density 0, gravity g: F_r,0 = f1 − m0·g [31] and F_r,cm = −Σ m_k·g [32] are both
  // the whole system's weight, +m_T·9.81 N along z (ballast 0).
  const uvms_arm_params_t p = PaperParams();
  ArmCall f;
  Junked<uvms_feedforward_t> ff;
  REQUIRE(uvms_feedforward(&f.m, &f.d, &f.fl, UVMS_REF_VEHICLE, &f.b, kZero7, kZero7, kZero7,
                           &ff) == UVMS_OK);
  const double mT = double(p.vehicle.mass_kg) + ArmMass(p);
  CHECK(double(ff.force_vehicle_N[2]) == Approx(mT * 9.81).epsilon(kTol));
  CHECK(double(ff.force_barycenter_N[2]) == Approx(mT * 9.81).epsilon(kTol));
  CHECK(AllEq(ff.base_accel_m_s2, 3, 0));
}

TEST_CASE("uvms_feedforward returns UVMS_ERR_ARG", "[api_status]") {
  ArmCall f;
  Junked<uvms_feedforward_t> ff;
  REQUIRE(uvms_feedforward(&f.m, &f.d, &f.fl, static_cast<uvms_reference_t>(7), &f.b, kZero7,
                           kZero7, kZero7, &ff) == UVMS_ERR_ARG);
  CHECK(ZeroBytes(&ff, sizeof ff));
}

TEST_CASE("uvms_feedforward returns UVMS_ERR_STATE", "[api_status]") {
  ArmCall f(kUnreadyModel);
  Junked<uvms_feedforward_t> ff;
  REQUIRE(uvms_feedforward(&f.m, &f.d, &f.fl, UVMS_REF_VEHICLE, &f.b, kZero7, kZero7, kZero7,
                           &ff) == UVMS_ERR_STATE);
  CHECK(ZeroBytes(&ff, sizeof ff));
  CHECK(ZeroBytes(&f.d, sizeof f.d));
}

TEST_CASE("uvms_ff_lead_check returns UVMS_OK", "[api_status]") {
  CHECK(uvms_ff_lead_check(0, UVMS_DRIVE_CURRENT) == UVMS_OK);
  CHECK(uvms_ff_lead_check(0, UVMS_DRIVE_VOLTAGE) == UVMS_OK);
  CHECK(uvms_ff_lead_check(1, UVMS_DRIVE_CURRENT) == UVMS_OK);
}

TEST_CASE("uvms_ff_lead_check returns UVMS_ERR_RANGE", "[api_status]") {
  CHECK(uvms_ff_lead_check(1, UVMS_DRIVE_VOLTAGE) == UVMS_ERR_RANGE);
  CHECK(uvms_ff_lead_check(2, UVMS_DRIVE_CURRENT) == UVMS_ERR_RANGE);
  CHECK(uvms_ff_lead_check(-1, UVMS_DRIVE_CURRENT) == UVMS_ERR_RANGE);
}

TEST_CASE("uvms_ff_lead returns UVMS_OK", "[api_status]") {
  const uvms_real_t w[2] = {1, 2}, prev[2] = {1, 1};
  uvms_real_t slope[2] = {99, 99}, out[2] = {7, 7};
  REQUIRE(uvms_ff_lead(2, w, prev, uvms_real_t(0.5), uvms_real_t(0.25), slope, 0, out) == UVMS_OK);
  CHECK((slope[0] == 0 && slope[1] == 2));  // no old value read: this step's slope
  CHECK((out[0] == 1 && out[1] == uvms_real_t(2.5)));
}

TEST_CASE("uvms_ff_lead returns UVMS_ERR_ARG", "[api_status]") {
  const uvms_real_t w[2] = {1, 2}, prev[2] = {1, 1};
  uvms_real_t slope[2] = {3, 4}, out[2] = {7, 7};
  CHECK(uvms_ff_lead(2, nullptr, prev, uvms_real_t(0.5), uvms_real_t(0.25), slope, 1, out) == UVMS_ERR_ARG);
  CHECK(uvms_ff_lead(2, w, nullptr, uvms_real_t(0.5), uvms_real_t(0.25), slope, 1, out) == UVMS_ERR_ARG);
  CHECK(uvms_ff_lead(2, w, prev, uvms_real_t(0.5), uvms_real_t(0.25), nullptr, 1, out) == UVMS_ERR_ARG);
  CHECK(uvms_ff_lead(2, w, prev, uvms_real_t(0.5), uvms_real_t(0.25), slope, 1, nullptr) == UVMS_ERR_ARG);
  CHECK((out[0] == 7 && out[1] == 7 && slope[0] == 3 && slope[1] == 4));  // writes nothing
}

TEST_CASE("uvms_ff_lead returns UVMS_ERR_RANGE", "[api_status]") {
  const uvms_real_t w[2] = {1, 2}, prev[2] = {1, 1};
  const uvms_real_t nan = std::numeric_limits<uvms_real_t>::quiet_NaN();
  for (const uvms_real_t bad_dt : {uvms_real_t(0), uvms_real_t(-0.1), nan,
                                   std::numeric_limits<uvms_real_t>::infinity()}) {
    uvms_real_t slope[2] = {3, 4}, out[2] = {7, 7};
    CHECK(uvms_ff_lead(2, w, prev, bad_dt, uvms_real_t(0.5), slope, 1, out) == UVMS_ERR_RANGE);
    CHECK((out[0] == w[0] && out[1] == w[1] && slope[0] == 3 && slope[1] == 4));
  }
  for (const uvms_real_t bad_lead : {uvms_real_t(-0.1), nan}) {
    uvms_real_t slope[2] = {3, 4}, out[2] = {7, 7};
    CHECK(uvms_ff_lead(2, w, prev, uvms_real_t(0.25), bad_lead, slope, 1, out) == UVMS_ERR_RANGE);
    CHECK((out[0] == w[0] && out[1] == w[1] && slope[0] == 3 && slope[1] == 4));
  }
}

// ---------------------------------------------------------------------------------------------
// allocation.h

TEST_CASE("uvms_alloc_init returns UVMS_OK", "[api_status]") {
  const uvms_thruster_geometry_t g = PaperGeometry();
  Junked<uvms_alloc_t> a;
  REQUIRE(uvms_alloc_init(&a, &g) == UVMS_OK);
  CHECK(a.initialised == 1);
  CHECK(a.ready == 1);
  CHECK(a.rank == 6u);
  CHECK(a.usable_mask == 0xFFu);
  CHECK(a.uncontrollable_axes == 0u);
}

TEST_CASE("uvms_alloc_init returns UVMS_ERR_ARG", "[api_status]") {
  Junked<uvms_alloc_t> a;
  REQUIRE(uvms_alloc_init(&a, nullptr) == UVMS_ERR_ARG);
  CheckRefused(a, UVMS_ERR_ARG);
}

TEST_CASE("uvms_alloc_init returns UVMS_ERR_SIZE", "[api_status]") {
  uvms_thruster_geometry_t g = PaperGeometry();
  g.num_thrusters = UVMS_MAX_THRUSTERS + 1;
  Junked<uvms_alloc_t> a;
  REQUIRE(uvms_alloc_init(&a, &g) == UVMS_ERR_SIZE);
  CheckRefused(a, UVMS_ERR_SIZE);
}

TEST_CASE("uvms_alloc_init returns UVMS_ERR_NONFINITE", "[api_status]") {
  uvms_thruster_geometry_t g = PaperGeometry();
  g.position_m[3][1] = kInf;
  Junked<uvms_alloc_t> a;
  REQUIRE(uvms_alloc_init(&a, &g) == UVMS_ERR_NONFINITE);
  CheckRefused(a, UVMS_ERR_NONFINITE);
}

TEST_CASE("uvms_alloc_init returns UVMS_ERR_RANGE", "[api_status]") {
  uvms_thruster_geometry_t g = PaperGeometry();
  Fill(g.direction[5], 3, 0);
  Junked<uvms_alloc_t> a;
  REQUIRE(uvms_alloc_init(&a, &g) == UVMS_ERR_RANGE);
  CheckRefused(a, UVMS_ERR_RANGE);
}

TEST_CASE("uvms_alloc_init returns UVMS_ERR_SINGULAR", "[api_status]") {
  // Every thruster pushes along x through the CoM: H has rank 1.
  uvms_thruster_geometry_t g = PaperGeometry();
  for (int j = 0; j < 8; ++j) {
    Fill(g.position_m[j], 3, 0);
    uvms_v3_set(g.direction[j], 1, 0, 0);
  }
  Junked<uvms_alloc_t> a;
  REQUIRE(uvms_alloc_init(&a, &g) == UVMS_ERR_SINGULAR);
  CheckRefused(a, UVMS_ERR_SINGULAR);
}

TEST_CASE("uvms_alloc_set_usable returns UVMS_OK", "[api_status]") {
  uvms_alloc_t a = PaperAlloc();
  REQUIRE(uvms_alloc_set_usable(&a, 0x7Fu) == UVMS_OK);
  CHECK(a.usable_mask == 0x7Fu);
  CHECK(a.ready == 1);
  CHECK(AllEq(&a.H_pinv[7 * UVMS_ALLOC_WRENCH_DIM], UVMS_ALLOC_WRENCH_DIM, 0));  // unusable
}

TEST_CASE("uvms_alloc_set_usable returns UVMS_ERR_ARG", "[api_status]") {
  REQUIRE(uvms_alloc_set_usable(nullptr, 0xFFu) == UVMS_ERR_ARG);  // nothing to write
}

TEST_CASE("uvms_alloc_set_usable returns UVMS_ERR_STATE", "[api_status]") {
  uvms_alloc_t a = ZeroAlloc();
  a.geom.num_thrusters = 8;
  uvms_alloc_t before;
  std::memcpy(&before, &a, sizeof before);  // bytes, padding included
  REQUIRE(uvms_alloc_set_usable(&a, 0x0Fu) == UVMS_ERR_STATE);
  CHECK(SameBytes(a, before));
}

TEST_CASE("uvms_alloc_set_usable returns UVMS_ERR_SINGULAR", "[api_status]") {
  uvms_alloc_t a = PaperAlloc();
  a.geom.position_m[0][0] = kNaN;  // corrupted after init
  REQUIRE(uvms_alloc_set_usable(&a, 0x7Fu) == UVMS_ERR_SINGULAR);
  CHECK(a.ready == 0);
  CHECK(a.rank == 0u);
  CHECK(a.uncontrollable_axes == UVMS_AXIS_ALL);
  CHECK(a.pinv_status == UVMS_ERR_SINGULAR);
  CHECK(AllEq(a.H_pinv, UVMS_MAX_THRUSTERS * UVMS_ALLOC_WRENCH_DIM, 0));
  CHECK(uvms_alloc_set_usable(&a, 0x7Fu) == UVMS_ERR_SINGULAR);  // stored status, same mask
}

TEST_CASE("uvms_alloc_step returns UVMS_OK", "[api_status]") {
  // A pure force: P_att = 0, P_pos = P, and the thrusts produce the wrench, H·P = (F; 0).
  const uvms_alloc_t a = PaperAlloc();
  AllocStepCall c;
  REQUIRE(uvms_alloc_step(&a, kI3, c.F, c.N, c.P, c.Pp, c.Pa) == UVMS_OK);
  CHECK(AllEq(c.Pa, 8, 0));
  for (int j = 0; j < 8; ++j) CHECK(c.P[j] == c.Pp[j]);
  R w[6];
  REQUIRE(uvms_alloc_wrench_body(&a, c.P, w) == UVMS_OK);
  for (int r = 0; r < 6; ++r)
    CHECK(double(w[r]) == Approx(r < 3 ? double(c.F[r]) : 0.0).margin(10 * kTol));
}

TEST_CASE("uvms_alloc_step returns UVMS_ERR_ARG", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  AllocStepCall c;
  REQUIRE(uvms_alloc_step(&a, nullptr, c.F, c.N, c.P, c.Pp, c.Pa) == UVMS_ERR_ARG);
  c.CheckZeroed();
}

TEST_CASE("uvms_alloc_step returns UVMS_ERR_STATE", "[api_status]") {
  const uvms_alloc_t a = ZeroAlloc();
  AllocStepCall c;
  REQUIRE(uvms_alloc_step(&a, kI3, c.F, c.N, c.P, c.Pp, c.Pa) == UVMS_ERR_STATE);
  c.CheckZeroed();
}

TEST_CASE("uvms_alloc_step returns UVMS_ERR_SINGULAR", "[api_status]") {
  const uvms_alloc_t a = SingularAlloc();
  AllocStepCall c;
  REQUIRE(uvms_alloc_step(&a, kI3, c.F, c.N, c.P, c.Pp, c.Pa) == UVMS_ERR_SINGULAR);
  c.CheckZeroed();
}

TEST_CASE("uvms_alloc_step returns UVMS_ERR_NONFINITE", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  AllocStepCall c;
  c.F[1] = kNaN;
  REQUIRE(uvms_alloc_step(&a, kI3, c.F, c.N, c.P, c.Pp, c.Pa) == UVMS_ERR_NONFINITE);
  c.CheckZeroed();
}

TEST_CASE("uvms_alloc_saturate returns UVMS_OK", "[api_status]") {
  // P_pos,0 = 3 N, P_att = 0, T = 1 N: s_pos = T/|P_pos,0| = 1/3, s_att = 1, P_0 = 1 N.
  const uvms_alloc_t a = PaperAlloc();
  SaturateCall s(R(0));
  s.Pp[0] = 3;
  REQUIRE(uvms_alloc_saturate(&a, R(1.0), s.Pp, s.Pa, s.P, &s.sp, &s.sa) == UVMS_OK);
  CHECK(double(s.sp) == Approx(1.0 / 3.0).epsilon(kTol));
  CHECK(s.sa == R(1));
  CHECK(double(s.P[0]) == Approx(1.0).epsilon(kTol));
  CHECK(AllEq(&s.P[1], 7, 0));
}

TEST_CASE("uvms_alloc_saturate returns UVMS_ERR_ARG", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  SaturateCall s;
  REQUIRE(uvms_alloc_saturate(&a, R(1.0), s.Pp, s.Pa, s.P, nullptr, &s.sa) == UVMS_ERR_ARG);
  s.CheckZeroed();
}

TEST_CASE("uvms_alloc_saturate returns UVMS_ERR_STATE", "[api_status]") {
  const uvms_alloc_t a = ZeroAlloc();
  SaturateCall s;
  REQUIRE(uvms_alloc_saturate(&a, R(1.0), s.Pp, s.Pa, s.P, &s.sp, &s.sa) == UVMS_ERR_STATE);
  s.CheckZeroed();
  CHECK(s.sp == R(0));
}

TEST_CASE("uvms_alloc_saturate returns UVMS_ERR_RANGE", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  SaturateCall s(R(1));
  REQUIRE(uvms_alloc_saturate(&a, R(0.0), s.Pp, s.Pa, s.P, &s.sp, &s.sa) == UVMS_ERR_RANGE);
  s.CheckZeroed();
  CHECK(s.sp == R(0));
}

TEST_CASE("uvms_alloc_saturate returns UVMS_ERR_NONFINITE", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  SaturateCall s(R(1));
  s.Pp[4] = kNaN;
  REQUIRE(uvms_alloc_saturate(&a, R(1.0), s.Pp, s.Pa, s.P, &s.sp, &s.sa) ==
          UVMS_ERR_NONFINITE);
  s.CheckZeroed();
  CHECK(s.sp == R(0));
}

// Per-thruster limits, none (+inf) on every thruster.
struct NoLimits {
  R N[8];
  NoLimits() { Fill(N, 8, kInf); }
};

// Per-thruster limits: 1 N on thruster 1, none (+inf) elsewhere.
static void OneLimited(R T[8]) {
  Fill(T, 8, kInf);
  T[0] = R(1.0);
}

TEST_CASE("uvms_alloc_saturate_each returns UVMS_OK", "[api_status]") {
  // P_pos,0 = 3 N, P_pos,1 = 5 N, P_att = 0, T_0 = 1 N, T_1 = +inf: s_pos = 1/3 (thruster 1's
  // bound), P_1 = 5/3 N.
  const uvms_alloc_t a = PaperAlloc();
  SaturateCall s(R(0));
  s.Pp[0] = 3;
  s.Pp[1] = 5;
  R T[8];
  OneLimited(T);
  REQUIRE(uvms_alloc_saturate_each(&a, T, s.Pp, s.Pa, s.P, &s.sp, &s.sa) == UVMS_OK);
  CHECK(double(s.sp) == Approx(1.0 / 3.0).epsilon(kTol));
  CHECK(s.sa == R(1));
  CHECK(double(s.P[0]) == Approx(1.0).epsilon(kTol));
  CHECK(double(s.P[1]) == Approx(5.0 / 3.0).epsilon(kTol));
}

TEST_CASE("uvms_alloc_saturate_each returns UVMS_ERR_ARG", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  SaturateCall s;
  REQUIRE(uvms_alloc_saturate_each(&a, nullptr, s.Pp, s.Pa, s.P, &s.sp, &s.sa) == UVMS_ERR_ARG);
  s.CheckZeroed();
  CHECK(s.sp == R(0));
}

TEST_CASE("uvms_alloc_saturate_each returns UVMS_ERR_STATE", "[api_status]") {
  const uvms_alloc_t a = ZeroAlloc();
  SaturateCall s;
  R T[8];
  OneLimited(T);
  REQUIRE(uvms_alloc_saturate_each(&a, T, s.Pp, s.Pa, s.P, &s.sp, &s.sa) == UVMS_ERR_STATE);
  s.CheckZeroed();
  CHECK(s.sp == R(0));
}

TEST_CASE("uvms_alloc_saturate_each returns UVMS_ERR_RANGE", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  SaturateCall s(R(1));
  R T[8];
  OneLimited(T);
  T[5] = R(0.0);
  REQUIRE(uvms_alloc_saturate_each(&a, T, s.Pp, s.Pa, s.P, &s.sp, &s.sa) == UVMS_ERR_RANGE);
  s.CheckZeroed();
  CHECK(s.sp == R(0));
}

TEST_CASE("uvms_alloc_saturate_each returns UVMS_ERR_NONFINITE", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  SaturateCall s(R(1));
  s.Pa[2] = kNaN;
  R T[8];
  OneLimited(T);
  REQUIRE(uvms_alloc_saturate_each(&a, T, s.Pp, s.Pa, s.P, &s.sp, &s.sa) == UVMS_ERR_NONFINITE);
  s.CheckZeroed();
  CHECK(s.sp == R(0));
}

// P of the paper layout for the wrench (F; N), unlimited.
static void PinvThrusts(const uvms_alloc_t &a, const R F[3], const R N[3], R P[8]) {
  REQUIRE(uvms_alloc_step(&a, kI3, F, N, P, nullptr, nullptr) == UVMS_OK);
}

// The outputs of uvms_alloc_min_power, filled with junk, and a warm start that must be cleared.
struct PowerOut {
  JunkReals<8> T;
  Junked<uvms_power_info_t> info;
  uvms_power_warm_t warm{{R(3.0), R(-2.0)}, 7u};
  void CheckZeroed() const {
    CHECK(AllEq(T, 8, 0));
    CHECK(warm.basis_id == 0u);
  }
  void CheckFallback(const R P[8]) const {
    for (int j = 0; j < 8; ++j) CHECK(T[j] == P[j]);
    CHECK(warm.basis_id == 0u);
  }
};

TEST_CASE("uvms_alloc_min_power returns UVMS_OK", "[api_status]") {
  // T delivers P's wrench with Σ|T|^1.5 ≤ Σ|P|^1.5 (alloc_power.h), and the warm start holds it.
  const uvms_alloc_t a = PaperAlloc();
  const R F[3] = {10, -4, 2}, N[3] = {1, 0, -3};
  R P[8];
  PinvThrusts(a, F, N, P);
  PowerOut o;
  REQUIRE(uvms_alloc_min_power(&a, kInf, P, &o.warm, o.T, &o.info) == UVMS_OK);
  R wP[6], wT[6];
  REQUIRE(uvms_alloc_wrench_body(&a, P, wP) == UVMS_OK);
  REQUIRE(uvms_alloc_wrench_body(&a, o.T, wT) == UVMS_OK);
  CHECK(double(o.info.cost) <= double(o.info.cost_pinv));
  CHECK(double(o.info.cost) == Approx(double(uvms_power_cost(8, o.T))).epsilon(kTol));
  CHECK(double(o.info.cost_pinv) == Approx(double(uvms_power_cost(8, P))).epsilon(kTol));
  CHECK(o.info.converged == 1);
  CHECK(o.info.null_dim == 2u);
  CHECK(o.warm.basis_id == a.pinv_computations);
  for (int r = 0; r < 6; ++r) CHECK(double(wT[r]) == Approx(double(wP[r])).margin(100 * kTol));
}

TEST_CASE("uvms_alloc_min_power returns UVMS_ERR_ARG", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  PowerOut o;
  REQUIRE(uvms_alloc_min_power(&a, kInf, nullptr, &o.warm, o.T, &o.info) == UVMS_ERR_ARG);
  o.CheckZeroed();
  CHECK(ZeroBytes(&o.info, sizeof o.info));
}

TEST_CASE("uvms_alloc_min_power returns UVMS_ERR_ARG: output is the input", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  PowerOut o;
  R P[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  REQUIRE(uvms_alloc_min_power(&a, kInf, P, &o.warm, P, &o.info) == UVMS_ERR_ARG);
  CHECK(AllEq(P, 8, 0));
  CHECK(o.warm.basis_id == 0u);
}

TEST_CASE("uvms_alloc_min_power returns UVMS_ERR_STATE", "[api_status]") {
  const uvms_alloc_t a = ZeroAlloc();
  PowerOut o;
  REQUIRE(uvms_alloc_min_power(&a, kInf, kThrust1, &o.warm, o.T, &o.info) == UVMS_ERR_STATE);
  o.CheckZeroed();
}

TEST_CASE("uvms_alloc_min_power returns UVMS_ERR_STATE: rank above 6", "[api_status]") {
  uvms_alloc_t a = PaperAlloc();
  a.rank = 7;  // corrupted: would leave 1 null direction of 8 thrusters that have 2
  PowerOut o;
  REQUIRE(uvms_alloc_min_power(&a, kInf, kThrust1, &o.warm, o.T, &o.info) == UVMS_ERR_STATE);
  o.CheckZeroed();
}

TEST_CASE("uvms_alloc_min_power returns UVMS_ERR_NONFINITE", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  const R P[8] = {1, 0, kNaN, 0, 0, 0, 0, 0};
  PowerOut o;
  REQUIRE(uvms_alloc_min_power(&a, kInf, P, &o.warm, o.T, &o.info) == UVMS_ERR_NONFINITE);
  o.CheckZeroed();
}

TEST_CASE("uvms_alloc_min_power returns UVMS_ERR_RANGE: limit not positive", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  PowerOut o;
  REQUIRE(uvms_alloc_min_power(&a, R(0.0), kThrust1, &o.warm, o.T, &o.info) == UVMS_ERR_RANGE);
  o.CheckZeroed();
}

TEST_CASE("uvms_alloc_min_power returns UVMS_ERR_RANGE: P above the limit", "[api_status]") {
  // P_0 = 100 N with T_max = 1 N: P is not the limited allocation the solver starts from.
  const uvms_alloc_t a = PaperAlloc();
  const R P[8] = {100, 0, 0, 0, 0, 0, 0, 0};
  PowerOut o;
  REQUIRE(uvms_alloc_min_power(&a, R(1.0), P, &o.warm, o.T, &o.info) == UVMS_ERR_RANGE);
  o.CheckZeroed();
}

TEST_CASE("uvms_alloc_min_power returns UVMS_ERR_SIZE", "[api_status]") {
  // A corrupted rank (4 with eight usable thrusters): four null directions, more than the
  // solver handles (unreachable from a valid instance: n ≤ 8 and rank 6 leave at most 2).
  uvms_alloc_t a = PaperAlloc();
  a.rank = 4;
  PowerOut o;
  REQUIRE(uvms_alloc_min_power(&a, kInf, kThrust1, &o.warm, o.T, &o.info) == UVMS_ERR_SIZE);
  o.CheckFallback(kThrust1);
}

TEST_CASE("uvms_alloc_min_power returns UVMS_ERR_SINGULAR", "[api_status]") {
  // A corrupted H⁺ (NaN): the null-space basis cannot be built; the fallback is P.
  uvms_alloc_t a = PaperAlloc();
  a.H_pinv[0] = kNaN;
  PowerOut o;
  REQUIRE(uvms_alloc_min_power(&a, kInf, kThrust1, &o.warm, o.T, &o.info) == UVMS_ERR_SINGULAR);
  o.CheckFallback(kThrust1);
}

TEST_CASE("uvms_alloc_min_power_each returns UVMS_OK", "[api_status]") {
  // Per-thruster limits (3 N on thrusters 1 and 2, 50 N elsewhere): T keeps each bound and
  // P's wrench, at a cost not above P's.
  const uvms_alloc_t a = PaperAlloc();
  const R F[3] = {4, -2, 1}, N[3] = {0.5, 0, -1};
  R P[8], T[8];
  PinvThrusts(a, F, N, P);
  Fill(T, 8, R(50.0));
  T[0] = T[1] = R(3.0);
  for (int j = 0; j < 8; ++j) REQUIRE(std::fabs(double(P[j])) <= double(T[j]));
  PowerOut o;
  REQUIRE(uvms_alloc_min_power_each(&a, T, nullptr, P, &o.warm, o.T, &o.info) == UVMS_OK);
  for (int j = 0; j < 8; ++j) CHECK(std::fabs(double(o.T[j])) <= double(T[j]));
  R wP[6], wT[6];
  REQUIRE(uvms_alloc_wrench_body(&a, P, wP) == UVMS_OK);
  REQUIRE(uvms_alloc_wrench_body(&a, o.T, wT) == UVMS_OK);
  for (int r = 0; r < 6; ++r) CHECK(double(wT[r]) == Approx(double(wP[r])).margin(100 * kTol));
  CHECK(double(o.info.cost) <= double(o.info.cost_pinv));
}

TEST_CASE("uvms_alloc_min_power_each returns UVMS_ERR_ARG", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  PowerOut o;
  REQUIRE(uvms_alloc_min_power_each(&a, nullptr, nullptr, kThrust1, &o.warm, o.T, &o.info) == UVMS_ERR_ARG);
  o.CheckZeroed();
}

TEST_CASE("uvms_alloc_min_power_each returns UVMS_ERR_STATE", "[api_status]") {
  const uvms_alloc_t a = ZeroAlloc();
  const NoLimits T;
  PowerOut o;
  REQUIRE(uvms_alloc_min_power_each(&a, T.N, nullptr, kThrust1, &o.warm, o.T, &o.info) == UVMS_ERR_STATE);
  o.CheckZeroed();
}

TEST_CASE("uvms_alloc_min_power_each returns UVMS_ERR_RANGE", "[api_status]") {
  // Thruster 1's P_0 = 1 N above its own 0.5 N bound (the others unlimited).
  const uvms_alloc_t a = PaperAlloc();
  NoLimits T;
  T.N[0] = R(0.5);
  PowerOut o;
  REQUIRE(uvms_alloc_min_power_each(&a, T.N, nullptr, kThrust1, &o.warm, o.T, &o.info) == UVMS_ERR_RANGE);
  o.CheckZeroed();
}

TEST_CASE("uvms_alloc_min_power_each returns UVMS_ERR_NONFINITE", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  const R P[8] = {1, 0, 0, kNaN, 0, 0, 0, 0};
  const NoLimits T;
  PowerOut o;
  REQUIRE(uvms_alloc_min_power_each(&a, T.N, nullptr, P, &o.warm, o.T, &o.info) == UVMS_ERR_NONFINITE);
  o.CheckZeroed();
}

TEST_CASE("uvms_alloc_min_power_each returns UVMS_ERR_SIZE", "[api_status]") {
  uvms_alloc_t a = PaperAlloc();
  a.rank = 4;  // corrupted, as in uvms_alloc_min_power's case
  const NoLimits T;
  PowerOut o;
  REQUIRE(uvms_alloc_min_power_each(&a, T.N, nullptr, kThrust1, &o.warm, o.T, &o.info) == UVMS_ERR_SIZE);
  o.CheckFallback(kThrust1);
}

TEST_CASE("uvms_alloc_min_power_each returns UVMS_ERR_SINGULAR", "[api_status]") {
  uvms_alloc_t a = PaperAlloc();
  a.H_pinv[0] = kNaN;
  const NoLimits T;
  PowerOut o;
  REQUIRE(uvms_alloc_min_power_each(&a, T.N, nullptr, kThrust1, &o.warm, o.T, &o.info) == UVMS_ERR_SINGULAR);
  o.CheckFallback(kThrust1);
}

TEST_CASE("uvms_alloc_min_power_each returns UVMS_ERR_RANGE: a weight not positive", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  const NoLimits T;
  R w[8];
  Fill(w, 8, R(1.0));
  w[4] = R(0.0);
  PowerOut o;
  REQUIRE(uvms_alloc_min_power_each(&a, T.N, w, kThrust1, &o.warm, o.T, &o.info) == UVMS_ERR_RANGE);
  o.CheckZeroed();
}

TEST_CASE("uvms_alloc_min_power_each returns UVMS_ERR_NONFINITE: a weight NaN", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  const NoLimits T;
  R w[8];
  Fill(w, 8, R(1.0));
  w[6] = kNaN;
  PowerOut o;
  REQUIRE(uvms_alloc_min_power_each(&a, T.N, w, kThrust1, &o.warm, o.T, &o.info) == UVMS_ERR_NONFINITE);
  o.CheckZeroed();
}

TEST_CASE("uvms_power_weights returns UVMS_OK", "[api_status]") {
  // D_1 = 0.05 m, D_6 = 0.1 m: w_6 = 0.5, the others 1 (entries j ≥ n = 7 are 1 too).
  uvms_thruster_params_t p[8];
  for (auto &x : p) x = PaperThruster();
  p[5].diameter_m = R(0.1);
  p[7].diameter_m = R(0.0);  // beyond n: never read
  JunkReals<8> w;
  REQUIRE(uvms_power_weights(p, 7, w) == UVMS_OK);
  for (int j = 0; j < 8; ++j) CHECK(w[j] == (j == 5 ? R(0.5) : R(1.0)));
}

TEST_CASE("uvms_power_weights returns UVMS_ERR_ARG", "[api_status]") {
  JunkReals<8> w;
  REQUIRE(uvms_power_weights(nullptr, 8, w) == UVMS_ERR_ARG);
  CHECK(AllEq(w, 8, 1));
}

TEST_CASE("uvms_power_weights returns UVMS_ERR_RANGE", "[api_status]") {
  uvms_thruster_params_t p[8];
  for (auto &x : p) x = PaperThruster();
  JunkReals<8> w;
  REQUIRE(uvms_power_weights(p, 9, w) == UVMS_ERR_RANGE);
  CHECK(AllEq(w, 8, 1));
  p[2].diameter_m = R(-0.05);
  REQUIRE(uvms_power_weights(p, 8, w) == UVMS_ERR_RANGE);
  CHECK(AllEq(w, 8, 1));
}

TEST_CASE("uvms_alloc_config_matrix returns UVMS_OK", "[api_status]") {
  // Column 1 of SPEC §3.4: u = (1, 0, 0) at a = (−0.5, 0.5, 0.5): a × u = (0, 0.5, −0.5).
  const uvms_alloc_t a = PaperAlloc();
  JunkReals<6 * 8> H;
  REQUIRE(uvms_alloc_config_matrix(&a, H) == UVMS_OK);
  const R col0[6] = {1, 0, 0, 0, R(0.5), R(-0.5)};
  for (int r = 0; r < 6; ++r) CHECK(double(H[r * 8]) == Approx(double(col0[r])).margin(kTol));
}

TEST_CASE("uvms_alloc_config_matrix returns UVMS_ERR_ARG", "[api_status]") {
  JunkReals<6 * 8> H;
  REQUIRE(uvms_alloc_config_matrix(nullptr, H) == UVMS_ERR_ARG);
  CHECK(AllEq(H, 48, 0));
}

TEST_CASE("uvms_alloc_config_matrix returns UVMS_ERR_STATE", "[api_status]") {
  const uvms_alloc_t a = ZeroAlloc();
  JunkReals<6 * 8> H;
  REQUIRE(uvms_alloc_config_matrix(&a, H) == UVMS_ERR_STATE);
  CHECK(AllEq(H, 48, 0));
}

TEST_CASE("uvms_alloc_wrench_body returns UVMS_OK", "[api_status]") {
  // 1 N on thruster 1 alone: the wrench is column 1 of H, (1, 0, 0, 0, 0.5, −0.5).
  const uvms_alloc_t a = PaperAlloc();
  JunkReals<6> w;
  REQUIRE(uvms_alloc_wrench_body(&a, kThrust1, w) == UVMS_OK);
  const R col0[6] = {1, 0, 0, 0, R(0.5), R(-0.5)};
  for (int r = 0; r < 6; ++r) CHECK(double(w[r]) == Approx(double(col0[r])).margin(kTol));
}

TEST_CASE("uvms_alloc_wrench_body returns UVMS_ERR_ARG", "[api_status]") {
  const uvms_alloc_t a = PaperAlloc();
  JunkReals<6> w;
  REQUIRE(uvms_alloc_wrench_body(&a, nullptr, w) == UVMS_ERR_ARG);
  CHECK(AllEq(w, 6, 0));
}

TEST_CASE("uvms_alloc_wrench_body returns UVMS_ERR_STATE", "[api_status]") {
  const uvms_alloc_t a = ZeroAlloc();
  JunkReals<6> w;
  REQUIRE(uvms_alloc_wrench_body(&a, kThrust1, w) == UVMS_ERR_STATE);
  CHECK(AllEq(w, 6, 0));
}

TEST_CASE("uvms_thruster_advance_speeds returns UVMS_OK", "[api_status]") {
  // Pure surge v0 = (1, 0, 0) m/s, R0 = I, no rotation, still water: v_a,j = u_j·e_x, i.e. 1 for
  // the four surge thrusters and 0 for the heave and sway ones (SPEC §3.4).
  const uvms_thruster_geometry_t g = PaperGeometry();
  const R v0[3] = {1, 0, 0};
  JunkReals<8> va;
  REQUIRE(uvms_thruster_advance_speeds(&g, kI3, v0, kZero3, kZero3, va) == UVMS_OK);
  for (int j = 0; j < 8; ++j) CHECK(va[j] == R(j < 4 ? 1 : 0));
}

TEST_CASE("uvms_thruster_advance_speeds returns UVMS_ERR_ARG", "[api_status]") {
  JunkReals<8> va;
  REQUIRE(uvms_thruster_advance_speeds(nullptr, kI3, kZero3, kZero3, kZero3, va) ==
          UVMS_ERR_ARG);
  CHECK(AllEq(va, 8, 0));
}

TEST_CASE("uvms_thruster_advance_speeds returns UVMS_ERR_SIZE", "[api_status]") {
  uvms_thruster_geometry_t g = PaperGeometry();
  g.num_thrusters = UVMS_MAX_THRUSTERS + 1;
  JunkReals<8> va;
  REQUIRE(uvms_thruster_advance_speeds(&g, kI3, kZero3, kZero3, kZero3, va) == UVMS_ERR_SIZE);
  CHECK(AllEq(va, 8, 0));
}

TEST_CASE("uvms_thruster_advance_speeds returns UVMS_ERR_NONFINITE", "[api_status]") {
  const uvms_thruster_geometry_t g = PaperGeometry();
  const R v0[3] = {0, kInf, 0};
  JunkReals<8> va;
  REQUIRE(uvms_thruster_advance_speeds(&g, kI3, v0, kZero3, kZero3, va) == UVMS_ERR_NONFINITE);
  CHECK(AllEq(va, 8, 0));
}

// ---------------------------------------------------------------------------------------------
// thruster.h

TEST_CASE("uvms_thruster_params_validate returns UVMS_OK", "[api_status]") {
  const uvms_thruster_params_t p = PaperThruster();
  REQUIRE(uvms_thruster_params_validate(&p) == UVMS_OK);
}

TEST_CASE("uvms_thruster_params_validate returns UVMS_ERR_ARG", "[api_status]") {
  REQUIRE(uvms_thruster_params_validate(nullptr) == UVMS_ERR_ARG);  // writes nothing
}

TEST_CASE("uvms_thruster_params_validate returns UVMS_ERR_NONFINITE", "[api_status]") {
  uvms_thruster_params_t p = PaperThruster();
  p.cq1 = kNaN;
  uvms_thruster_params_t before;
  std::memcpy(&before, &p, sizeof before);
  REQUIRE(uvms_thruster_params_validate(&p) == UVMS_ERR_NONFINITE);
  CHECK(SameBytes(p, before));
}

TEST_CASE("uvms_thruster_params_validate returns UVMS_ERR_RANGE", "[api_status]") {
  uvms_thruster_params_t p = PaperThruster();
  p.ct2 = R(0.5);  // CT2 must be < 0
  REQUIRE(uvms_thruster_params_validate(&p) == UVMS_ERR_RANGE);
}

TEST_CASE("uvms_thruster_desired_speed returns UVMS_OK", "[api_status]") {
  // T = 5 N at v_a = 0: ω̂ = −√(T/|c1|) (positive thrust, negative speed), and the thrust law
  // gives back T (thruster.h).
  const uvms_thruster_params_t p = PaperThruster();
  R w = kJunk;
  REQUIRE(uvms_thruster_desired_speed(&p, R(1025.0), R(5.0), R(0.0), &w) == UVMS_OK);
  const double D = 0.05, c1 = -0.5 * 1025.0 * D * D * D * D / (4.0 * M_PI * M_PI);
  CHECK(double(w) == Approx(-std::sqrt(5.0 / -c1)).epsilon(kTol));
  CHECK(double(uvms_thruster_thrust_N(&p, R(1025.0), w, R(0.0))) == Approx(5.0).epsilon(kTol));
}

TEST_CASE("uvms_thruster_desired_speed returns UVMS_ERR_ARG", "[api_status]") {
  R w = kJunk;
  REQUIRE(uvms_thruster_desired_speed(nullptr, R(1025.0), R(5.0), R(0.0), &w) == UVMS_ERR_ARG);
  CHECK(w == R(0));
}

TEST_CASE("uvms_thruster_desired_speed returns UVMS_ERR_NONFINITE", "[api_status]") {
  const uvms_thruster_params_t p = PaperThruster();
  R w = kJunk;
  REQUIRE(uvms_thruster_desired_speed(&p, R(1025.0), kNaN, R(0.0), &w) == UVMS_ERR_NONFINITE);
  CHECK(w == R(0));
}

TEST_CASE("uvms_thruster_desired_speed returns UVMS_ERR_RANGE", "[api_status]") {
  const uvms_thruster_params_t p = PaperThruster();
  R w = kJunk;
  REQUIRE(uvms_thruster_desired_speed(&p, R(0.0), R(5.0), R(0.0), &w) == UVMS_ERR_RANGE);
  CHECK(w == R(0));
}

TEST_CASE("uvms_motor_control returns UVMS_OK", "[api_status]") {
  // From rest (ω = I = 0): V = Rm·I + Lm·İ* + km·ω [53] = Lm·İ* = İ* (Lm = 1 H), not clamped.
  const uvms_thruster_params_t p = PaperThruster();
  Junked<uvms_motor_cmd_t> c;
  REQUIRE(uvms_motor_control(&p, R(1025.0), R(5.0), R(0.0), R(0.0), R(0.0), &c) == UVMS_OK);
  CHECK(c.saturated == 0);
  CHECK(double(c.voltage_V) == Approx(double(c.current_dot_des_A_s)).epsilon(kTol));
  CHECK(c.current_dot_cmd_A_s == c.current_dot_des_A_s);
  CHECK(c.omega_des_rad_s < R(0));  // positive thrust, negative speed
}

TEST_CASE("uvms_motor_control returns UVMS_ERR_ARG", "[api_status]") {
  Junked<uvms_motor_cmd_t> c;
  REQUIRE(uvms_motor_control(nullptr, R(1025.0), R(5.0), R(0.0), R(0.0), R(0.0), &c) ==
          UVMS_ERR_ARG);
  CHECK(ZeroBytes(&c, sizeof c));
}

TEST_CASE("uvms_motor_control returns UVMS_ERR_NONFINITE", "[api_status]") {
  const uvms_thruster_params_t p = PaperThruster();
  Junked<uvms_motor_cmd_t> c;
  REQUIRE(uvms_motor_control(&p, R(1025.0), R(5.0), R(0.0), kInf, R(0.0), &c) ==
          UVMS_ERR_NONFINITE);
  CHECK(ZeroBytes(&c, sizeof c));
}

TEST_CASE("uvms_motor_control returns UVMS_ERR_RANGE", "[api_status]") {
  const uvms_thruster_params_t p = PaperThruster();
  Junked<uvms_motor_cmd_t> c;
  REQUIRE(uvms_motor_control(&p, R(-1.0), R(5.0), R(0.0), R(0.0), R(0.0), &c) ==
          UVMS_ERR_RANGE);
  CHECK(ZeroBytes(&c, sizeof c));
}

TEST_CASE("uvms_motor_init returns UVMS_OK", "[api_status]") {
  const uvms_thruster_params_t p = PaperThruster();
  Junked<uvms_motor_t> m;
  REQUIRE(uvms_motor_init(&m, &p, R(1025.0), R(0.03)) == UVMS_OK);
  CHECK(m.ready == 1);
  CHECK(AllEq(m.current_cmd_A, UVMS_MAX_THRUSTERS, 0));
  CHECK(m.tick_s == R(0.03));
}

TEST_CASE("uvms_motor_init returns UVMS_ERR_ARG", "[api_status]") {
  Junked<uvms_motor_t> m;
  REQUIRE(uvms_motor_init(&m, nullptr, R(1025.0), R(0.03)) == UVMS_ERR_ARG);
  CHECK(ZeroBytes(&m, sizeof m));
}

TEST_CASE("uvms_motor_init returns UVMS_ERR_NONFINITE", "[api_status]") {
  const uvms_thruster_params_t p = PaperThruster();
  Junked<uvms_motor_t> m;
  REQUIRE(uvms_motor_init(&m, &p, R(1025.0), kNaN) == UVMS_ERR_NONFINITE);
  CHECK(ZeroBytes(&m, sizeof m));
}

TEST_CASE("uvms_motor_init returns UVMS_ERR_RANGE", "[api_status]") {
  const uvms_thruster_params_t p = PaperThruster();
  Junked<uvms_motor_t> m;
  REQUIRE(uvms_motor_init(&m, &p, R(1025.0), R(0.0)) == UVMS_ERR_RANGE);
  CHECK(ZeroBytes(&m, sizeof m));
}

TEST_CASE("uvms_motor_init_each returns UVMS_OK", "[api_status]") {
  uvms_thruster_params_t p[8];
  for (auto &x : p) x = PaperThruster();
  p[1].ct2 = R(-0.25);  // thruster 2 of another type
  Junked<uvms_motor_t> m;
  REQUIRE(uvms_motor_init_each(&m, p, 3, R(1025.0), R(0.03)) == UVMS_OK);
  CHECK(m.ready == 1);
  CHECK(m.num_thrusters == 3u);
  CHECK((m.p[0] == &p[0] && m.p[1] == &p[1] && m.p[2] == &p[2]));  // not copied
  CHECK((m.p[3] == &p[0] && m.p[7] == &p[0]));  // beyond the count: thruster 1's, never NULL
  CHECK(m.coef[1].c1_N_s2 != m.coef[0].c1_N_s2);  // thruster 2's own CT2
  CHECK(m.coef[7].c1_N_s2 == m.coef[0].c1_N_s2);
  CHECK(AllEq(m.current_cmd_A, UVMS_MAX_THRUSTERS, 0));
}

TEST_CASE("uvms_motor_init_each returns UVMS_ERR_ARG", "[api_status]") {
  Junked<uvms_motor_t> m;
  REQUIRE(uvms_motor_init_each(&m, nullptr, 3, R(1025.0), R(0.03)) == UVMS_ERR_ARG);
  CHECK(ZeroBytes(&m, sizeof m));
}

TEST_CASE("uvms_motor_init_each returns UVMS_ERR_SIZE", "[api_status]") {
  uvms_thruster_params_t p[8];
  for (auto &x : p) x = PaperThruster();
  Junked<uvms_motor_t> m;
  REQUIRE(uvms_motor_init_each(&m, p, 9, R(1025.0), R(0.03)) == UVMS_ERR_SIZE);
  CHECK(ZeroBytes(&m, sizeof m));
}

TEST_CASE("uvms_motor_init_each returns UVMS_ERR_NONFINITE", "[api_status]") {
  uvms_thruster_params_t p[8];
  for (auto &x : p) x = PaperThruster();
  p[2].rotor_inertia_kg_m2 = kNaN;
  Junked<uvms_motor_t> m;
  REQUIRE(uvms_motor_init_each(&m, p, 3, R(1025.0), R(0.03)) == UVMS_ERR_NONFINITE);
  CHECK(ZeroBytes(&m, sizeof m));
}

TEST_CASE("uvms_motor_init_each returns UVMS_ERR_RANGE", "[api_status]") {
  uvms_thruster_params_t p[8];
  for (auto &x : p) x = PaperThruster();
  p[2].ct2 = R(0.1);  // CT2 must be < 0
  Junked<uvms_motor_t> m;
  REQUIRE(uvms_motor_init_each(&m, p, 3, R(1025.0), R(0.03)) == UVMS_ERR_RANGE);
  CHECK(ZeroBytes(&m, sizeof m));
}

TEST_CASE("uvms_motor_step returns UVMS_OK", "[api_status]") {
  // Identical to uvms_motor_control with the instance's parameters (thruster.h).
  const uvms_motor_t m = ReadyMotor();
  Junked<uvms_motor_cmd_t> c;
  uvms_motor_cmd_t ref;
  REQUIRE(uvms_motor_step(&m, 3, R(2.0), R(0.1), R(-50.0), R(1.0), &c) == UVMS_OK);
  REQUIRE(uvms_motor_control(m.p[3], m.density_kg_m3, R(2.0), R(0.1), R(-50.0), R(1.0), &ref) ==
          UVMS_OK);
  // Field by field: padding bytes are unspecified after member stores (C11 6.2.6.1).
  CHECK(c.omega_des_rad_s == ref.omega_des_rad_s);
  CHECK(c.omega_dot_des_rad_s2 == ref.omega_dot_des_rad_s2);
  CHECK(c.current_des_A == ref.current_des_A);
  CHECK(c.current_dot_des_A_s == ref.current_dot_des_A_s);
  CHECK(c.voltage_V == ref.voltage_V);
  CHECK(c.current_dot_cmd_A_s == ref.current_dot_cmd_A_s);
  CHECK(c.saturated == ref.saturated);
}

TEST_CASE("uvms_motor_step returns UVMS_ERR_ARG", "[api_status]") {
  const uvms_motor_t m = ReadyMotor();
  Junked<uvms_motor_cmd_t> c;
  REQUIRE(uvms_motor_step(&m, UVMS_MAX_THRUSTERS, R(2.0), R(0.0), R(0.0), R(0.0), &c) ==
          UVMS_ERR_ARG);
  CHECK(ZeroBytes(&c, sizeof c));
  Junked<uvms_motor_cmd_t> c2;  // no motor: the safe output all the same
  REQUIRE(uvms_motor_step(nullptr, 0, R(2.0), R(0.0), R(0.0), R(0.0), &c2) == UVMS_ERR_ARG);
  CHECK(ZeroBytes(&c2, sizeof c2));
  CHECK(uvms_motor_step(&m, 0, R(2.0), R(0.0), R(0.0), R(0.0), nullptr) == UVMS_ERR_ARG);
}

TEST_CASE("uvms_motor_step returns UVMS_ERR_STATE", "[api_status]") {
  uvms_motor_t m;
  std::memset(&m, 0, sizeof m);
  Junked<uvms_motor_cmd_t> c;
  REQUIRE(uvms_motor_step(&m, 0, R(2.0), R(0.0), R(0.0), R(0.0), &c) == UVMS_ERR_STATE);
  CHECK(ZeroBytes(&c, sizeof c));
  // Not ready comes before the index: an uninitialised instance says so for any j.
  Junked<uvms_motor_cmd_t> c2;
  REQUIRE(uvms_motor_step(&m, UVMS_MAX_THRUSTERS, R(2.0), R(0.0), R(0.0), R(0.0), &c2) ==
          UVMS_ERR_STATE);
  CHECK(ZeroBytes(&c2, sizeof c2));
}

TEST_CASE("uvms_motor_step returns UVMS_ERR_NONFINITE", "[api_status]") {
  const uvms_motor_t m = ReadyMotor();
  Junked<uvms_motor_cmd_t> c;
  REQUIRE(uvms_motor_step(&m, 0, kNaN, R(0.0), R(0.0), R(0.0), &c) == UVMS_ERR_NONFINITE);
  CHECK(ZeroBytes(&c, sizeof c));
  // Finite inputs whose loop overflows after the desired speed (its second stage): a motor
  // current of kMax makes the current rate İ* = KB·(Î − I) overflow.
  Junked<uvms_motor_cmd_t> c2;
  REQUIRE(uvms_motor_step(&m, 0, R(2.0), R(0.0), R(0.0), kMax, &c2) ==
          UVMS_ERR_NONFINITE);
  CHECK(ZeroBytes(&c2, sizeof c2));
}

TEST_CASE("uvms_motor_step returns UVMS_ERR_RANGE", "[api_status]") {
  // A finite but huge advance speed: the discriminant c2² of [57–63] overflows.
  const uvms_motor_t m = ReadyMotor();
  Junked<uvms_motor_cmd_t> c;
  REQUIRE(uvms_motor_step(&m, 0, R(2.0), kMax / R(10.0), R(0.0), R(0.0), &c) == UVMS_ERR_RANGE);
  CHECK(ZeroBytes(&c, sizeof c));
}

// ---------------------------------------------------------------------------------------------
// trajectory.h

TEST_CASE("uvms_cycloid_eval returns UVMS_OK", "[api_status]") {
  // τ = 1/2, Δ = 1 rad, tF = 2 s: θ = 1/2, θ̇ = (Δ/tF)·(1 − cos π) = 1 rad/s, θ̈ ∝ sin π = 0.
  const R th0[1] = {0}, th1[1] = {1};
  R q[1] = {kJunk}, qd[1] = {kJunk}, qdd[1] = {kJunk};
  REQUIRE(uvms_cycloid_eval(1, th0, th1, R(2.0), R(1.0), q, qd, qdd) == UVMS_OK);
  CHECK(double(q[0]) == Approx(0.5).epsilon(kTol));
  CHECK(double(qd[0]) == Approx(1.0).epsilon(kTol));
  CHECK(double(qdd[0]) == Approx(0.0).margin(kTol));
}

TEST_CASE("uvms_cycloid_eval returns UVMS_ERR_ARG", "[api_status]") {
  const R th0[1] = {R(0.25)};
  R q[1] = {kJunk}, qdd[1] = {kJunk};
  REQUIRE(uvms_cycloid_eval(1, th0, nullptr, R(2.0), R(1.0), q, nullptr, qdd) == UVMS_ERR_ARG);
  CHECK(q[0] == R(0.25));  // hold the start
  CHECK(qdd[0] == R(0));
}

TEST_CASE("uvms_cycloid_eval returns UVMS_ERR_SIZE", "[api_status]") {
  R th0[UVMS_MAX_JOINTS + 1], th1[UVMS_MAX_JOINTS + 1];
  Fill(th0, UVMS_MAX_JOINTS + 1, R(0.5));
  Fill(th1, UVMS_MAX_JOINTS + 1, R(1.0));
  JunkReals<UVMS_MAX_JOINTS + 1> q, qd, qdd;
  REQUIRE(uvms_cycloid_eval(UVMS_MAX_JOINTS + 1, th0, th1, R(2.0), R(1.0), q, qd, qdd) ==
          UVMS_ERR_SIZE);
  CHECK(AllEq(q, UVMS_MAX_JOINTS, R(0.5)));  // hold the start in min(n, MAX) entries
  CHECK(AllEq(qd, UVMS_MAX_JOINTS, 0));
  CHECK(AllEq(qdd, UVMS_MAX_JOINTS, 0));
  CHECK(q[UVMS_MAX_JOINTS] == kJunk);  // nothing beyond
}

TEST_CASE("uvms_cycloid_eval returns UVMS_ERR_NONFINITE", "[api_status]") {
  const R th0[2] = {kNaN, R(0.3)}, th1[2] = {1, 1};
  R q[2] = {kJunk, kJunk}, qd[2] = {kJunk, kJunk}, qdd[2] = {kJunk, kJunk};
  REQUIRE(uvms_cycloid_eval(2, th0, th1, R(2.0), R(1.0), q, qd, qdd) == UVMS_ERR_NONFINITE);
  CHECK(q[0] == R(0));  // non-finite start: 0
  CHECK(q[1] == R(0.3));
  CHECK(AllEq(qd, 2, 0));
  CHECK(AllEq(qdd, 2, 0));
}

TEST_CASE("uvms_cycloid_eval returns UVMS_ERR_RANGE", "[api_status]") {
  const R th0[1] = {R(0.25)}, th1[1] = {1};
  R q[1] = {kJunk}, qd[1] = {kJunk}, qdd[1] = {kJunk};
  REQUIRE(uvms_cycloid_eval(1, th0, th1, R(0.0), R(1.0), q, qd, qdd) == UVMS_ERR_RANGE);
  CHECK(q[0] == R(0.25));
  CHECK(qd[0] == R(0));
  CHECK(qdd[0] == R(0));
}

// One joint of uvms_joint_servo: θ_ref = 1, θ̇_ref = 0, θ̈_ref = 0.5, θ = θ̇ = 0; the output
// filled with junk.
struct ServoCall {
  R qr[1] = {1};
  const R qdr[1] = {0}, qddr[1] = {R(0.5)}, q[1] = {0}, qd[1] = {0};
  R out[1] = {kJunk};
};

TEST_CASE("uvms_joint_servo returns UVMS_OK", "[api_status]") {
  // θ̈_cmd = θ̈_ref + Kq·(θ_ref − θ) + Kqd·(θ̇_ref − θ̇) = 0.5 + 100·1 + 20·0 = 100.5 rad/s².
  ServoCall s;
  REQUIRE(uvms_joint_servo(1, s.qr, s.qdr, s.qddr, s.q, s.qd, R(100), R(20), s.out) == UVMS_OK);
  CHECK(double(s.out[0]) == Approx(100.5).epsilon(kTol));
}

TEST_CASE("uvms_joint_servo returns UVMS_ERR_ARG", "[api_status]") {
  ServoCall s;
  REQUIRE(uvms_joint_servo(1, s.qr, s.qdr, s.qddr, s.q, nullptr, R(100), R(20), s.out) ==
          UVMS_ERR_ARG);
  CHECK(s.out[0] == R(0));
}

TEST_CASE("uvms_joint_servo returns UVMS_ERR_SIZE", "[api_status]") {
  R v[UVMS_MAX_JOINTS + 1];
  Fill(v, UVMS_MAX_JOINTS + 1, R(1));
  JunkReals<UVMS_MAX_JOINTS + 1> out;
  REQUIRE(uvms_joint_servo(UVMS_MAX_JOINTS + 1, v, v, v, v, v, R(100), R(20), out) ==
          UVMS_ERR_SIZE);
  CHECK(AllEq(out, UVMS_MAX_JOINTS, 0));
  CHECK(out[UVMS_MAX_JOINTS] == kJunk);
}

TEST_CASE("uvms_joint_servo returns UVMS_ERR_NONFINITE: measurement", "[api_status]") {
  const R qr[2] = {1, 1}, qdr[2] = {0, 0}, qddr[2] = {R(0.5), R(-0.25)}, q[2] = {0, kNaN},
          qd[2] = {0, 0};
  R out[2] = {kJunk, kJunk};
  REQUIRE(uvms_joint_servo(2, qr, qdr, qddr, q, qd, R(100), R(20), out) == UVMS_ERR_NONFINITE);
  CHECK(out[0] == R(0.5));  // feed-forward only, every joint
  CHECK(out[1] == R(-0.25));
}

TEST_CASE("uvms_joint_servo returns UVMS_ERR_NONFINITE: reference", "[api_status]") {
  ServoCall s;
  s.qr[0] = kInf;
  REQUIRE(uvms_joint_servo(1, s.qr, s.qdr, s.qddr, s.q, s.qd, R(100), R(20), s.out) ==
          UVMS_ERR_NONFINITE);
  CHECK(s.out[0] == R(0));
}

TEST_CASE("uvms_joint_servo returns UVMS_ERR_RANGE: negative gain", "[api_status]") {
  ServoCall s;
  REQUIRE(uvms_joint_servo(1, s.qr, s.qdr, s.qddr, s.q, s.qd, R(-1), R(20), s.out) ==
          UVMS_ERR_RANGE);
  CHECK(s.out[0] == R(0));
}

TEST_CASE("uvms_joint_servo returns UVMS_ERR_RANGE: feedback overflow", "[api_status]") {
  ServoCall s;
  s.qr[0] = 10;
  REQUIRE(uvms_joint_servo(1, s.qr, s.qdr, s.qddr, s.q, s.qd, kMax, R(20), s.out) ==
          UVMS_ERR_RANGE);
  CHECK(s.out[0] == R(0.5));  // feed-forward only
}

// The outputs of uvms_cosine_line_eval, filled with junk.
struct LineOut {
  JunkReals<3> r, v, a;
  // The error output: r = r0 (the start), ṙ = r̈ = 0.
  void CheckHold(const R r0[3]) const {
    for (int k = 0; k < 3; ++k) CHECK(r[k] == r0[k]);
    CHECK(AllEq(v, 3, 0));
    CHECK(AllEq(a, 3, 0));
  }
};

TEST_CASE("uvms_cosine_line_eval returns UVMS_OK", "[api_status]") {
  // τ = 1/2, rΔ = 1 m, tF = 2 s, u = e_x (direction (2, 0, 0) normalised):
  // r = (rΔ/2)·(1 − cos(π/2)) = 0.5 m, ṙ = π·rΔ/(2tF)·sin(π/2) = π/4 m/s, r̈ ∝ cos(π/2) = 0.
  const R r0[3] = {0, 0, 0}, dir[3] = {2, 0, 0};
  LineOut o;
  REQUIRE(uvms_cosine_line_eval(r0, dir, R(1.0), R(2.0), R(1.0), o.r, o.v, o.a) == UVMS_OK);
  CHECK(double(o.r[0]) == Approx(0.5).epsilon(kTol));
  CHECK(double(o.v[0]) == Approx(M_PI / 4.0).epsilon(kTol));
  CHECK(double(o.a[0]) == Approx(0.0).margin(kTol));
  CHECK(o.r[1] == R(0));
  CHECK(o.v[2] == R(0));
}

TEST_CASE("uvms_cosine_line_eval returns UVMS_ERR_ARG", "[api_status]") {
  const R r0[3] = {1, 2, 3};
  LineOut o;
  REQUIRE(uvms_cosine_line_eval(r0, nullptr, R(1.0), R(2.0), R(1.0), o.r, o.v, o.a) ==
          UVMS_ERR_ARG);
  o.CheckHold(r0);
}

TEST_CASE("uvms_cosine_line_eval returns UVMS_ERR_NONFINITE", "[api_status]") {
  const R r0[3] = {1, kNaN, 3}, dir[3] = {1, 0, 0};
  LineOut o;
  REQUIRE(uvms_cosine_line_eval(r0, dir, R(1.0), R(2.0), R(1.0), o.r, o.v, o.a) ==
          UVMS_ERR_NONFINITE);
  const R held[3] = {1, 0, 3};  // non-finite start component: 0
  o.CheckHold(held);
}

TEST_CASE("uvms_cosine_line_eval returns UVMS_ERR_RANGE", "[api_status]") {
  const R r0[3] = {1, 2, 3}, dir[3] = {R(1e-7), 0, 0};  // |u| < UVMS_TRAJ_MIN_DIRECTION_NORM
  LineOut o;
  REQUIRE(uvms_cosine_line_eval(r0, dir, R(1.0), R(2.0), R(1.0), o.r, o.v, o.a) ==
          UVMS_ERR_RANGE);
  o.CheckHold(r0);
}

TEST_CASE("uvms_cart_traj_init returns UVMS_OK", "[api_status]") {
  // The line starts at the EE of [3] at (r0d, R0d, θI), at rest, in the start pose.
  CartFixture f(kNotStarted);
  REQUIRE(f.Init() == UVMS_OK);
  CHECK(f.traj.ready == 1);
  CHECK(f.traj.n == 7u);
  CHECK(f.traj.t_state_s == R(0));
  for (int j = 0; j < 7; ++j) CHECK(f.traj.q_ref_rad[j] == f.q0[j]);
  CHECK(AllEq(f.traj.qd_ref_rad_s, 7, 0));
  uvms_arm_data_t d;
  REQUIRE(uvms_arm_fk(&f.model, &d, f.r0d, f.R0d, f.q0) == UVMS_OK);
  for (int k = 0; k < 3; ++k) CHECK(f.traj.r_start_m[k] == d.ee_m[k]);
}

TEST_CASE("uvms_cart_traj_init returns UVMS_ERR_ARG", "[api_status]") {
  CartFixture f(kNotStarted);
  REQUIRE(uvms_cart_traj_init(&f.traj, &f.params, &f.model, &f.work, nullptr, f.r0d, f.R0d) ==
          UVMS_ERR_ARG);
  CHECK(ZeroBytes(&f.traj, sizeof f.traj));
}

TEST_CASE("uvms_cart_traj_init returns UVMS_ERR_STATE", "[api_status]") {
  CartFixture f(kNotStarted);
  f.model.ready = 0;
  REQUIRE(f.Init() == UVMS_ERR_STATE);
  CHECK(ZeroBytes(&f.traj, sizeof f.traj));
}

TEST_CASE("uvms_cart_traj_init returns UVMS_ERR_NONFINITE", "[api_status]") {
  CartFixture f(kNotStarted);
  f.q0[3] = kNaN;
  REQUIRE(f.Init() == UVMS_ERR_NONFINITE);
  CHECK(ZeroBytes(&f.traj, sizeof f.traj));
}

TEST_CASE("uvms_cart_traj_init returns UVMS_ERR_RANGE", "[api_status]") {
  CartFixture f(kNotStarted);
  f.params.damping_m = 0;
  REQUIRE(f.Init() == UVMS_ERR_RANGE);
  CHECK(ZeroBytes(&f.traj, sizeof f.traj));
}

TEST_CASE("uvms_cart_traj_rate returns UVMS_OK", "[api_status]") {
  // At t = 0 in the start pose: ṙ_d = 0, r_d = r̂ and z = k0·(θI − θ) = 0, so q̇ = 0 exactly
  // (the DLS solve of a zero right-hand side), and r̂ = the line's start.
  CartFixture f;
  REQUIRE(f.Rate(R(0.0), f.q0) == UVMS_OK);
  CHECK(AllEq(f.qd, UVMS_MAX_JOINTS, 0));
  for (int k = 0; k < 3; ++k) CHECK(f.r[k] == f.traj.r_start_m[k]);
}

TEST_CASE("uvms_cart_traj_rate returns UVMS_ERR_ARG", "[api_status]") {
  CartFixture f;
  REQUIRE(f.Rate(R(0.0), nullptr) == UVMS_ERR_ARG);  // θ NULL
  f.CheckRateZero();
}

TEST_CASE("uvms_cart_traj_rate returns UVMS_ERR_STATE", "[api_status]") {
  CartFixture f;
  f.traj.ready = 0;
  REQUIRE(f.Rate(R(0.0), f.q0) == UVMS_ERR_STATE);
  f.CheckRateZero();
}

TEST_CASE("uvms_cart_traj_rate returns UVMS_ERR_NONFINITE", "[api_status]") {
  CartFixture f;
  REQUIRE(f.Rate(kNaN, f.q0) == UVMS_ERR_NONFINITE);  // t NaN
  f.CheckRateZero();
}

TEST_CASE("uvms_cart_traj_rate returns UVMS_ERR_RANGE", "[api_status]") {
  // rΔ = max/4 over tF = 1 ms: r̈ of the line (∝ rΔ/tF²) overflows inside (0, tF).
  CartFixture f(kNotStarted);
  f.params.distance_m = kMax / R(4.0);
  f.params.duration_s = R(1e-3);
  REQUIRE(f.Init() == UVMS_OK);
  REQUIRE(f.Rate(R(5e-4), f.q0) == UVMS_ERR_RANGE);
  f.CheckRateZero();
}

TEST_CASE("uvms_cart_traj_rate returns UVMS_ERR_SINGULAR", "[api_status]") {
  SingularCartFixture f;
  REQUIRE(f.Rate(R(1.0), f.q0) == UVMS_ERR_SINGULAR);
  f.CheckRateZero();
}

TEST_CASE("uvms_cart_traj_step returns UVMS_OK", "[api_status]") {
  // First tick after init at t = 0: θ_ref = θI (the stored state), θ̇_ref = f(0, θI) = 0 (see
  // the rate case above); the state advances to t + dt.
  CartFixture f;
  REQUIRE(f.Step(R(0.0), R(0.03)) == UVMS_OK);
  for (int j = 0; j < 7; ++j) CHECK(f.q[j] == f.q0[j]);
  CHECK(AllEq(f.qd, UVMS_MAX_JOINTS, 0));
  CHECK(AllFinite(f.qdd, UVMS_MAX_JOINTS));
  CHECK(f.traj.t_state_s == R(0.03));
}

TEST_CASE("uvms_cart_traj_step returns UVMS_ERR_ARG", "[api_status]") {
  CartFixture f;
  REQUIRE(uvms_cart_traj_step(&f.traj, &f.model, &f.work, R(0.0), R(0.03), nullptr, f.qd,
                              f.qdd) == UVMS_ERR_ARG);
  CHECK(AllEq(f.qd, UVMS_MAX_JOINTS, 0));
  CHECK(AllEq(f.qdd, UVMS_MAX_JOINTS, 0));
}

TEST_CASE("uvms_cart_traj_step returns UVMS_ERR_STATE", "[api_status]") {
  CartFixture f;
  f.traj.ready = 0;
  REQUIRE(f.Step(R(0.0), R(0.03)) == UVMS_ERR_STATE);
  CHECK(AllEq(f.q, UVMS_MAX_JOINTS, 0));  // not ready: all zero, not the hold
  CHECK(AllEq(f.qd, UVMS_MAX_JOINTS, 0));
  CHECK(AllEq(f.qdd, UVMS_MAX_JOINTS, 0));
}

TEST_CASE("uvms_cart_traj_step returns UVMS_ERR_NONFINITE", "[api_status]") {
  CartFixture f;
  REQUIRE(f.Step(kNaN, R(0.03)) == UVMS_ERR_NONFINITE);  // t NaN
  f.CheckHold();
}

TEST_CASE("uvms_cart_traj_step returns UVMS_ERR_RANGE", "[api_status]") {
  CartFixture f;
  REQUIRE(f.Step(R(0.0), R(0.0)) == UVMS_ERR_RANGE);  // dt = 0
  f.CheckHold();
}

TEST_CASE("uvms_cart_traj_step returns UVMS_ERR_SINGULAR", "[api_status]") {
  SingularCartFixture f;
  REQUIRE(f.Step(R(1.0), R(0.03)) == UVMS_ERR_SINGULAR);
  f.CheckHold();
}

// ---------------------------------------------------------------------------------------------
// The Table X switches (feedback.h) and the configuration checks of the modules (pure checks:
// the argument is const, nothing is written). uvms_ctrl_init calls them, each for the part its
// module owns.

TEST_CASE("uvms_switches_case returns UVMS_OK", "[api_status]") {
  // Table X, case VII: attitude on, barycenter reference, position feedforward and feedback.
  Junked<uvms_switches_t> sw;
  REQUIRE(uvms_switches_case(7, &sw) == UVMS_OK);
  CHECK(sw.attitude_control == 1);
  CHECK(sw.position_reference == UVMS_REF_BARYCENTER);
  CHECK(sw.position_feedforward == 1);
  CHECK(sw.position_feedback == 1);
}

TEST_CASE("uvms_switches_case returns UVMS_ERR_ARG", "[api_status]") {
  REQUIRE(uvms_switches_case(4, nullptr) == UVMS_ERR_ARG);  // nothing to write
}

TEST_CASE("uvms_switches_case returns UVMS_ERR_RANGE", "[api_status]") {
  Junked<uvms_switches_t> sw;
  REQUIRE(uvms_switches_case(0, &sw) == UVMS_ERR_RANGE);
  CHECK(ZeroBytes(&sw, sizeof sw));  // every switch off, vehicle reference
}

TEST_CASE("uvms_fluid_check returns UVMS_OK", "[api_status]") {
  const uvms_ctrl_config_t c = PaperConfig();
  CHECK(uvms_fluid_check(&c.fluid) == UVMS_OK);
  uvms_fluid_t fl = c.fluid;
  fl.angle_of_attack = 0;
  uvms_v3_set(fl.flow_m_s, R(0.1), R(-0.2), R(0));
  uvms_v3_set(fl.gravity_m_s2, R(0), R(0), R(-9.81));
  CHECK(uvms_fluid_check(&fl) == UVMS_OK);
}

TEST_CASE("uvms_fluid_check returns UVMS_ERR_ARG", "[api_status]") {
  CHECK(uvms_fluid_check(nullptr) == UVMS_ERR_ARG);
}

TEST_CASE("uvms_fluid_check returns UVMS_ERR_NONFINITE", "[api_status]") {
  const uvms_ctrl_config_t c = PaperConfig();
  for (int which = 0; which < 3; ++which) {
    uvms_fluid_t fl = c.fluid;
    if (which == 0) fl.density_kg_m3 = kNaN;
    if (which == 1) fl.flow_m_s[2] = kInf;
    if (which == 2) fl.gravity_m_s2[0] = -kInf;
    CHECK(uvms_fluid_check(&fl) == UVMS_ERR_NONFINITE);
  }
}

TEST_CASE("uvms_fluid_check returns UVMS_ERR_RANGE", "[api_status]") {
  const uvms_ctrl_config_t c = PaperConfig();
  uvms_fluid_t fl = c.fluid;
  fl.density_kg_m3 = 0;  // the thruster loops divide by it
  CHECK(uvms_fluid_check(&fl) == UVMS_ERR_RANGE);
  fl = c.fluid;
  fl.angle_of_attack = 2;
  CHECK(uvms_fluid_check(&fl) == UVMS_ERR_RANGE);
}

TEST_CASE("uvms_pd_gains_check returns UVMS_OK", "[api_status]") {
  uvms_pd_gains_t g;
  uvms_pd_gains_paper(&g);
  CHECK(uvms_pd_gains_check(&g) == UVMS_OK);
  g.kpf_N_m = 0;  // a term off
  CHECK(uvms_pd_gains_check(&g) == UVMS_OK);
}

TEST_CASE("uvms_pd_gains_check returns UVMS_ERR_ARG", "[api_status]") {
  CHECK(uvms_pd_gains_check(nullptr) == UVMS_ERR_ARG);
}

TEST_CASE("uvms_pd_gains_check returns UVMS_ERR_NONFINITE", "[api_status]") {
  uvms_pd_gains_t g;
  uvms_pd_gains_paper(&g);
  g.kdn_Nm_s_rad = kNaN;
  g.kpf_N_m = -1;  // a NaN anywhere is reported before a range error
  CHECK(uvms_pd_gains_check(&g) == UVMS_ERR_NONFINITE);
}

TEST_CASE("uvms_pd_gains_check returns UVMS_ERR_RANGE", "[api_status]") {
  uvms_pd_gains_t g;
  uvms_pd_gains_paper(&g);
  g.kpn_Nm_rad = R(-0.5);
  CHECK(uvms_pd_gains_check(&g) == UVMS_ERR_RANGE);
}

TEST_CASE("uvms_switches_check returns UVMS_OK", "[api_status]") {
  for (int c = 1; c <= 8; ++c) {
    uvms_switches_t sw;
    REQUIRE(uvms_switches_case(c, &sw) == UVMS_OK);
    CHECK(uvms_switches_check(&sw) == UVMS_OK);
  }
}

TEST_CASE("uvms_switches_check returns UVMS_ERR_ARG", "[api_status]") {
  CHECK(uvms_switches_check(nullptr) == UVMS_ERR_ARG);
}

TEST_CASE("uvms_switches_check returns UVMS_ERR_RANGE", "[api_status]") {
  for (int which = 0; which < 4; ++which) {
    uvms_switches_t sw;
    REQUIRE(uvms_switches_case(7, &sw) == UVMS_OK);
    if (which == 0) sw.attitude_control = 2;
    if (which == 1) sw.position_feedforward = -1;
    if (which == 2) sw.position_feedback = 5;
    if (which == 3) sw.position_reference = static_cast<uvms_reference_t>(2);
    CHECK(uvms_switches_check(&sw) == UVMS_ERR_RANGE);
  }
}

TEST_CASE("uvms_joint_servo_gains_check returns UVMS_OK", "[api_status]") {
  CHECK(uvms_joint_servo_gains_check(UVMS_JOINT_SERVO_KQ_DEFAULT_1_S2,
                                     UVMS_JOINT_SERVO_KQD_DEFAULT_1_S) == UVMS_OK);
  CHECK(uvms_joint_servo_gains_check(0, 0) == UVMS_OK);
}

TEST_CASE("uvms_joint_servo_gains_check returns UVMS_ERR_NONFINITE", "[api_status]") {
  CHECK(uvms_joint_servo_gains_check(kNaN, 1) == UVMS_ERR_NONFINITE);
  CHECK(uvms_joint_servo_gains_check(-1, kInf) == UVMS_ERR_NONFINITE);
}

TEST_CASE("uvms_joint_servo_gains_check returns UVMS_ERR_RANGE", "[api_status]") {
  CHECK(uvms_joint_servo_gains_check(-1, 1) == UVMS_ERR_RANGE);
  CHECK(uvms_joint_servo_gains_check(1, R(-1e-9)) == UVMS_ERR_RANGE);
}

TEST_CASE("uvms_alloc_mode_check returns UVMS_OK", "[api_status]") {
  CHECK(uvms_alloc_mode_check(UVMS_ALLOC_PSEUDOINVERSE) == UVMS_OK);
  CHECK(uvms_alloc_mode_check(UVMS_ALLOC_MIN_POWER) == UVMS_OK);
}

TEST_CASE("uvms_alloc_mode_check returns UVMS_ERR_RANGE", "[api_status]") {
  CHECK(uvms_alloc_mode_check(static_cast<uvms_alloc_mode_t>(1)) == UVMS_ERR_RANGE);  // retired
  CHECK(uvms_alloc_mode_check(static_cast<uvms_alloc_mode_t>(3)) == UVMS_ERR_RANGE);
  CHECK(uvms_alloc_mode_check(static_cast<uvms_alloc_mode_t>(-1)) == UVMS_ERR_RANGE);
}

TEST_CASE("uvms_alloc_thrust_limit_check returns UVMS_OK", "[api_status]") {
  CHECK(uvms_alloc_thrust_limit_check(0) == UVMS_OK);  // no limit
  CHECK(uvms_alloc_thrust_limit_check(R(40)) == UVMS_OK);
}

TEST_CASE("uvms_alloc_thrust_limit_check returns UVMS_ERR_NONFINITE", "[api_status]") {
  CHECK(uvms_alloc_thrust_limit_check(kNaN) == UVMS_ERR_NONFINITE);
  CHECK(uvms_alloc_thrust_limit_check(kInf) == UVMS_ERR_NONFINITE);
}

TEST_CASE("uvms_alloc_thrust_limit_check returns UVMS_ERR_RANGE", "[api_status]") {
  CHECK(uvms_alloc_thrust_limit_check(R(-1)) == UVMS_ERR_RANGE);
}

TEST_CASE("uvms_drive_check returns UVMS_OK", "[api_status]") {
  CHECK(uvms_drive_check(UVMS_DRIVE_CURRENT) == UVMS_OK);
  CHECK(uvms_drive_check(UVMS_DRIVE_VOLTAGE) == UVMS_OK);
}

TEST_CASE("uvms_drive_check returns UVMS_ERR_RANGE", "[api_status]") {
  CHECK(uvms_drive_check(static_cast<uvms_drive_t>(2)) == UVMS_ERR_RANGE);
}

// ---------------------------------------------------------------------------------------------
// controller.h

TEST_CASE("uvms_ctrl_config_paper returns UVMS_OK", "[api_status]") {
  Junked<uvms_ctrl_config_t> c;
  REQUIRE(uvms_ctrl_config_paper(&c, 7) == UVMS_OK);
  CHECK(c.switches.position_reference == UVMS_REF_BARYCENTER);
  CHECK(c.cart.reference == UVMS_REF_BARYCENTER);
  CHECK(c.tick_s == R(0.03));
  uvms_ctrl_t ctrl;
  CHECK(uvms_ctrl_init(&ctrl, &c) == UVMS_OK);  // a valid configuration
}

TEST_CASE("uvms_ctrl_config_paper returns UVMS_ERR_ARG", "[api_status]") {
  REQUIRE(uvms_ctrl_config_paper(nullptr, 4) == UVMS_ERR_ARG);  // nothing to write
}

TEST_CASE("uvms_ctrl_config_paper returns UVMS_ERR_RANGE", "[api_status]") {
  Junked<uvms_ctrl_config_t> c;
  uvms_ctrl_config_t iv;
  REQUIRE(uvms_ctrl_config_paper(&c, 9) == UVMS_ERR_RANGE);
  REQUIRE(uvms_ctrl_config_paper(&iv, 4) == UVMS_OK);
  CHECK(SameBytes<uvms_ctrl_config_t>(c, iv));  // case IV's configuration
}

TEST_CASE("uvms_ctrl_init returns UVMS_OK", "[api_status]") {
  const uvms_ctrl_config_t c = PaperConfig();
  Junked<uvms_ctrl_t> ctrl;
  REQUIRE(uvms_ctrl_init(&ctrl, &c) == UVMS_OK);
  CHECK(ctrl.ready == 1);
  CHECK(ctrl.config_error == UVMS_CFG_OK);
  CHECK(ctrl.cfg == &c);  // the caller's configuration, not a copy
  for (int j = 0; j < UVMS_MAX_JOINTS; ++j) CHECK(ctrl.q_ref_last_rad[j] == c.theta_start_rad[j]);
}

TEST_CASE("uvms_ctrl_init returns UVMS_ERR_ARG: cfg NULL", "[api_status]") {
  Junked<uvms_ctrl_t> ctrl;
  REQUIRE(uvms_ctrl_init(&ctrl, nullptr) == UVMS_ERR_ARG);
  CheckRefusedCtrl(ctrl, UVMS_CFG_OK);
}

TEST_CASE("uvms_ctrl_init returns UVMS_ERR_ARG: no thrusters", "[api_status]") {
  uvms_ctrl_config_t c = PaperConfig();
  c.thrusters.num_thrusters = 0;
  Junked<uvms_ctrl_t> ctrl;
  REQUIRE(uvms_ctrl_init(&ctrl, &c) == UVMS_ERR_ARG);
  CheckRefusedCtrl(ctrl, UVMS_CFG_THRUSTER_GEOMETRY);
}

TEST_CASE("uvms_ctrl_init returns UVMS_ERR_SIZE", "[api_status]") {
  uvms_ctrl_config_t c = PaperConfig();
  c.arm.num_joints = UVMS_MAX_JOINTS + 1;
  Junked<uvms_ctrl_t> ctrl;
  REQUIRE(uvms_ctrl_init(&ctrl, &c) == UVMS_ERR_SIZE);
  CheckRefusedCtrl(ctrl, UVMS_CFG_ARM);
}

TEST_CASE("uvms_ctrl_init returns UVMS_ERR_NONFINITE", "[api_status]") {
  uvms_ctrl_config_t c = PaperConfig();
  c.tick_s = kNaN;
  Junked<uvms_ctrl_t> ctrl;
  REQUIRE(uvms_ctrl_init(&ctrl, &c) == UVMS_ERR_NONFINITE);
  CheckRefusedCtrl(ctrl, UVMS_CFG_TICK);
}

TEST_CASE("uvms_ctrl_init returns UVMS_ERR_RANGE: drive", "[api_status]") {
  uvms_ctrl_config_t c = PaperConfig();
  c.drive = static_cast<uvms_drive_t>(5);
  Junked<uvms_ctrl_t> ctrl;
  REQUIRE(uvms_ctrl_init(&ctrl, &c) == UVMS_ERR_RANGE);
  CheckRefusedCtrl(ctrl, UVMS_CFG_DRIVE);
}

TEST_CASE("uvms_ctrl_init returns UVMS_ERR_RANGE: Cartesian line reference", "[api_status]") {
  uvms_ctrl_config_t c = PaperConfig(4);  // vehicle reference
  c.traj_mode = UVMS_TRAJ_CARTESIAN_LINE;
  c.cart.reference = UVMS_REF_BARYCENTER;
  Junked<uvms_ctrl_t> ctrl;
  REQUIRE(uvms_ctrl_init(&ctrl, &c) == UVMS_ERR_RANGE);
  CheckRefusedCtrl(ctrl, UVMS_CFG_TRAJECTORY);
}

TEST_CASE("uvms_ctrl_init returns UVMS_ERR_SINGULAR", "[api_status]") {
  uvms_ctrl_config_t c = PaperConfig();
  for (int j = 0; j < 8; ++j) {
    Fill(c.thrusters.position_m[j], 3, 0);
    uvms_v3_set(c.thrusters.direction[j], 1, 0, 0);
  }
  Junked<uvms_ctrl_t> ctrl;
  REQUIRE(uvms_ctrl_init(&ctrl, &c) == UVMS_ERR_SINGULAR);
  CheckRefusedCtrl(ctrl, UVMS_CFG_THRUSTER_RANK);
}

TEST_CASE("uvms_ctrl_config_verify returns UVMS_OK", "[api_status]") {
  CtrlStepCall f;
  CHECK(uvms_ctrl_config_verify(&f.ctrl) == UVMS_OK);
  // Stepping reads the configuration, never writes it.
  REQUIRE(uvms_ctrl_step(&f.ctrl, &f.s, &f.cmd, &f.t) == UVMS_OK);
  CHECK(uvms_ctrl_config_verify(&f.ctrl) == UVMS_OK);
}

TEST_CASE("uvms_ctrl_config_verify returns UVMS_ERR_ARG", "[api_status]") {
  CHECK(uvms_ctrl_config_verify(nullptr) == UVMS_ERR_ARG);
}

TEST_CASE("uvms_ctrl_config_verify returns UVMS_ERR_STATE: not ready", "[api_status]") {
  CtrlStepCall f(kNotInitialised);
  CHECK(uvms_ctrl_config_verify(&f.ctrl) == UVMS_ERR_STATE);
  uvms_ctrl_config_t c = PaperConfig();
  c.tick_s = 0;
  uvms_ctrl_t refused;
  REQUIRE(uvms_ctrl_init(&refused, &c) == UVMS_ERR_RANGE);
  CHECK(uvms_ctrl_config_verify(&refused) == UVMS_ERR_STATE);
}

TEST_CASE("uvms_ctrl_config_verify returns UVMS_ERR_STATE: configuration changed", "[api_status]") {
  // Any byte of the configuration the instance points to, changed after init: a gain, the last
  // byte of the record, one bit of a count. Restored, it verifies again.
  uvms_ctrl_config_t c = PaperConfig();
  uvms_ctrl_t ctrl;
  REQUIRE(uvms_ctrl_init(&ctrl, &c) == UVMS_OK);
  unsigned char *bytes = reinterpret_cast<unsigned char *>(&c);
  const size_t offsets[] = {offsetof(uvms_ctrl_config_t, gains), sizeof c - 1,
                            offsetof(uvms_ctrl_config_t, arm)};
  for (const size_t at : offsets) {
    INFO("byte " << at);
    bytes[at] ^= 0x01u;
    CHECK(uvms_ctrl_config_verify(&ctrl) == UVMS_ERR_STATE);
    bytes[at] ^= 0x01u;
    CHECK(uvms_ctrl_config_verify(&ctrl) == UVMS_OK);
  }
  CHECK(ctrl.ready == 1);  // a pure check: the instance is untouched
}

TEST_CASE("uvms_ctrl_step returns UVMS_OK", "[api_status]") {
  CtrlStepCall f;
  REQUIRE(uvms_ctrl_step(&f.ctrl, &f.s, &f.cmd, &f.t) == UVMS_OK);
  CHECK(f.t.status == UVMS_OK);
  CHECK((f.t.flags & UVMS_FLAG_REFERENCE_CAPTURED) != 0u);
  CHECK((f.t.flags & UVMS_FLAG_SENSOR_HOLD_EXPIRED) == 0u);
  // t = 0: the cycloid holds θI at rest; the servo sees no error.
  for (int j = 0; j < 7; ++j) CHECK(f.cmd.joint_ref_rad[j] == f.c.theta_start_rad[j]);
  CHECK(AllEq(f.cmd.joint_acceleration_rad_s2, UVMS_MAX_JOINTS, 0));
  CHECK(AllFinite(f.cmd.motor_voltage_V, UVMS_MAX_THRUSTERS));
  CHECK(TelemetryFinite(f.t));
}

TEST_CASE("uvms_ctrl_step returns UVMS_ERR_ARG", "[api_status]") {
  CtrlStepCall f;
  REQUIRE(uvms_ctrl_step(&f.ctrl, nullptr, &f.cmd, &f.t) == UVMS_ERR_ARG);
  CHECK(f.t.status == UVMS_ERR_ARG);
  CheckSafeCommand(f.cmd, f.c.theta_start_rad);  // θ_ref = θI before the first good tick
  CHECK(TelemetryFinite(f.t));
  CHECK(AllEq(f.ctrl.motor.current_cmd_A, UVMS_MAX_THRUSTERS, 0));  // next tick's I* = 0
}

TEST_CASE("uvms_ctrl_step returns UVMS_ERR_STATE: not initialised", "[api_status]") {
  CtrlStepCall f(kNotInitialised);  // all zero
  REQUIRE(uvms_ctrl_step(&f.ctrl, &f.s, &f.cmd, &f.t) == UVMS_ERR_STATE);
  CHECK(f.t.status == UVMS_ERR_STATE);
  CheckSafeCommand(f.cmd, kZero7);  // no reference known: θ_ref = 0
}

TEST_CASE("uvms_ctrl_step returns UVMS_ERR_STATE: corrupt joint count", "[api_status]") {
  CtrlStepCall f;
  f.ctrl.model.num_joints = 1000;  // corrupted in RAM
  REQUIRE(uvms_ctrl_step(&f.ctrl, &f.s, &f.cmd, &f.t) == UVMS_ERR_STATE);
  CHECK((f.t.flags & UVMS_FLAG_INSTANCE_INVALID) != 0u);
  CheckSafeCommand(f.cmd, f.c.theta_start_rad);
  CHECK(TelemetryFinite(f.t));
}

TEST_CASE("uvms_ctrl_step returns UVMS_ERR_NONFINITE", "[api_status]") {
  // A NaN on the first record: no good record to hold (SENSOR_HOLD_EXPIRED).
  CtrlStepCall f;
  f.s.position_m[1] = kNaN;
  REQUIRE(uvms_ctrl_step(&f.ctrl, &f.s, &f.cmd, &f.t) == UVMS_ERR_NONFINITE);
  CHECK(f.t.status == UVMS_ERR_NONFINITE);
  CHECK((f.t.flags & UVMS_FLAG_SENSOR_NONFINITE) != 0u);
  CHECK((f.t.flags & UVMS_FLAG_SENSOR_HOLD_EXPIRED) != 0u);
  CheckSafeCommand(f.cmd, f.c.theta_start_rad);
  CHECK(TelemetryFinite(f.t));
}

TEST_CASE("uvms_ctrl_step returns UVMS_ERR_RANGE", "[api_status]") {
  // |q| = 2 on the first record: QUATERNION_INVALID, nothing to hold.
  CtrlStepCall f;
  f.s.quaternion_wxyz[0] = 2;
  REQUIRE(uvms_ctrl_step(&f.ctrl, &f.s, &f.cmd, &f.t) == UVMS_ERR_RANGE);
  CHECK(f.t.status == UVMS_ERR_RANGE);
  CHECK((f.t.flags & UVMS_FLAG_QUATERNION_INVALID) != 0u);
  CHECK((f.t.flags & UVMS_FLAG_SENSOR_HOLD_EXPIRED) != 0u);
  CheckSafeCommand(f.cmd, f.c.theta_start_rad);
  CHECK(TelemetryFinite(f.t));
}

TEST_CASE("uvms_ctrl_step returns UVMS_ERR_SINGULAR", "[api_status]") {
  // A corrupted allocation instance (NaN in its geometry after init) and a new usable set:
  // H⁺ cannot be computed. Thrusters idle, the joint command of the tick stands: at t = 30 s,
  // mid-cycloid, θ_ref is the cycloid's and becomes the last good reference.
  CtrlStepCall f;
  f.ctrl.alloc.geom.position_m[0][0] = kNaN;
  f.s.time_s = R(30.0);
  f.s.thruster_usable_mask = 0x7Fu;
  REQUIRE(uvms_ctrl_step(&f.ctrl, &f.s, &f.cmd, &f.t) == UVMS_ERR_SINGULAR);
  CHECK(f.t.status == UVMS_ERR_SINGULAR);
  CHECK((f.t.flags & UVMS_FLAG_ALLOC_SINGULAR) != 0u);
  CHECK(AllEq(f.cmd.motor_voltage_V, UVMS_MAX_THRUSTERS, 0));
  CHECK(AllEq(f.cmd.motor_current_cmd_A, UVMS_MAX_THRUSTERS, 0));
  CHECK(AllEq(f.cmd.motor_current_rate_A_s, UVMS_MAX_THRUSTERS, 0));
  const uvms_ctrl_config_t &c = f.c;
  R q[UVMS_MAX_JOINTS], qd[UVMS_MAX_JOINTS], qdd[UVMS_MAX_JOINTS];
  REQUIRE(uvms_cycloid_eval(7, c.theta_start_rad, c.theta_final_rad, c.traj_duration_s,
                            R(30.0) - c.traj_start_s, q, qd, qdd) == UVMS_OK);
  for (int j = 0; j < 7; ++j) {
    CHECK(f.cmd.joint_ref_rad[j] == q[j]);
    CHECK(f.cmd.joint_ref_rate_rad_s[j] == qd[j]);
    CHECK(f.ctrl.q_ref_last_rad[j] == q[j]);  // committed
  }
  CHECK(AllFinite(f.cmd.joint_acceleration_rad_s2, UVMS_MAX_JOINTS));
  CHECK(TelemetryFinite(f.t));
}

// ---------------------------------------------------------------------------------------------
// Functions without a status: the documented behaviour on bad input (not counted by
// check_api_retval.py, whose pairs come from @retval lines).

TEST_CASE("Name functions give a fixed string for values outside their enum", "[api_status]") {
  CHECK(std::strcmp(uvms_status_str(static_cast<uvms_status_t>(-99)), "UVMS_ERR_UNKNOWN") == 0);
  CHECK(std::strcmp(uvms_cfg_field_str(static_cast<uvms_cfg_field_t>(99)), "unknown") == 0);
  CHECK(std::strcmp(uvms_alloc_mode_str(static_cast<uvms_alloc_mode_t>(9)), "invalid") == 0);
  CHECK(std::strcmp(uvms_drive_str(static_cast<uvms_drive_t>(9)), "invalid") == 0);
  CHECK(uvms_joint_table_deg(static_cast<uvms_joint_table_column_t>(-1)) == nullptr);
  CHECK(uvms_joint_table_payload_kg(UVMS_JOINT_TABLE_COLUMNS) == R(-1));
}

TEST_CASE("Fill and reset functions ignore NULL", "[api_status]") {
  uvms_arm_params_paper(nullptr);
  uvms_pd_gains_paper(nullptr);
  uvms_thruster_params_paper(nullptr);
  uvms_thruster_geometry_paper(nullptr);
  uvms_cart_traj_params_default(nullptr);
  uvms_motor_reset(nullptr);
  uvms_motor_end_tick(nullptr, nullptr, nullptr);
  uvms_ctrl_reset(nullptr);
  uvms_arm_shift_base_accel(nullptr, nullptr, nullptr);
  CHECK(uvms_thruster_thrust_N(nullptr, R(1025), R(10), R(0)) == R(0));
  CHECK(uvms_thruster_torque_Nm(nullptr, R(1025), R(10), R(0)) == R(0));
}

TEST_CASE("uvms_motor_end_tick without a command zeroes every integrated current",
          "[api_status]") {
  uvms_motor_t m = ReadyMotor();
  Fill(m.current_cmd_A, UVMS_MAX_THRUSTERS, kJunk);
  uvms_motor_end_tick(&m, nullptr, nullptr);
  CHECK(AllEq(m.current_cmd_A, UVMS_MAX_THRUSTERS, 0));
  // An overflowing I* + İ*·tick gives 0 (thruster.h).
  R cmd[UVMS_MAX_THRUSTERS], rate[UVMS_MAX_THRUSTERS];
  Fill(cmd, UVMS_MAX_THRUSTERS, kMax);
  Fill(rate, UVMS_MAX_THRUSTERS, kMax);
  uvms_motor_end_tick(&m, cmd, rate);
  CHECK(AllEq(m.current_cmd_A, UVMS_MAX_THRUSTERS, 0));
}

TEST_CASE("uvms_drag_force is zero for a NaN relative speed", "[api_status]") {
  const R w[3] = {kNaN, 0, 0};
  R D[3] = {kJunk, kJunk, kJunk};
  uvms_drag_force(R(1025), R(1), R(1), w, nullptr, D);
  CHECK(AllEq(D, 3, 0));
}

TEST_CASE("uvms_ctrl_reset keeps an instance that is not ready refused", "[api_status]") {
  const uvms_ctrl_config_t c = PaperConfig();
  uvms_ctrl_t ctrl;
  std::memset(&ctrl, 0, sizeof ctrl);
  uvms_ctrl_reset(&ctrl);
  CHECK(ctrl.ready == 0);
  const uvms_ctrl_sensors_t s = RestSensors(c);
  uvms_ctrl_command_t cmd;
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, nullptr) == UVMS_ERR_STATE);
}
