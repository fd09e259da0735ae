// SPDX-License-Identifier: Apache-2.0
// Trajectories and the joint servo (SPEC §8): the cycloid and the cosine line against their
// own derivatives by finite differences, the servo against its formula and in closed loop on a
// double integrator, and the Cartesian resolved-rate IK against an EE estimate recomputed here
// from uvms_arm_fk ([3] for the vehicle reference, [4] for the barycenter reference).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "fw_test_util.hpp"
#include "uvms/kinematics.h"
#include "uvms/trajectory.h"
#include "eigen_reference.hpp"

using namespace fwtest;

namespace {

constexpr double kDeg = M_PI / 180.0;
// SPEC §8 table (the firmware's): θI and the "Veh." final column [deg].
const uvms_real_t *const kThetaIDeg = uvms_joint_table_deg(UVMS_JOINT_TABLE_START);
const uvms_real_t *const kThetaVehDeg = uvms_joint_table_deg(UVMS_JOINT_TABLE_VEHICLE);

struct Joints {
  uvms_real_t v[UVMS_MAX_JOINTS] = {};
};

Joints FromDeg(const uvms_real_t *deg) {
  Joints j;
  for (int i = 0; i < 7; ++i) j.v[i] = uvms_real_t(double(deg[i]) * kDeg);
  return j;
}

double MaxAbsDelta(const Joints &a, const Joints &b) {
  double m = 0;
  for (int i = 0; i < 7; ++i) m = std::max(m, std::abs(double(b.v[i]) - double(a.v[i])));
  return m;
}

// ---------------------------------------------------------------------------------------------
// Cartesian line runs.

// The line [78] written out again here (double), from a start point the test computed itself.
Eigen::Vector3d LinePoint(const Eigen::Vector3d &start, const Eigen::Vector3d &u, double dist,
                          double tF, double t) {
  const double tau = std::min(1.0, std::max(0.0, t / tF));
  return start + u * (0.5 * dist * (1.0 - std::cos(M_PI * tau)));
}

Eigen::Vector3d LineVelocity(const Eigen::Vector3d &u, double dist, double tF, double t) {
  if (t <= 0 || t >= tF) return Eigen::Vector3d::Zero();
  return u * (0.5 * dist * M_PI / tF * std::sin(M_PI * t / tF));
}

// EE estimate and the 3×7 task Jacobian, recomputed in the test from the kinematics module:
// vehicle reference: p_EE at (0, I) [3]; barycenter: cm0 + (p_EE − p_cm)(I, q) [4].
struct Task {
  Eigen::Vector3d r;
  Eigen::Matrix<double, 3, 7> J;
};

Task EvalTask(const uvms_arm_model_t &m, uvms_arm_data_t &d, uvms_reference_t ref,
              const Eigen::Vector3d &cm0, const uvms_real_t *q) {
  const uvms_real_t origin[3] = {0, 0, 0};
  uvms_real_t I3[9];
  uvms_m3_identity(I3);
  Task t;
  REQUIRE(uvms_arm_fk(&m, &d, origin, I3, q) == UVMS_OK);
  uvms_real_t J[6 * UVMS_MAX_JOINTS], Jcm[3 * UVMS_MAX_JOINTS];
  REQUIRE(uvms_arm_jacobian(&m, &d, J) == UVMS_OK);
  REQUIRE(uvms_arm_barycenter_jacobian(&m, &d, Jcm) == UVMS_OK);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 7; ++c)
      t.J(r, c) = double(J[r * 7 + c]) - (ref == UVMS_REF_BARYCENTER ? double(Jcm[r * 7 + c]) : 0.0);
  if (ref == UVMS_REF_BARYCENTER) {
    uvms_real_t rel[3];
    REQUIRE(uvms_arm_ee_minus_barycenter(&m, &d, I3, q, rel) == UVMS_OK);
    t.r = cm0 + V(rel);
  } else {
    t.r = V(d.ee_m);
  }
  return t;
}

struct LineRun {
  Eigen::Vector3d r_start;        // EE estimate at q_start (test's own)
  double max_path_err_m = 0;      // max |r̂(q_ref(t)) − r(t)|
  double max_lateral_m = 0;       // max component of that error across the line
  double final_err_m = 0;         // |r̂ − (r_start + rΔ u)| at the last tick
  double max_qd_rad_s = 0;        // max |θ̇_ref,i|
  double max_qd_excess = 0;       // max of ‖θ̇‖ − (‖v‖/σ_min + k0‖q_start − q‖), should be ≤ 0
  double max_vehicle_frame_dev_m = 0;  // max |p_EE([3]) − r(t)|: differs from r̂ for barycenter
  bool all_ok = true, all_finite = true;
};

// Runs uvms_cart_traj_step from t = 0 every dt until t_end and measures the reference's EE
// estimate against the straight line, all recomputed here.
LineRun RunLine(const uvms_arm_model_t &m, const Joints &q0, uvms_reference_t ref, double dist,
                const Eigen::Vector3d &dir, double tF, double dt, double t_end,
                uvms_cart_traj_params_t prm) {
  static uvms_arm_data_t work, d;
  const uvms_real_t origin[3] = {0, 0, 0};
  uvms_real_t I3[9];
  uvms_m3_identity(I3);
  prm.distance_m = uvms_real_t(dist);
  Put(dir, prm.direction);
  prm.duration_s = uvms_real_t(tF);
  prm.reference = ref;
  uvms_cart_traj_t traj;
  REQUIRE(uvms_cart_traj_init(&traj, &prm, &m, &work, q0.v, origin, I3) == UVMS_OK);

  REQUIRE(uvms_arm_fk(&m, &d, origin, I3, q0.v) == UVMS_OK);
  const Eigen::Vector3d cm0 = V(d.barycenter_m);
  LineRun out;
  out.r_start = EvalTask(m, d, ref, cm0, q0.v).r;
  const Eigen::Vector3d u = dir.normalized();
  const double K = double(prm.position_gain_1_s), k0 = double(prm.nullspace_gain_1_s);
  const long steps = std::lround(t_end / dt);
  Eigen::Vector3d r_est = out.r_start;
  for (long k = 0; k <= steps; ++k) {
    const double t = double(k) * dt;
    Joints q, qd, qdd;
    if (uvms_cart_traj_step(&traj, &m, &work, uvms_real_t(t), uvms_real_t(dt), q.v, qd.v,
                            qdd.v) != UVMS_OK) {
      out.all_ok = false;
      break;
    }
    Eigen::Matrix<double, 7, 1> qdv, dq;
    for (int i = 0; i < 7; ++i) {
      out.all_finite = out.all_finite && std::isfinite(double(q.v[i])) &&
                       std::isfinite(double(qd.v[i])) && std::isfinite(double(qdd.v[i]));
      out.max_qd_rad_s = std::max(out.max_qd_rad_s, std::abs(double(qd.v[i])));
      qdv[i] = double(qd.v[i]);
      dq[i] = double(q0.v[i]) - double(q.v[i]);
    }
    const Task task = EvalTask(m, d, ref, cm0, q.v);
    r_est = task.r;
    const Eigen::Vector3d rd = LinePoint(out.r_start, u, dist, tF, t);
    const Eigen::Vector3d err = r_est - rd;
    out.max_path_err_m = std::max(out.max_path_err_m, err.norm());
    out.max_lateral_m = std::max(out.max_lateral_m, (err - err.dot(u) * u).norm());
    // DLS bound: ‖Jᵀ(JJᵀ+λ²)⁻¹ v‖ ≤ ‖v‖/σ_min and ‖(I − J⁺J) z‖ ≤ ‖z‖ (eigenvalues in [0, 1]).
    const Eigen::Vector3d v = LineVelocity(u, dist, tF, t) + K * (rd - r_est);
    const double smin = uvms_test::SvdOf(task.J).singular_values[2];
    out.max_qd_excess =
        std::max(out.max_qd_excess,
                 qdv.norm() - (v.norm() / smin + k0 * dq.norm()) * (1 + 1e-4) - 1e3 * kEps);
    if (ref == UVMS_REF_BARYCENTER) {
      const uvms_real_t o[3] = {0, 0, 0};
      REQUIRE(uvms_arm_fk(&m, &d, o, I3, q.v) == UVMS_OK);
      out.max_vehicle_frame_dev_m = std::max(out.max_vehicle_frame_dev_m, (V(d.ee_m) - rd).norm());
    }
  }
  out.final_err_m = (r_est - (out.r_start + dist * u)).norm();
  return out;
}

uvms_cart_traj_params_t DefaultParams() {
  uvms_cart_traj_params_t p;
  uvms_cart_traj_params_default(&p);
  return p;
}

}  // namespace

// =============================================================================================
// Joint cycloid (SPEC §8, corrected [69–71])

TEST_CASE("CycloidMeetsBoundaryConditionsAndHoldsOutsideItsInterval", "[trajectory][cycloid]") {
  const Joints qI = FromDeg(kThetaIDeg), qF = FromDeg(kThetaVehDeg);
  const uvms_real_t tF = 6;
  for (double t : {-1e6, -1.0, 0.0, 6.0, 6.5, 1e6}) {
    Joints q, qd, qdd;
    REQUIRE(uvms_cycloid_eval(7, qI.v, qF.v, tF, uvms_real_t(t), q.v, qd.v, qdd.v) == UVMS_OK);
    const Joints &end = (t <= 0) ? qI : qF;
    for (int i = 0; i < 7; ++i) {
      CHECK(q.v[i] == end.v[i]);  // exactly θI before/at start, exactly θF at/after tF
      CHECK(qd.v[i] == 0);
      CHECK(qdd.v[i] == 0);
    }
  }
  // Continuity at the ends: a step of δ inside moves θ by ~ (2π²/3)·Δ·(δ/tF)³ (the cycloid's
  // leading term), and θ̇ by ~ 2π²Δ·(δ/tF)²/tF: both vanish, no jump.
  const double delta = 1e-3 * 6;
  Joints q, qd, qdd;
  REQUIRE(uvms_cycloid_eval(7, qI.v, qF.v, tF, uvms_real_t(delta), q.v, qd.v, qdd.v) == UVMS_OK);
  CHECK(MaxAbsDelta(q, qI) < 1e-7 + 10 * kEps * 4);
  REQUIRE(uvms_cycloid_eval(7, qI.v, qF.v, tF, uvms_real_t(6 - delta), q.v, qd.v, qdd.v) == UVMS_OK);
  CHECK(MaxAbsDelta(q, qF) < 1e-7 + 10 * kEps * 4);
  for (int i = 0; i < 7; ++i) CHECK(std::abs(double(qd.v[i])) < 1e-4);
}

TEST_CASE("CycloidRateAndAccelerationEqualCentralDifferences", "[trajectory][cycloid]") {
  const Joints qI = FromDeg(kThetaIDeg), qF = FromDeg(kThetaVehDeg);
  double dmax = 0;  // largest |Δ| [rad] (joint 5: 193.47°)
  for (int i = 0; i < 7; ++i) dmax = std::max(dmax, std::abs(double(qF.v[i]) - double(qI.v[i])));
  std::mt19937 rng(69);
  for (double tF : {6.0, 60.0}) {  // the shortest and the paper's trajectory duration (SPEC §9)
    // Central difference error: h²/6·max|f'''| (truncation) + 2·eps·max|f|/h (rounding of f).
    // θ''' peaks at 4π²Δ/tF³, θ'''' at 8π³Δ/tF⁴; |θ| ≤ 2π·... ≤ 7 rad, |θ̇| ≤ 2Δ/tF.
    const double h = kFloat ? 3e-3 * tF : 1e-4 * tF;
    const double d3 = 4 * M_PI * M_PI * dmax / std::pow(tF, 3);
    const double d4 = 8 * std::pow(M_PI, 3) * dmax / std::pow(tF, 4);
    const double tol_qd = 2 * (h * h / 6 * d3 + 2 * kEps * 7 / h);
    const double tol_qdd = 2 * (h * h / 6 * d4 + 2 * kEps * (2 * dmax / tF) / h);
    std::uniform_real_distribution<double> ut(h, tF - h);
    double worst_qd = 0, worst_qdd = 0;
    for (int trial = 0; trial < 200; ++trial) {
      const double t = ut(rng);
      Joints q, qd, qdd, qp, qdp, qddp, qm, qdm, qddm;
      REQUIRE(uvms_cycloid_eval(7, qI.v, qF.v, uvms_real_t(tF), uvms_real_t(t), q.v, qd.v, qdd.v) == UVMS_OK);
      REQUIRE(uvms_cycloid_eval(7, qI.v, qF.v, uvms_real_t(tF), uvms_real_t(t + h), qp.v, qdp.v, qddp.v) == UVMS_OK);
      REQUIRE(uvms_cycloid_eval(7, qI.v, qF.v, uvms_real_t(tF), uvms_real_t(t - h), qm.v, qdm.v, qddm.v) == UVMS_OK);
      // Divide by the times actually evaluated (rounded to the real type).
      const double two_h = double(uvms_real_t(t + h)) - double(uvms_real_t(t - h));
      for (int i = 0; i < 7; ++i) {
        const double fd_qd = (double(qp.v[i]) - double(qm.v[i])) / two_h;
        const double fd_qdd = (double(qdp.v[i]) - double(qdm.v[i])) / two_h;
        worst_qd = std::max(worst_qd, std::abs(double(qd.v[i]) - fd_qd));
        worst_qdd = std::max(worst_qdd, std::abs(double(qdd.v[i]) - fd_qdd));
      }
    }
    INFO("tF = " << tF << " s: worst θ̇ mismatch " << worst_qd << " (tol " << tol_qd
                 << "), worst θ̈ mismatch " << worst_qdd << " (tol " << tol_qdd << ")");
    CHECK(worst_qd < tol_qd);
    CHECK(worst_qdd < tol_qdd);
  }
}

TEST_CASE("CycloidIsSymmetricWithPeakRateTwiceTheMeanRateAtHalfTime", "[trajectory][cycloid]") {
  const Joints qI = FromDeg(kThetaIDeg), qF = FromDeg(kThetaVehDeg);
  const double tF = 60;
  Joints qm, qdm, qddm;
  REQUIRE(uvms_cycloid_eval(7, qI.v, qF.v, uvms_real_t(tF), uvms_real_t(tF / 2), qm.v, qdm.v, qddm.v) == UVMS_OK);
  for (int i = 0; i < 7; ++i) {
    const double delta = double(qF.v[i]) - double(qI.v[i]);
    // θ̇(tF/2) = (Δ/tF)(1 − cos π) = 2Δ/tF; θ̈(tF/2) = 0; θ(tF/2) = (θI + θF)/2.
    CHECK(double(qdm.v[i]) == Approx(2 * delta / tF).epsilon(20 * kEps).margin(1e-300));
    CHECK(std::abs(double(qddm.v[i])) <= 20 * kEps * 2 * M_PI * std::abs(delta) / (tF * tF));
    CHECK(std::abs(double(qm.v[i]) - 0.5 * (double(qI.v[i]) + double(qF.v[i]))) < 20 * kEps * 7);
  }
  for (int k = 1; k < 300; ++k) {
    const double s = tF / 2 * k / 300.0;
    Joints qa, qda, qdda, qb, qdb, qddb;
    REQUIRE(uvms_cycloid_eval(7, qI.v, qF.v, uvms_real_t(tF), uvms_real_t(tF / 2 + s), qa.v, qda.v, qdda.v) == UVMS_OK);
    REQUIRE(uvms_cycloid_eval(7, qI.v, qF.v, uvms_real_t(tF), uvms_real_t(tF / 2 - s), qb.v, qdb.v, qddb.v) == UVMS_OK);
    for (int i = 0; i < 7; ++i) {
      const double delta = std::abs(double(qF.v[i]) - double(qI.v[i]));
      const double mid = 0.5 * (double(qI.v[i]) + double(qF.v[i]));
      // Point symmetry of θ about (tF/2, mid); θ̇ even, θ̈ odd about tF/2.
      CHECK(std::abs((double(qa.v[i]) - mid) + (double(qb.v[i]) - mid)) < 50 * kEps * 7);
      CHECK(std::abs(double(qda.v[i]) - double(qdb.v[i])) < 50 * kEps * 2 * delta / tF + 1e-300);
      CHECK(std::abs(double(qdda.v[i]) + double(qddb.v[i])) <
            50 * kEps * 2 * M_PI * delta / (tF * tF) + 1e-300);
      // The peak rate is the one at tF/2.
      CHECK(std::abs(double(qda.v[i])) <= std::abs(double(qdm.v[i])) * (1 + 20 * kEps));
    }
  }
}

// =============================================================================================
// Joint servo (SPEC §8)

TEST_CASE("JointServoIsTheSpec8ControlLaw", "[trajectory][servo]") {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int trial = 0; trial < 50; ++trial) {
    Joints qr, qdr, qddr, q, qd, cmd;
    for (int i = 0; i < 7; ++i) {
      qr.v[i] = uvms_real_t(u(rng));
      qdr.v[i] = uvms_real_t(u(rng));
      qddr.v[i] = uvms_real_t(u(rng));
      q.v[i] = uvms_real_t(u(rng));
      qd.v[i] = uvms_real_t(u(rng));
    }
    const double kq = 100 * (1 + u(rng) / 4), kqd = 20 * (1 + u(rng) / 4);
    REQUIRE(uvms_joint_servo(7, qr.v, qdr.v, qddr.v, q.v, qd.v, uvms_real_t(kq), uvms_real_t(kqd),
                             cmd.v) == UVMS_OK);
    for (int i = 0; i < 7; ++i) {
      const double want = double(qddr.v[i]) + double(uvms_real_t(kq)) * (double(qr.v[i]) - double(q.v[i])) +
                          double(uvms_real_t(kqd)) * (double(qdr.v[i]) - double(qd.v[i]));
      // Terms up to ~125·6 = 750 rad/s², a few roundings each.
      CHECK(std::abs(double(cmd.v[i]) - want) < 8 * kEps * 1000);
    }
  }
}

TEST_CASE("JointServoWithDefaultGainsTracksCycloidOnADoubleIntegrator", "[trajectory][servo]") {
  // Gains: ωn = 10 rad/s, ζ = 1 (Kq = ωn², Kqd = 2ζωn), UVMS_JOINT_SERVO_*_DEFAULT.
  const double kq = double(UVMS_JOINT_SERVO_KQ_DEFAULT_1_S2);
  const double kqd = double(UVMS_JOINT_SERVO_KQD_DEFAULT_1_S);
  CHECK(kq == Approx(10.0 * 10.0));
  CHECK(kqd == Approx(2 * 1.0 * 10.0));
  const Joints qI = FromDeg(kThetaIDeg), qF = FromDeg(kThetaVehDeg);
  const double tF = 6, dt = 0.03;  // the shortest duration of SPEC §9 at the controller tick
  double dmax = 0;
  for (int i = 0; i < 7; ++i) dmax = std::max(dmax, std::abs(double(qF.v[i]) - double(qI.v[i])));
  // The plant integrates θ̈_cmd held over each tick (zero-order hold), exactly. The held θ̈_ref
  // differs from the true one by up to max|θ⃛|·dt (θ⃛ peaks at 4π²Δ/tF³); the loop turns an
  // acceleration error a into a position error ≈ a/Kq. Bound: max|θ⃛|·dt/Kq, doubled.
  // Without the feed-forward θ̈_ref the error would be ≈ max|θ̈|/Kq = 2πΔ/(tF²·Kq), 30 times
  // larger than this bound, so the check fails if the feed-forward is lost.
  const double jerk = 4 * M_PI * M_PI * dmax / std::pow(tF, 3);
  const double bound = 2 * jerk * dt / kq;
  const double no_ff_error = 2 * M_PI * dmax / (tF * tF) / kq;
  REQUIRE(bound < no_ff_error / 10);

  for (double offset : {0.0, 0.01}) {  // start on the reference, or 0.01 rad off on every joint
    double q[7], qd[7];
    for (int i = 0; i < 7; ++i) {
      q[i] = double(qI.v[i]) + offset;
      qd[i] = 0;
    }
    double max_err = 0, err_after_1s = 0;
    const int steps = int(std::lround((tF + 1) / dt));
    for (int k = 0; k <= steps; ++k) {
      const double t = k * dt;
      Joints qr, qdr, qddr, qm, qdm, cmd;
      REQUIRE(uvms_cycloid_eval(7, qI.v, qF.v, uvms_real_t(tF), uvms_real_t(t), qr.v, qdr.v, qddr.v) == UVMS_OK);
      for (int i = 0; i < 7; ++i) {
        qm.v[i] = uvms_real_t(q[i]);
        qdm.v[i] = uvms_real_t(qd[i]);
        const double e = std::abs(q[i] - double(qr.v[i]));
        if (t >= 1.0) err_after_1s = std::max(err_after_1s, e);
        max_err = std::max(max_err, e);
      }
      REQUIRE(uvms_joint_servo(7, qr.v, qdr.v, qddr.v, qm.v, qdm.v, UVMS_JOINT_SERVO_KQ_DEFAULT_1_S2,
                               UVMS_JOINT_SERVO_KQD_DEFAULT_1_S, cmd.v) == UVMS_OK);
      for (int i = 0; i < 7; ++i) {
        const double a = double(cmd.v[i]);
        q[i] += qd[i] * dt + 0.5 * a * dt * dt;
        qd[i] += a * dt;
      }
    }
    INFO("offset " << offset << " rad: max error " << max_err << " rad, after 1 s "
                   << err_after_1s << " rad, bound " << bound << " rad");
    if (offset == 0.0) {
      CHECK(max_err < bound + 10 * kEps * 7);
    } else {
      // Critically damped: e(t) = e0·(1 + ωn t)·e^(−ωn t) = 5e-4·e0 at 1 s; sampling slows it
      // slightly (discrete poles 0.80 and 0.56 per tick vs e^(−0.3) = 0.74), so 10× margin.
      CHECK(err_after_1s < bound + 10 * 5e-4 * offset);
      CHECK(max_err <= offset * (1 + 1e-6) + bound);  // no growth beyond the initial error
    }
  }
}

// =============================================================================================
// Cosine line profile [78]

TEST_CASE("CosineLineStartsAndEndsAtRestOnTheLine", "[trajectory][line]") {
  const uvms_real_t start[3] = {0.7f, -0.2f, uvms_real_t(0.3)};
  const uvms_real_t dir[3] = {3, 4, 0};  // not unit: normalised to (0.6, 0.8, 0)
  const double dist = 0.5, tF = 10;
  for (double t : {-5.0, 0.0, 10.0, 12.0}) {
    uvms_real_t r[3], v[3], a[3];
    REQUIRE(uvms_cosine_line_eval(start, dir, uvms_real_t(dist), uvms_real_t(tF), uvms_real_t(t), r, v, a) == UVMS_OK);
    const Eigen::Vector3d want = V(start) + (t <= 0 ? 0.0 : dist) * Eigen::Vector3d(0.6, 0.8, 0);
    CHECK((V(r) - want).norm() < 10 * kEps * 4);
    CHECK(V(v).norm() == 0);
    CHECK(V(a).norm() == 0);
  }
  // Mid-way: half the distance at the peak speed π·rΔ/(2tF), zero acceleration.
  uvms_real_t r[3], v[3], a[3];
  REQUIRE(uvms_cosine_line_eval(start, dir, uvms_real_t(dist), uvms_real_t(tF), uvms_real_t(tF / 2), r, v, a) == UVMS_OK);
  CHECK((V(r) - (V(start) + dist / 2 * Eigen::Vector3d(0.6, 0.8, 0))).norm() < 10 * kEps * 4);
  CHECK((V(v) - M_PI * dist / (2 * tF) * Eigen::Vector3d(0.6, 0.8, 0)).norm() < 10 * kEps);
  CHECK(V(a).norm() < 10 * kEps * M_PI * M_PI * dist / (2 * tF * tF));
}

TEST_CASE("CosineLineVelocityAndAccelerationEqualCentralDifferences", "[trajectory][line]") {
  const uvms_real_t start[3] = {0.724f, 0, 0.242f};
  const uvms_real_t dir[3] = {1, 0, 0};
  const double dist = 0.3, tF = 10;
  // Central differences: h²/6·max|f'''| + 2·eps·max|f|/h; r''' ≤ π³rΔ/(2tF³), r'''' ≤ π⁴rΔ/(2tF⁴).
  const double h = kFloat ? 2e-2 : 1e-4;
  const double tol_v = 2 * (h * h / 6 * std::pow(M_PI, 3) * dist / (2 * std::pow(tF, 3)) + 2 * kEps * 1.1 / h);
  const double tol_a = 2 * (h * h / 6 * std::pow(M_PI, 4) * dist / (2 * std::pow(tF, 4)) +
                            2 * kEps * (M_PI * dist / (2 * tF)) / h);
  std::mt19937 rng(78);
  std::uniform_real_distribution<double> ut(h, tF - h);  // the profile is C¹ only at the ends
  double worst_v = 0, worst_a = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double t = ut(rng);
    uvms_real_t r[3], v[3], a[3], rp[3], vp[3], ap[3], rm[3], vm[3], am[3];
    REQUIRE(uvms_cosine_line_eval(start, dir, uvms_real_t(dist), uvms_real_t(tF), uvms_real_t(t), r, v, a) == UVMS_OK);
    REQUIRE(uvms_cosine_line_eval(start, dir, uvms_real_t(dist), uvms_real_t(tF), uvms_real_t(t + h), rp, vp, ap) == UVMS_OK);
    REQUIRE(uvms_cosine_line_eval(start, dir, uvms_real_t(dist), uvms_real_t(tF), uvms_real_t(t - h), rm, vm, am) == UVMS_OK);
    const double two_h = double(uvms_real_t(t + h)) - double(uvms_real_t(t - h));
    worst_v = std::max(worst_v, (V(v) - (V(rp) - V(rm)) / two_h).norm());
    worst_a = std::max(worst_a, (V(a) - (V(vp) - V(vm)) / two_h).norm());
  }
  INFO("worst velocity mismatch " << worst_v << " (tol " << tol_v << "), acceleration "
                                  << worst_a << " (tol " << tol_a << ")");
  CHECK(worst_v < tol_v);
  CHECK(worst_a < tol_a);
}

// =============================================================================================
// Cartesian straight line by resolved-rate DLS IK (SPEC §8)
//
// Start pose θI (stowed) with the vehicle at the origin, identity attitude. The line runs
// along −x: along +x it leaves the workspace after about 2 cm (see
// StraightPlusXLineFromStowedPoseIsUnreachableAndTheRateLimitHolds), so no IK can follow it.

TEST_CASE("VehicleReferenceLineKeepsTheEeOnTheLineWithinOneMillimetre", "[trajectory][cartesian]") {
  const auto m = PaperModel();
  const double tol = 1e-3;  // [m]
  const LineRun run = RunLine(m, FromDeg(kThetaIDeg), UVMS_REF_VEHICLE, 0.3,
                              Eigen::Vector3d(-1, 0, 0), 10, 0.03, 11, DefaultParams());
  std::printf("Cartesian line, vehicle reference, θI, 0.3 m along −x in 10 s: max path error "
              "%.3e m, lateral %.3e m, final %.3e m, max |θ̇| %.3f rad/s\n",
              run.max_path_err_m, run.max_lateral_m, run.final_err_m, run.max_qd_rad_s);
  CHECK(run.all_ok);
  CHECK(run.all_finite);
  CHECK(run.max_path_err_m < tol);
  CHECK(run.max_lateral_m < tol);
  CHECK(run.final_err_m < tol);
  CHECK(run.max_qd_excess <= 0);
  // The rate limit (1 rad/s) stayed inactive: peak line speed 0.047 m/s over σ_min ≈ 0.1 m/rad.
  CHECK(run.max_qd_rad_s < 0.5);
}

TEST_CASE("BarycenterReferenceLineKeepsTheVirtualManipulatorEstimateOnTheLine", "[trajectory][cartesian]") {
  const auto m = PaperModel();
  const double tol = 1e-3;  // [m]
  const LineRun run = RunLine(m, FromDeg(kThetaIDeg), UVMS_REF_BARYCENTER, 0.3,
                              Eigen::Vector3d(-1, 0, 0), 10, 0.03, 11, DefaultParams());
  std::printf("Cartesian line, barycenter reference, θI, 0.3 m along −x in 10 s: max path error "
              "%.3e m, lateral %.3e m, final %.3e m, max |θ̇| %.3f rad/s; EE by [3] with the "
              "vehicle held deviates up to %.3e m\n",
              run.max_path_err_m, run.max_lateral_m, run.final_err_m, run.max_qd_rad_s,
              run.max_vehicle_frame_dev_m);
  CHECK(run.all_ok);
  CHECK(run.all_finite);
  CHECK(run.max_path_err_m < tol);  // estimate [4]: barycenter0 + (p_EE − p_cm)(R0d, q)
  CHECK(run.max_lateral_m < tol);
  CHECK(run.final_err_m < tol);
  CHECK(run.max_qd_excess <= 0);
  CHECK(run.max_qd_rad_s < 0.5);
  // The two references really differ: moving the arm moves the barycenter (≈ 20 kg of arm and
  // payload of 149 kg total over 0.3 m: centimetres), so the same joint motion judged by [3]
  // with the vehicle held is far off the line. A module that ignored the reference fails above.
  CHECK(run.max_vehicle_frame_dev_m > 10 * tol);
}

TEST_CASE("SixtySecondOneMetreLineStaysAccurateAtTheControllerTick", "[trajectory][cartesian]") {
  // The travel experiment's longest line (SPEC §9.5: up to 1 m, 60 s run, 0.03 s tick), from
  // the sampling pose (SPEC §8 "Veh." column, EE at x ≈ 1.51 m) back along −x.
  const auto m = PaperModel();
  for (uvms_reference_t ref : {UVMS_REF_VEHICLE, UVMS_REF_BARYCENTER}) {
    const LineRun run = RunLine(m, FromDeg(kThetaVehDeg), ref, 1.0, Eigen::Vector3d(-1, 0, 0),
                                60, 0.03, 61, DefaultParams());
    std::printf("Cartesian line, %s reference, sampling pose, 1.0 m along −x in 60 s: max path "
                "error %.3e m, lateral %.3e m, final %.3e m, max |θ̇| %.3f rad/s\n",
                ref == UVMS_REF_VEHICLE ? "vehicle" : "barycenter", run.max_path_err_m,
                run.max_lateral_m, run.final_err_m, run.max_qd_rad_s);
    CHECK(run.all_ok);
    CHECK(run.all_finite);
    CHECK(run.max_path_err_m < 1e-3);
    CHECK(run.max_lateral_m < 1e-3);
    CHECK(run.final_err_m < 1e-3);
    CHECK(run.max_qd_excess <= 0);
  }
}

TEST_CASE("NullSpaceTermDoesNotChangeTheEeVelocity", "[trajectory][cartesian]") {
  const auto m = PaperModel();
  static uvms_arm_data_t work, d;
  const uvms_real_t origin[3] = {0, 0, 0};
  uvms_real_t I3[9];
  uvms_m3_identity(I3);
  const Joints q0 = FromDeg(kThetaVehDeg);  // all seven joints take part from this pose
  for (uvms_reference_t ref : {UVMS_REF_VEHICLE, UVMS_REF_BARYCENTER}) {
    uvms_cart_traj_params_t p = DefaultParams();
    p.distance_m = 0.3;
    p.duration_s = 10;
    uvms_v3_set(p.direction, -1, 0, 0);
    p.reference = ref;
    uvms_cart_traj_t traj;
    REQUIRE(uvms_cart_traj_init(&traj, &p, &m, &work, q0.v, origin, I3) == UVMS_OK);
    // Run to mid-way so that q_ref has left q_start and the null-space pull z is non-zero.
    Joints q, qd, qdd;
    for (int k = 0; k <= 166; ++k)
      REQUIRE(uvms_cart_traj_step(&traj, &m, &work, uvms_real_t(k * 0.03), uvms_real_t(0.03), q.v, qd.v, qdd.v) == UVMS_OK);
    const uvms_real_t t = uvms_real_t(167 * 0.03);
    uvms_cart_traj_t no_null = traj;  // the same state, configured without the null-space term
    no_null.p.nullspace_gain_1_s = 0;
    Joints with, without;
    REQUIRE(uvms_cart_traj_rate(&traj, &m, &work, t, traj.q_ref_rad, with.v, nullptr) == UVMS_OK);
    REQUIRE(uvms_cart_traj_rate(&no_null, &m, &work, t, traj.q_ref_rad, without.v, nullptr) == UVMS_OK);

    // Task Jacobian at q_ref (only J is used here, so the barycenter origin is irrelevant).
    const Task task = EvalTask(m, d, ref, Eigen::Vector3d::Zero(), traj.q_ref_rad);
    Eigen::Matrix<double, 7, 1> dqd, z;
    for (int i = 0; i < 7; ++i) {
      dqd[i] = double(with.v[i]) - double(without.v[i]);
      z[i] = double(p.nullspace_gain_1_s) * (double(q0.v[i]) - double(traj.q_ref_rad[i]));
    }
    // Independent DLS projector (Eigen, double): (I − J⁺J)z with J⁺ = Jᵀ(JJᵀ + λ²I)⁻¹.
    const double lam = double(p.damping_m);
    const Eigen::Matrix3d A = task.J * task.J.transpose() + lam * lam * Eigen::Matrix3d::Identity();
    const Eigen::Matrix<double, 7, 1> Pz = z - task.J.transpose() * A.ldlt().solve(task.J * z);
    const double smin = uvms_test::SvdOf(task.J).singular_values[2];
    const double leak_bound = lam * lam / (smin * smin + lam * lam) * (task.J * z).norm();
    INFO("reference " << int(ref) << ": |Δθ̇| = " << dqd.norm() << " rad/s, |J·Δθ̇| = "
                      << (task.J * dqd).norm() << " m/s, |J·z| = " << (task.J * z).norm()
                      << " m/s, DLS leak bound " << leak_bound << " m/s");
    REQUIRE(z.norm() > 1e-2);               // the term is active: not a vacuous check
    CHECK(dqd.norm() > 1e-3);
    CHECK((dqd - Pz).norm() < (kFloat ? 1e-4 : 1e-10) * (1 + z.norm()));
    // EE velocity from the null-space term: only the DLS leak λ²(JJᵀ+λ²I)⁻¹Jz remains.
    CHECK((task.J * dqd).norm() <= leak_bound * 1.01 + (kFloat ? 1e-5 : 1e-12));
    CHECK((task.J * dqd).norm() < 0.05 * (task.J * z).norm());
  }
}

TEST_CASE("EmittedReferenceIsConstantAccelerationMotionOverEachTick", "[trajectory][cartesian]") {
  const auto m = PaperModel();
  static uvms_arm_data_t work;
  const uvms_real_t origin[3] = {0, 0, 0};
  uvms_real_t I3[9];
  uvms_m3_identity(I3);
  const Joints q0 = FromDeg(kThetaIDeg);
  uvms_cart_traj_params_t p = DefaultParams();
  p.distance_m = 0.3;
  p.duration_s = 10;
  uvms_v3_set(p.direction, -1, 0, 0);
  uvms_cart_traj_t traj;
  REQUIRE(uvms_cart_traj_init(&traj, &p, &m, &work, q0.v, origin, I3) == UVMS_OK);
  const double dt = 0.03;
  Joints q, qd, qdd;
  // First tick: the start pose at rest (t = 0 output belongs to t = 0).
  REQUIRE(uvms_cart_traj_step(&traj, &m, &work, 0, uvms_real_t(dt), q.v, qd.v, qdd.v) == UVMS_OK);
  for (int i = 0; i < 7; ++i) {
    CHECK(q.v[i] == q0.v[i]);
    CHECK(std::abs(double(qd.v[i])) < 100 * kEps);
  }
  CHECK(std::abs(double(traj.t_state_s) - dt) < 10 * kEps);
  double worst_pos = 0, worst_rate = 0, max_qdd = 0;
  for (int k = 1; k < 340; ++k) {
    Joints qn, qdn, qddn;
    REQUIRE(uvms_cart_traj_step(&traj, &m, &work, uvms_real_t(k * dt), uvms_real_t(dt), qn.v, qdn.v, qddn.v) == UVMS_OK);
    for (int i = 0; i < 7; ++i) {
      // Heun's update is exactly θ + θ̇·dt + θ̈·dt²/2 with the emitted θ̇, θ̈.
      const double pred = double(q.v[i]) + double(qd.v[i]) * dt + 0.5 * double(qdd.v[i]) * dt * dt;
      worst_pos = std::max(worst_pos, std::abs(double(qn.v[i]) - pred));
      // The next rate differs from θ̇ + θ̈·dt only by f's change between predictor and
      // corrector, |∂f/∂θ|·θ̈·dt²/2 with |∂f/∂θ| ≈ max(K, k0) = 5 1/s (and rounding).
      worst_rate = std::max(worst_rate, std::abs(double(qdn.v[i]) - (double(qd.v[i]) + double(qdd.v[i]) * dt)));
      max_qdd = std::max(max_qdd, std::abs(double(qdd.v[i])));
    }
    q = qn;
    qd = qdn;
    qdd = qddn;
  }
  INFO("worst position mismatch " << worst_pos << " rad, rate mismatch " << worst_rate
                                  << " rad/s, max |θ̈| " << max_qdd << " rad/s²");
  CHECK(worst_pos < 50 * kEps * 7);
  CHECK(worst_rate < 2 * 5.0 * max_qdd * dt * dt / 2 + 1e4 * kEps);
}

TEST_CASE("StraightPlusXLineFromStowedPoseIsUnreachableAndTheRateLimitHolds", "[trajectory][cartesian]") {
  // Joints 1–3 intersect at the shoulder p2, so |p_EE − p2| depends on θ4…θ7 only and by the
  // triangle inequality is ≥ |l3| − |l4| − (|l5| + |l6| + |l7|) = 0.552 − 0.045 − 0.36 m =
  // 0.147 m. From θI the EE sits 0.09 m above the shoulder and 0.19 m behind it; the line's
  // end 0.3 m along +x is 0.142 m from the shoulder: unreachable for any joint angles.
  const auto m = PaperModel();
  static uvms_arm_data_t d;
  const uvms_real_t origin[3] = {0, 0, 0};
  uvms_real_t I3[9];
  uvms_m3_identity(I3);
  const Joints q0 = FromDeg(kThetaIDeg);
  REQUIRE(uvms_arm_fk(&m, &d, origin, I3, q0.v) == UVMS_OK);
  const Eigen::Vector3d shoulder = V(d.p_m[2]);
  const Eigen::Vector3d end = V(d.ee_m) + Eigen::Vector3d(0.3, 0, 0);
  const double min_reach = double(m.length_m[3]) - double(m.length_m[4]) -
                           (double(m.length_m[5]) + double(m.length_m[6]) + double(m.length_m[7]));
  INFO("end point " << (end - shoulder).norm() << " m from the shoulder, minimum reach " << min_reach << " m");
  REQUIRE((end - shoulder).norm() < min_reach);

  // Asked anyway, the module must stay safe: OK status, finite output, every joint rate within
  // the configured limit (undamped by the limit, DLS alone reaches ~20 rad/s here).
  const uvms_cart_traj_params_t p = DefaultParams();
  const LineRun run = RunLine(m, q0, UVMS_REF_VEHICLE, 0.3, Eigen::Vector3d(1, 0, 0), 10, 0.03, 11, p);
  std::printf("Unreachable +x line from θI: max |θ̇| %.3f rad/s (limit %.1f), final miss %.3f m\n",
              run.max_qd_rad_s, double(p.max_joint_rate_rad_s), run.final_err_m);
  CHECK(run.all_ok);
  CHECK(run.all_finite);
  CHECK(run.max_qd_rad_s <= double(p.max_joint_rate_rad_s) * (1 + 10 * kEps));
  CHECK(run.final_err_m > min_reach - (end - shoulder).norm());
}

// =============================================================================================
// Bad input: each gives its status and the documented safe output.

TEST_CASE("CycloidRejectsBadInputAndHoldsTheStart", "[trajectory][cycloid][errors]") {
  const Joints qI = FromDeg(kThetaIDeg), qF = FromDeg(kThetaVehDeg);
  auto check_hold = [&](const Joints &q, const Joints &qd, const Joints &qdd, const Joints &start) {
    for (int i = 0; i < 7; ++i) {
      CHECK(q.v[i] == (std::isfinite(double(start.v[i])) ? start.v[i] : 0));
      CHECK(qd.v[i] == 0);
      CHECK(qdd.v[i] == 0);
    }
  };
  Joints q, qd, qdd;
  const uvms_real_t nan = uvms_real_t(NAN), inf = uvms_real_t(INFINITY);
  CHECK(uvms_cycloid_eval(7, qI.v, qF.v, 6, nan, q.v, qd.v, qdd.v) == UVMS_ERR_NONFINITE);
  check_hold(q, qd, qdd, qI);
  CHECK(uvms_cycloid_eval(7, qI.v, qF.v, inf, 1, q.v, qd.v, qdd.v) == UVMS_ERR_NONFINITE);
  check_hold(q, qd, qdd, qI);
  Joints badF = qF;
  badF.v[3] = nan;
  CHECK(uvms_cycloid_eval(7, qI.v, badF.v, 6, 1, q.v, qd.v, qdd.v) == UVMS_ERR_NONFINITE);
  check_hold(q, qd, qdd, qI);
  Joints badI = qI;
  badI.v[2] = inf;
  CHECK(uvms_cycloid_eval(7, badI.v, qF.v, 6, 1, q.v, qd.v, qdd.v) == UVMS_ERR_NONFINITE);
  check_hold(q, qd, qdd, badI);  // the bad joint reads 0, the others hold θI
  for (uvms_real_t tF : {uvms_real_t(0), uvms_real_t(-6)}) {
    CHECK(uvms_cycloid_eval(7, qI.v, qF.v, tF, 1, q.v, qd.v, qdd.v) == UVMS_ERR_RANGE);
    check_hold(q, qd, qdd, qI);
  }
  // n = 0: nothing to write (the outputs are untouched); n too large: SIZE, first 7 held.
  Joints sentinel;
  for (auto &x : sentinel.v) x = 42;
  Joints a = sentinel, b = sentinel, c = sentinel;
  CHECK(uvms_cycloid_eval(0, qI.v, qF.v, 6, 1, a.v, b.v, c.v) == UVMS_ERR_SIZE);
  for (int i = 0; i < 7; ++i) CHECK((a.v[i] == 42 && b.v[i] == 42 && c.v[i] == 42));
  uvms_real_t big_q[UVMS_MAX_JOINTS + 1], big_qd[UVMS_MAX_JOINTS + 1], big_qdd[UVMS_MAX_JOINTS + 1];
  uvms_real_t big_I[UVMS_MAX_JOINTS + 1] = {}, big_F[UVMS_MAX_JOINTS + 1] = {};
  CHECK(uvms_cycloid_eval(UVMS_MAX_JOINTS + 1, big_I, big_F, 6, 1, big_q, big_qd, big_qdd) == UVMS_ERR_SIZE);
  CHECK(uvms_cycloid_eval(7, nullptr, qF.v, 6, 1, q.v, qd.v, qdd.v) == UVMS_ERR_ARG);
  for (int i = 0; i < 7; ++i) CHECK((q.v[i] == 0 && qd.v[i] == 0 && qdd.v[i] == 0));
  CHECK(uvms_cycloid_eval(7, qI.v, qF.v, 6, 1, nullptr, qd.v, qdd.v) == UVMS_ERR_ARG);
}

TEST_CASE("JointServoRejectsBadInputWithZeroOrFeedForwardOutput", "[trajectory][servo][errors]") {
  Joints qr, qdr, qddr, q, qd, cmd;
  for (int i = 0; i < 7; ++i) {
    qr.v[i] = uvms_real_t(0.1 * i);
    qdr.v[i] = uvms_real_t(0.01 * i);
    qddr.v[i] = uvms_real_t(0.5 + i);
    q.v[i] = uvms_real_t(0.1 * i - 0.02);
    qd.v[i] = 0;
  }
  const uvms_real_t nan = uvms_real_t(NAN);
  const uvms_real_t kq = UVMS_JOINT_SERVO_KQ_DEFAULT_1_S2, kqd = UVMS_JOINT_SERVO_KQD_DEFAULT_1_S;
  // Corrupt measurement: feed-forward only.
  for (int which = 0; which < 2; ++which) {
    Joints qb = q, qdb = qd;
    (which == 0 ? qb : qdb).v[4] = nan;
    CHECK(uvms_joint_servo(7, qr.v, qdr.v, qddr.v, qb.v, qdb.v, kq, kqd, cmd.v) == UVMS_ERR_NONFINITE);
    for (int i = 0; i < 7; ++i) CHECK(cmd.v[i] == qddr.v[i]);
  }
  auto all_zero = [&] {
    for (int i = 0; i < 7; ++i) CHECK(cmd.v[i] == 0);
  };
  Joints bad = qddr;
  bad.v[0] = nan;
  CHECK(uvms_joint_servo(7, qr.v, qdr.v, bad.v, q.v, qd.v, kq, kqd, cmd.v) == UVMS_ERR_NONFINITE);
  all_zero();
  CHECK(uvms_joint_servo(7, qr.v, qdr.v, qddr.v, q.v, qd.v, nan, kqd, cmd.v) == UVMS_ERR_NONFINITE);
  all_zero();
  CHECK(uvms_joint_servo(7, qr.v, qdr.v, qddr.v, q.v, qd.v, kq, -1, cmd.v) == UVMS_ERR_RANGE);
  all_zero();
  CHECK(uvms_joint_servo(7, nullptr, qdr.v, qddr.v, q.v, qd.v, kq, kqd, cmd.v) == UVMS_ERR_ARG);
  all_zero();
  Joints sentinel;
  for (auto &x : sentinel.v) x = 42;
  CHECK(uvms_joint_servo(0, qr.v, qdr.v, qddr.v, q.v, qd.v, kq, kqd, sentinel.v) == UVMS_ERR_SIZE);
  for (int i = 0; i < 7; ++i) CHECK(sentinel.v[i] == 42);  // n = 0: nothing written
}

TEST_CASE("CosineLineRejectsBadInputAndHoldsTheStart", "[trajectory][line][errors]") {
  const uvms_real_t start[3] = {1, 2, 3}, dir[3] = {1, 0, 0}, zero_dir[3] = {0, 0, 0};
  const uvms_real_t nan = uvms_real_t(NAN);
  uvms_real_t r[3], v[3], a[3];
  auto check_hold = [&] {
    CHECK((V(r) - V(start)).norm() == 0);
    CHECK(V(v).norm() == 0);
    CHECK(V(a).norm() == 0);
  };
  CHECK(uvms_cosine_line_eval(start, dir, uvms_real_t(0.3), 10, nan, r, v, a) == UVMS_ERR_NONFINITE);
  check_hold();
  CHECK(uvms_cosine_line_eval(start, dir, nan, 10, 1, r, v, a) == UVMS_ERR_NONFINITE);
  check_hold();
  CHECK(uvms_cosine_line_eval(start, dir, uvms_real_t(0.3), 0, 1, r, v, a) == UVMS_ERR_RANGE);
  check_hold();
  CHECK(uvms_cosine_line_eval(start, dir, uvms_real_t(0.3), -1, 1, r, v, a) == UVMS_ERR_RANGE);
  check_hold();
  CHECK(uvms_cosine_line_eval(start, zero_dir, uvms_real_t(0.3), 10, 1, r, v, a) == UVMS_ERR_RANGE);
  check_hold();
  CHECK(uvms_cosine_line_eval(nullptr, dir, uvms_real_t(0.3), 10, 1, r, v, a) == UVMS_ERR_ARG);
  CHECK(V(r).norm() == 0);
}

TEST_CASE("CartesianInitRejectsBadParametersAndLeavesNotReady", "[trajectory][cartesian][errors]") {
  const auto m = PaperModel();
  static uvms_arm_data_t work;
  const uvms_real_t origin[3] = {0, 0, 0};
  uvms_real_t I3[9];
  uvms_m3_identity(I3);
  const Joints q0 = FromDeg(kThetaIDeg);
  uvms_cart_traj_t traj;
  auto expect = [&](uvms_status_t want, auto mutate) {
    uvms_cart_traj_params_t p = DefaultParams();
    mutate(p);
    std::memset(&traj, 0x5a, sizeof traj);
    CHECK(uvms_cart_traj_init(&traj, &p, &m, &work, q0.v, origin, I3) == want);
    CHECK(traj.ready == 0);
    CHECK(traj.n == 0);
    CHECK(traj.q_ref_rad[0] == 0);
  };
  expect(UVMS_ERR_NONFINITE, [](uvms_cart_traj_params_t &p) { p.direction[1] = uvms_real_t(NAN); });
  expect(UVMS_ERR_NONFINITE, [](uvms_cart_traj_params_t &p) { p.distance_m = uvms_real_t(INFINITY); });
  expect(UVMS_ERR_RANGE, [](uvms_cart_traj_params_t &p) { p.duration_s = 0; });
  expect(UVMS_ERR_RANGE, [](uvms_cart_traj_params_t &p) { p.duration_s = -60; });
  expect(UVMS_ERR_RANGE, [](uvms_cart_traj_params_t &p) { p.damping_m = 0; });
  expect(UVMS_ERR_RANGE, [](uvms_cart_traj_params_t &p) { p.position_gain_1_s = -1; });
  expect(UVMS_ERR_RANGE, [](uvms_cart_traj_params_t &p) { p.max_joint_rate_rad_s = 0; });
  expect(UVMS_ERR_RANGE, [](uvms_cart_traj_params_t &p) { uvms_v3_set(p.direction, 0, 0, 0); });
  expect(UVMS_ERR_RANGE, [](uvms_cart_traj_params_t &p) { p.reference = static_cast<uvms_reference_t>(7); });

  uvms_cart_traj_params_t p = DefaultParams();
  Joints bad = q0;
  bad.v[6] = uvms_real_t(NAN);
  CHECK(uvms_cart_traj_init(&traj, &p, &m, &work, bad.v, origin, I3) == UVMS_ERR_NONFINITE);
  CHECK(traj.ready == 0);
  uvms_arm_model_t not_ready;
  std::memset(&not_ready, 0, sizeof not_ready);
  CHECK(uvms_cart_traj_init(&traj, &p, &not_ready, &work, q0.v, origin, I3) == UVMS_ERR_STATE);
  CHECK(traj.ready == 0);
  CHECK(uvms_cart_traj_init(&traj, nullptr, &m, &work, q0.v, origin, I3) == UVMS_ERR_ARG);
  CHECK(traj.ready == 0);

  // Re-initialising from the instance's own fields is allowed (inputs are copied first), and
  // the direction is stored normalised.
  uvms_v3_set(p.direction, -2, 0, 0);
  REQUIRE(uvms_cart_traj_init(&traj, &p, &m, &work, q0.v, origin, I3) == UVMS_OK);
  CHECK(double(traj.p.direction[0]) == Approx(-1.0));
  REQUIRE(uvms_cart_traj_init(&traj, &traj.p, &m, &work, traj.q_start_rad, traj.r0d_m, traj.R0d) == UVMS_OK);
  CHECK(traj.ready == 1);
  CHECK(double(traj.p.duration_s) == Approx(60.0));
  for (int i = 0; i < 7; ++i) CHECK(traj.q_start_rad[i] == q0.v[i]);
}

TEST_CASE("CartesianStepRejectsBadInputAndHoldsTheReference", "[trajectory][cartesian][errors]") {
  const auto m = PaperModel();
  static uvms_arm_data_t work;
  const uvms_real_t origin[3] = {0, 0, 0};
  uvms_real_t I3[9];
  uvms_m3_identity(I3);
  const Joints q0 = FromDeg(kThetaIDeg);
  uvms_cart_traj_params_t p = DefaultParams();
  uvms_v3_set(p.direction, -1, 0, 0);
  p.duration_s = 10;
  Joints q, qd, qdd;

  // Not initialised: STATE, all outputs zero.
  uvms_cart_traj_t traj;
  std::memset(&traj, 0, sizeof traj);
  CHECK(uvms_cart_traj_step(&traj, &m, &work, 0, uvms_real_t(0.03), q.v, qd.v, qdd.v) == UVMS_ERR_STATE);
  for (int i = 0; i < 7; ++i) CHECK((q.v[i] == 0 && qd.v[i] == 0 && qdd.v[i] == 0));

  REQUIRE(uvms_cart_traj_init(&traj, &p, &m, &work, q0.v, origin, I3) == UVMS_OK);
  for (int k = 0; k < 100; ++k)
    REQUIRE(uvms_cart_traj_step(&traj, &m, &work, uvms_real_t(k * 0.03), uvms_real_t(0.03), q.v, qd.v, qdd.v) == UVMS_OK);
  const uvms_cart_traj_t before = traj;
  auto check_hold = [&] {
    for (int i = 0; i < 7; ++i) {
      CHECK(q.v[i] == before.q_ref_rad[i]);
      CHECK(qd.v[i] == 0);
      CHECK(qdd.v[i] == 0);
      CHECK(traj.q_ref_rad[i] == before.q_ref_rad[i]);  // state not advanced
    }
    CHECK(traj.t_state_s == before.t_state_s);
  };
  const uvms_real_t t = uvms_real_t(100 * 0.03);
  CHECK(uvms_cart_traj_step(&traj, &m, &work, t, 0, q.v, qd.v, qdd.v) == UVMS_ERR_RANGE);
  check_hold();
  CHECK(uvms_cart_traj_step(&traj, &m, &work, t, -uvms_real_t(0.03), q.v, qd.v, qdd.v) == UVMS_ERR_RANGE);
  check_hold();
  // K·dt = 5·0.3 = 1.5 > UVMS_CART_TRAJ_MAX_GAIN_DT.
  CHECK(uvms_cart_traj_step(&traj, &m, &work, t, uvms_real_t(0.3), q.v, qd.v, qdd.v) == UVMS_ERR_RANGE);
  check_hold();
  CHECK(uvms_cart_traj_step(&traj, &m, &work, uvms_real_t(NAN), uvms_real_t(0.03), q.v, qd.v, qdd.v) == UVMS_ERR_NONFINITE);
  check_hold();
  CHECK(uvms_cart_traj_step(&traj, &m, &work, t, uvms_real_t(INFINITY), q.v, qd.v, qdd.v) == UVMS_ERR_NONFINITE);
  check_hold();

  // A model with another joint count: ARG, zeros.
  uvms_arm_params_t p6;
  uvms_arm_params_paper(&p6);
  p6.num_joints = 6;
  uvms_arm_model_t m6;
  REQUIRE(uvms_arm_model_init(&p6, &m6) == UVMS_OK);
  CHECK(uvms_cart_traj_step(&traj, &m6, &work, t, uvms_real_t(0.03), q.v, qd.v, qdd.v) == UVMS_ERR_ARG);
  for (int i = 0; i < 7; ++i) CHECK((q.v[i] == 0 && qd.v[i] == 0 && qdd.v[i] == 0));
  CHECK(uvms_cart_traj_step(nullptr, &m, &work, t, uvms_real_t(0.03), q.v, qd.v, qdd.v) == UVMS_ERR_ARG);

  // Rate law: non-finite joint angles give NONFINITE and zeros.
  Joints bad = q0, out;
  bad.v[1] = uvms_real_t(NAN);
  uvms_real_t r_est[3] = {9, 9, 9};
  CHECK(uvms_cart_traj_rate(&traj, &m, &work, t, bad.v, out.v, r_est) == UVMS_ERR_NONFINITE);
  for (int i = 0; i < 7; ++i) CHECK(out.v[i] == 0);
  CHECK(V(r_est).norm() == 0);
}
