// SPDX-License-Identifier: Apache-2.0
/*
 * bench_vs_pinocchio: one double-precision controller tick (uvms_ctrl_step) against one
 * Pinocchio floating-base RNEA (free-flyer + 7 revolute joints), side by side in one process.
 * Built and run by bench/pinocchio_bench.sh (not part of the project build).
 *
 *   bench_vs_pinocchio check           the Pinocchio model against the firmware's arm model
 *   bench_vs_pinocchio time RUNS       check, then RUNS × 2000 ticks of each, interleaved
 *   bench_vs_pinocchio count ctrl|rnea|ne-vacuum|ne-water RUNS
 *                                      no timing: RUNS × 2000 calls of one side, for
 *                                      valgrind --tool=callgrind --toggle-collect=uvms_ctrl_step
 *                                      (ctrl), --toggle-collect=bench_rnea_call (rnea) or
 *                                      --toggle-collect=bench_ne_call (ne-*)
 *
 * Controller: the paper configuration of case VII (uvms_ctrl_config_paper) driven by the 60 s
 * sensor sequence of tests/support/sensor_sequence.c (2000 ticks of 0.03 s, precomputed), as in
 * bench/bench_ctrl_host.c; the firmware library of a host (double) build.
 *
 * Pinocchio: pinocchio::rnea(model, data, q, v, a) compiled from pin's headers in this
 * translation unit (no explicit-instantiation library), -O3 -DNDEBUG like the firmware. The
 * model is built from the firmware's own paper parameters (uvms_arm_params_paper): a
 * JointModelFreeFlyer at the vehicle CoM carrying the vehicle's mass and inertia, then the
 * WAM's 7 revolute joints from its standard DH parameters (joint i about z of frame i−1,
 * placement Trans(d)·Trans(a)·Rx(α) between joints), each link's mass, CoM and inertia
 * (given in DH frame i, rotated by Rx(α) into the joint frame), and the payload as a point
 * mass at the end effector. `check` verifies that model: in vacuum (density 0, so no drag,
 * buoyancy or added mass) the firmware's Newton–Euler (uvms_arm_rnea) and Pinocchio's rnea
 * must give the same 7 joint torques at the sensor sequence's states. RNEA inputs: q, v from
 * the same 2000 sensor records (vehicle pose and twist, joint angles and rates) and fixed,
 * smooth accelerations.
 *
 * The firmware's Newton–Euler alone (uvms_arm_rnea: the forward kinematics and both passes, the
 * part of the tick that does what the RNEA does) at the same states and accelerations, in two
 * fluids: vacuum (the model check's, Earth gravity) and the paper configuration's fluid
 * (cfg.fluid, as the tick's feedforward uses it: water's density, the flow, the paper's zero
 * gravity; so added mass and drag). Nearly, not exactly, the RNEA's work: Pinocchio's also
 * carries the vehicle body's inertia into the base wrench (one body of its eight), the
 * firmware's also the barycenter's position and velocity, the vehicle's drag and the payload
 * point.
 *
 * Timing: batches of 100 calls (100 consecutive ticks; the controller re-initialised, untimed,
 * every 2000), a batch of each of the four (controller, RNEA, Newton–Euler in vacuum and in the
 * fluid) in turn, in the orders of a balanced Latin square (kOrder: each one first, and after
 * each other one, equally often; the square's row moves on with the run too, so that every
 * window of ticks gets every order). Reported: median over batches of ns per call for each,
 * the ratios of the medians to the RNEA's, and the median of the per-batch tick/RNEA ratios.
 * This is a benchmark: nothing here asserts a time.
 */
#include <pinocchio/multibody.hpp>  // ModelTpl, DataTpl, the joint models (pin 4.x layout)
#include <pinocchio/algorithm/rnea.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "sensor_sequence.h"
#include "uvms/controller.h"
#include "uvms/dynamics.h"
#include "uvms/linalg.h"

static_assert(!UVMS_REAL_IS_FLOAT, "the comparison is with the double-precision controller");

/** One RNEA call's arguments. */
struct RneaInput {
  Eigen::VectorXd q, v, a;
};

/** The same state as the firmware's Newton–Euler takes it (uvms_arm_rnea). */
struct NeInput {
  uvms_base_state_t base;
  double qdd[UVMS_MAX_JOINTS];
  const double *q, *qd;  // the sensor record's joint angles and rates
  bool ok;               // the record's quaternion gave a rotation
};

namespace {

constexpr int kTicks = 2000;   // 60 s of 0.03 s ticks (the paper's run length)
constexpr int kBatch = 100;    // calls per timed batch
constexpr int kCase = 7;       // paper case VII
constexpr double kGravity = -9.81;

using pinocchio::Data;
using pinocchio::Inertia;
using pinocchio::Model;
using pinocchio::SE3;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

uvms_ctrl_t g_ctrl;
uvms_ctrl_sensors_t g_sensors[kTicks];
uvms_arm_model_t g_arm;
uvms_arm_data_t g_arm_data;
uvms_ctrl_command_t g_cmd;
uvms_ctrl_telemetry_t g_tlm;

long long now_ns() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<long long>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

Matrix3d rot_x(double alpha) { return Eigen::AngleAxisd(alpha, Vector3d::UnitX()).toRotationMatrix(); }

// The firmware's paper arm as a Pinocchio model (see the file comment).
Model build_model(const uvms_arm_params_t &p) {
  Model m;
  m.gravity.linear(Vector3d(0.0, 0.0, kGravity));
  const uvms_vehicle_params_t &veh = p.vehicle;
  const pinocchio::JointIndex base =
      m.addJoint(0, pinocchio::JointModelFreeFlyer(), SE3::Identity(), "vehicle");
  m.appendBodyToJoint(base,
                      Inertia(veh.mass_kg, Vector3d::Zero(),
                              Vector3d(veh.inertia_kg_m2[0], veh.inertia_kg_m2[1],
                                       veh.inertia_kg_m2[2]).asDiagonal().toDenseMatrix()),
                      SE3::Identity());
  // Joint 1 sits at the manipulator base point s0 (vehicle axes: R_0 = R0 in the firmware).
  SE3 placement(Matrix3d::Identity(), Vector3d(veh.base_offset_m[0], veh.base_offset_m[1],
                                               veh.base_offset_m[2]));
  pinocchio::JointIndex parent = base;
  Matrix3d Rx = Matrix3d::Identity();
  Vector3d distal = Vector3d::Zero();
  for (size_t i = 0; i < p.num_joints; ++i) {
    const uvms_link_params_t &L = p.link[i];
    const pinocchio::JointIndex j = m.addJoint(parent, pinocchio::JointModelRZ(), placement,
                                               "joint" + std::to_string(i + 1));
    // Joint frame J_i = frame i−1 turned by θ_i about its z; DH frame i = J_i·Trans(0,0,d)·
    // Trans(a,0,0)·Rx(α): the link's CoM r_i and inertia (frame-i axes) rotate by Rx(α).
    Rx = rot_x(L.alpha_rad);
    const Vector3d com = Rx * Vector3d(L.com_m[0], L.com_m[1], L.com_m[2]);
    const Matrix3d I = Rx *
                       Vector3d(L.inertia_kg_m2[0], L.inertia_kg_m2[1], L.inertia_kg_m2[2])
                           .asDiagonal()
                           .toDenseMatrix() *
                       Rx.transpose();
    m.appendBodyToJoint(j, Inertia(L.mass_kg, com, I), SE3::Identity());
    distal = Vector3d(L.a_m, 0.0, L.d_m);  // p_i* − p_{i−1}* in J_i: Rx(α)·l_i = (a, 0, d)
    placement = SE3(Rx, distal);
    parent = j;
  }
  // Payload: a point mass at the EE (p_N*) plus r_{N+1} in frame N.
  const Vector3d payload =
      distal + Rx * Vector3d(p.payload_offset_m[0], p.payload_offset_m[1], p.payload_offset_m[2]);
  m.appendBodyToJoint(parent, Inertia(p.payload_kg, payload, Matrix3d::Zero()), SE3::Identity());
  return m;
}

// Fixed, smooth vehicle and joint accelerations of tick k (inertial for the vehicle).
void accelerations(int k, double a0[3], double alpha0[3], double qdd[UVMS_MAX_JOINTS]) {
  const double t = 0.03 * k;
  for (int c = 0; c < 3; ++c) {
    a0[c] = 0.05 * std::sin(0.7 * t + c);
    alpha0[c] = 0.02 * std::cos(0.4 * t + 2.0 * c);
  }
  for (int i = 0; i < UVMS_MAX_JOINTS; ++i) qdd[i] = 0.3 * std::sin(0.5 * t + 0.9 * i);
}

// Pinocchio's (q, v, a) for the state of sensor record s and tick k. Free-flyer convention:
// q = (position, quaternion x y z w), v = (R0ᵀv0, R0ᵀω0) (local frame), a = dv/dt in the
// local frame, whose linear part is R0ᵀ·v̇0 − ω_b × v_b.
RneaInput rnea_input(const uvms_ctrl_sensors_t &s, int k, size_t n) {
  RneaInput in{VectorXd(7 + n), VectorXd(6 + n), VectorXd(6 + n)};
  const Eigen::Quaterniond quat(s.quaternion_wxyz[0], s.quaternion_wxyz[1],
                                s.quaternion_wxyz[2], s.quaternion_wxyz[3]);
  const Matrix3d R = quat.normalized().toRotationMatrix();
  const Vector3d v0(s.velocity_m_s[0], s.velocity_m_s[1], s.velocity_m_s[2]);
  const Vector3d w0(s.angular_velocity_rad_s[0], s.angular_velocity_rad_s[1], s.angular_velocity_rad_s[2]);
  double a0[3], al0[3], qdd[UVMS_MAX_JOINTS];
  accelerations(k, a0, al0, qdd);
  const Vector3d vb = R.transpose() * v0, wb = R.transpose() * w0;
  in.q << s.position_m[0], s.position_m[1], s.position_m[2], quat.normalized().coeffs(),
      Eigen::Map<const VectorXd>(s.joint_position_rad, static_cast<Eigen::Index>(n));
  in.v << vb, wb, Eigen::Map<const VectorXd>(s.joint_velocity_rad_s, static_cast<Eigen::Index>(n));
  in.a << R.transpose() * Vector3d(a0[0], a0[1], a0[2]) - wb.cross(vb),
      R.transpose() * Vector3d(al0[0], al0[1], al0[2]),
      Eigen::Map<const VectorXd>(qdd, static_cast<Eigen::Index>(n));
  return in;
}

// The firmware Newton–Euler's input for sensor record s and tick k: the RNEA's state.
NeInput ne_input(const uvms_ctrl_sensors_t &s, int k) {
  NeInput in{};
  std::memcpy(in.base.position_m, s.position_m, sizeof in.base.position_m);
  in.ok = uvms_quat_to_rot(s.quaternion_wxyz, in.base.R0) == UVMS_OK;
  std::memcpy(in.base.velocity_m_s, s.velocity_m_s, sizeof in.base.velocity_m_s);
  std::memcpy(in.base.omega_rad_s, s.angular_velocity_rad_s, sizeof in.base.omega_rad_s);
  accelerations(k, in.base.accel_m_s2, in.base.alpha_rad_s2, in.qdd);
  in.q = s.joint_position_rad;
  in.qd = s.joint_velocity_rad_s;
  return in;
}

uvms_fluid_t vacuum_fluid() {
  uvms_fluid_t vacuum{};  // density 0: no drag, buoyancy or added mass
  vacuum.gravity_m_s2[2] = kGravity;
  return vacuum;
}

// Largest |τ_Pinocchio − τ_firmware| over the joints and every 100th tick, relative to the
// largest |τ|; returns it, prints both.
double check_model(const Model &model, Data &data, const std::vector<RneaInput> &in,
                   const std::vector<NeInput> &ne) {
  const uvms_fluid_t vacuum = vacuum_fluid();
  const size_t n = g_arm.num_joints;
  double max_diff = 0.0, max_tau = 0.0;
  for (int k = 0; k < kTicks; k += 100) {
    const NeInput &x = ne[static_cast<size_t>(k)];
    if (uvms_arm_rnea(&g_arm, &g_arm_data, &x.base, &vacuum, x.q, x.qd, x.qdd) != UVMS_OK)
      return INFINITY;
    const VectorXd &tau = pinocchio::rnea(model, data, in[k].q, in[k].v, in[k].a);
    for (size_t i = 0; i < n; ++i) {
      max_diff = std::max(max_diff, std::fabs(tau[6 + static_cast<Eigen::Index>(i)] -
                                              g_arm_data.tau_Nm[i + 1]));
      max_tau = std::max(max_tau, std::fabs(g_arm_data.tau_Nm[i + 1]));
    }
  }
  std::printf("model check: joint torques, Pinocchio rnea vs firmware uvms_arm_rnea (vacuum), "
              "20 states: max |difference| %.3g N·m, max |torque| %.3g N·m\n",
              max_diff, max_tau);
  return max_diff / max_tau;
}

}  // namespace

// The RNEA call behind one symbol, for callgrind's --toggle-collect (not inlined).
extern "C" __attribute__((noinline)) void bench_rnea_call(const Model &model, Data &data,
                                                          const RneaInput &in) {
  pinocchio::rnea(model, data, in.q, in.v, in.a);
}

// The firmware's Newton–Euler behind one symbol (bench_ne_call), as the RNEA's.
extern "C" __attribute__((noinline)) int bench_ne_call(const NeInput &in,
                                                       const uvms_fluid_t &fluid) {
  return uvms_arm_rnea(&g_arm, &g_arm_data, &in.base, &fluid, in.q, in.qd, in.qdd) != UVMS_OK;
}

// The sides a run times or counts.
enum Side { kCtrl, kRnea, kNeVacuum, kNeWater, kSides };
const char *const kSideNames[kSides] = {"ctrl", "rnea", "ne-vacuum", "ne-water"};
// A balanced Latin square (Williams): batch b runs the sides in row (b + b / windows) % 4;
// over four rows each side runs once in each place and once after each other side.
const int kOrder[kSides][kSides] = {{0, 1, 3, 2}, {1, 2, 0, 3}, {2, 3, 1, 0}, {3, 0, 2, 1}};

int side_of(const char *name) {
  for (int i = 0; i < kSides; ++i)
    if (std::strcmp(name, kSideNames[i]) == 0) return i;
  return -1;
}

// One batch of calls of `side` over ticks [k0, k0 + kBatch); the errors it returned.
int run_batch(int side, int k0, const Model &model, Data &data, const std::vector<RneaInput> &in,
              const std::vector<NeInput> &ne, const uvms_fluid_t fluids[2]) {
  int errors = 0;
  for (int k = k0; k < k0 + kBatch; ++k) {
    const size_t i = static_cast<size_t>(k);
    switch (side) {
      case kCtrl:
        errors += uvms_ctrl_step(&g_ctrl, &g_sensors[k], &g_cmd, &g_tlm) != UVMS_OK;
        break;
      case kRnea: bench_rnea_call(model, data, in[i]); break;
      default: errors += bench_ne_call(ne[i], fluids[side - kNeVacuum]); break;
    }
  }
  return errors;
}

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  const size_t n = x.size();
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

const char kUsage[] =
    "usage: bench_vs_pinocchio check | time RUNS | count ctrl|rnea|ne-vacuum|ne-water RUNS\n"
    "  check       Pinocchio's joint torques against the firmware's Newton-Euler\n"
    "  time RUNS   the tick, the RNEA and the Newton-Euler alone in batches, median ns\n"
    "  count W RUNS  one of them untimed, for valgrind --tool=callgrind\n"
    "(bench/pinocchio_bench.sh builds and runs it; docs/BENCHMARKS.md)\n";

int main(int argc, char **argv) {
  if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const bool mode_check = argc >= 2 && std::strcmp(argv[1], "check") == 0;
  const bool mode_time = argc >= 3 && std::strcmp(argv[1], "time") == 0;
  const int count_side = argc >= 4 && std::strcmp(argv[1], "count") == 0 ? side_of(argv[2]) : -1;
  const bool mode_count = count_side >= 0;
  const int runs = mode_time ? std::atoi(argv[2]) : mode_count ? std::atoi(argv[3]) : 1;
  if (!(mode_check || mode_time || mode_count) || runs < 1) {
    std::fputs(kUsage, stderr);
    return 2;
  }

  uvms_ctrl_config_t cfg;
  if (uvms_ctrl_config_paper(&cfg, kCase) != UVMS_OK) return 3;
  for (int k = 0; k < kTicks; ++k) uvms_sensor_sequence(&cfg, k, &g_sensors[k]);
  uvms_arm_params_t params;
  uvms_arm_params_paper(&params);
  if (uvms_arm_model_init(&params, &g_arm) != UVMS_OK) return 3;
  const uvms_fluid_t fluids[2] = {vacuum_fluid(), cfg.fluid};

  const Model model = build_model(params);
  Data data(model);
  std::vector<RneaInput> in;
  std::vector<NeInput> ne;
  in.reserve(kTicks);
  ne.reserve(kTicks);
  for (int k = 0; k < kTicks; ++k) {
    in.push_back(rnea_input(g_sensors[k], k, params.num_joints));
    ne.push_back(ne_input(g_sensors[k], k));
    if (!ne.back().ok) {
      std::fprintf(stderr, "bench_vs_pinocchio: sensor record %d: no rotation from its "
                           "quaternion\n", k);
      return 3;
    }
  }
  if (model.nq != 14 || model.nv != 13) {
    std::fprintf(stderr, "bench_vs_pinocchio: model nq %d nv %d, expected 14 and 13\n",
                 model.nq, model.nv);
    return 3;
  }

  int errors = 0;
  if (mode_count) {
    for (int r = 0; r < runs; ++r) {
      if (count_side == kCtrl && uvms_ctrl_init(&g_ctrl, &cfg) != UVMS_OK) return 4;
      for (int k0 = 0; k0 < kTicks; k0 += kBatch)
        errors += run_batch(count_side, k0, model, data, in, ne, fluids);
    }
    std::printf("count %s: %d calls\n", argv[2], runs * kTicks);
    return errors ? 1 : 0;
  }

  const double rel = check_model(model, data, in, ne);
  if (!(rel < 1e-9)) {
    std::fprintf(stderr, "bench_vs_pinocchio: the Pinocchio model does not reproduce the "
                         "firmware's arm (relative torque difference %.3g)\n", rel);
    return 5;
  }
  if (mode_check) return 0;

  // Warm-up: one run of each, untimed.
  if (uvms_ctrl_init(&g_ctrl, &cfg) != UVMS_OK) return 4;
  for (int k0 = 0; k0 < kTicks; k0 += kBatch)
    for (int side = 0; side < kSides; ++side)
      errors += run_batch(side, k0, model, data, in, ne, fluids);
  const int windows = kTicks / kBatch;  // batches per run of the sequence
  const int batches = runs * windows;
  std::vector<double> ns[kSides], pair_ratio;
  for (auto &v : ns) v.reserve(static_cast<size_t>(batches));
  pair_ratio.reserve(static_cast<size_t>(batches));
  for (int b = 0; b < batches; ++b) {
    const int k0 = (b % windows) * kBatch;
    if (k0 == 0 && uvms_ctrl_init(&g_ctrl, &cfg) != UVMS_OK) return 4;
    double t_ns[kSides];
    const int *order = kOrder[(b + b / windows) % kSides];
    for (int turn = 0; turn < kSides; ++turn) {
      const int side = order[turn];
      const long long t0 = now_ns();
      errors += run_batch(side, k0, model, data, in, ne, fluids);
      t_ns[side] = static_cast<double>(now_ns() - t0) / kBatch;
    }
    for (int side = 0; side < kSides; ++side) ns[side].push_back(t_ns[side]);
    pair_ratio.push_back(t_ns[kCtrl] / t_ns[kRnea]);
  }
  double med[kSides];
  for (int side = 0; side < kSides; ++side) med[side] = median(ns[side]);
  std::printf("time: %d batches of %d calls of each (case VII, %d runs of %d ticks): "
              "ctrl_median_ns=%.1f rnea_median_ns=%.1f ratio_of_medians=%.3f "
              "median_pair_ratio=%.3f ne_vacuum_median_ns=%.1f ne_vacuum_ratio=%.3f "
              "ne_water_median_ns=%.1f ne_water_ratio=%.3f pinocchio=%s\n",
              batches, kBatch, runs, kTicks, med[kCtrl], med[kRnea], med[kCtrl] / med[kRnea],
              median(pair_ratio), med[kNeVacuum], med[kNeVacuum] / med[kRnea], med[kNeWater],
              med[kNeWater] / med[kRnea], PINOCCHIO_VERSION);
  if (errors) std::fprintf(stderr, "bench_vs_pinocchio: %d calls returned an error\n", errors);
  return errors ? 1 : 0;
}
