// SPDX-License-Identifier: Apache-2.0
// tick_analyses.cpp: task-space error and the propulsive-energy split (tick_analyses.hpp).
#include "run/tick_analyses.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "uvms_plant/propulsion.hpp"

namespace uvms::sil {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A sample at t is "at or after t_F" when t ≥ t_F − kTimeTol_s: tick times are k·tick_s in
// floating point (60 s = 2000 × 0.03 s may round either way); the log's times are whole µs.
constexpr double kTimeTol_s = 1e-6;
// The reconstruction check of a tick's split: |T_ff + T_fb − P| and |P_pos + P_att − P| within
// this share of max(1 N, max|P|). The double firmware agrees to ~1e-14; a float build, sensor
// noise on R0 or a non-linear allocation fail it and the tick is counted as inexact.
constexpr double kSplitRelTol = 1e-6;

}  // namespace

plant::Vec3 TaskReference::At(double t_s) const {
  if (!line) return target_m;
  // firmware/src/trajectory.c uvms_cosine_line_eval: t' ≤ 0 holds the start, t' ≥ tF is the
  // exact end point, otherwise s = (rΔ/2)(1 − cos(π t'/tF)) [78].
  const double tp = t_s - start_s;
  double s_m = 0.0;
  if (tp >= duration_s)
    s_m = line_distance_m;
  else if (tp > 0.0)
    s_m = 0.5 * line_distance_m * (1.0 - std::cos(M_PI * (tp / duration_s)));
  return line_start_m + s_m * line_unit;
}

TaskReference MakeTaskReference(const uvms_ctrl_config_t &cfg, const plant::Vec3 &target_m,
                                const plant::Vec3 &ee_start_m) {
  TaskReference r;
  r.target_m = target_m;
  r.start_s = double(cfg.traj_start_s);
  r.duration_s = double(cfg.traj_duration_s);
  if (cfg.traj_mode == UVMS_TRAJ_CARTESIAN_LINE) {
    r.line = true;
    r.line_start_m = ee_start_m;
    const plant::Vec3 d(cfg.cart.direction[0], cfg.cart.direction[1], cfg.cart.direction[2]);
    r.line_unit = d / d.norm();  // the reader checked |d| ≥ UVMS_TRAJ_MIN_DIRECTION_NORM
    r.line_distance_m = double(cfg.cart.distance_m);
    r.duration_s = double(cfg.cart.duration_s);  // the line's tF (= trajectory.duration_s)
  }
  return r;
}

void TaskError::Add(const TaskReference &ref, double t_s, double e, Acc *a) {
  a->sum += e;
  ++a->n;
  a->max = (std::isnan(a->max) || std::isnan(e)) ? kNaN : std::max(a->max, e);
  const double tf = ref.end_s();
  if (!a->have_tf && t_s >= tf - kTimeTol_s) {
    a->have_tf = true;
    a->at_tf = e;
  }
  if (t_s > tf + kTimeTol_s) {
    a->hold_sum += e;
    ++a->hold_n;
  }
}

void TaskError::OnSample(double t_s, const plant::Vec3 &ee_m) {
  Add(ref_, t_s, (ee_m - ref_.At(t_s)).norm(), &acc_);
}

void TaskError::WriteTo(const plant::Truth &t, RunSummary *sum) const {
  Acc a = acc_;
  const double e_end = (t.ee_m - ref_.At(t.time_s)).norm();
  Add(ref_, t.time_s, e_end, &a);
  sum->task_error_reference = ref_.line ? "line" : "target";
  const plant::Vec3 end = ref_.At(ref_.end_s());
  sum->task_reference_end_m = {end[0], end[1], end[2]};
  sum->task_error_mean_m = a.sum / double(a.n);
  sum->task_error_max_m = a.max;
  sum->task_error_final_m = e_end;
  sum->task_error_at_tf_m = a.have_tf ? a.at_tf : kNaN;
  sum->task_error_hold_mean_m = a.hold_n > 0 ? a.hold_sum / double(a.hold_n) : kNaN;
}

// --- PropulsiveSplit ---

PropulsiveSplit::PropulsiveSplit(const plant::PlantParams &p, bool pseudoinverse_allocation)
    : params_(p), pinv_(pseudoinverse_allocation) {
  const std::size_t n = p.thrusters.size();
  H_.resize(6, Eigen::Index(n));
  group_.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const plant::ThrusterGeometry &g = p.thrusters[j];
    H_.col(Eigen::Index(j)) << g.direction, g.position_m.cross(g.direction);
    Eigen::Index axis = 0;
    g.direction.cwiseAbs().maxCoeff(&axis);
    group_[j] = std::string(1, "xyz"[axis]);
  }
  thruster_J_.assign(n, 0.0);
}

PropulsiveSplit::Sample PropulsiveSplit::Take(const plant::Truth &t) const {
  Sample s;
  s.time_s = t.time_s;
  s.energy_J = t.propulsive_energy_J;
  s.R0 = t.attitude.toRotationMatrix();
  const double rho = params_.env.density_kg_m3;
  s.power_W.resize(params_.thrusters.size());
  for (std::size_t j = 0; j < params_.thrusters.size(); ++j) {
    const plant::PropulsionParams &pp = plant::PropulsionOf(params_, j);
    s.power_W[j] = plant::PropulsivePowerW(pp, rho, {t.thrust_N[j]});  // the plant's own P_j
    const double w = t.motor_speed_rad_s[j], i = t.motor_current_A[j];
    const double va = plant::AdvanceSpeedMS(params_.thrusters[j], s.R0, t.v0_m_s, t.w0_rad_s, t.flow_m_s);
    s.shaft_W += plant::TorqueNm(pp, rho, w, va) * w;  // Q_j·ω_j, Q as in the motor's [54]
    s.friction_W += pp.viscous_friction_Nm_s * w * w;
    s.copper_W += pp.resistance_ohm * i * i;
  }
  return s;
}

const Eigen::MatrixXd *PropulsiveSplit::PseudoInverse(std::uint32_t mask) {
  auto it = pinv_cache_.find(mask);
  if (it == pinv_cache_.end()) {
    Eigen::MatrixXd Hu = H_;
    for (Eigen::Index j = 0; j < Hu.cols(); ++j)
      if (((mask >> j) & 1u) == 0u) Hu.col(j).setZero();  // unusable: a zero row of H⁺
    Eigen::MatrixXd pinv;
    const Eigen::MatrixXd HHt = Hu * Hu.transpose();
    Eigen::FullPivLU<Eigen::MatrixXd> lu(HHt);
    if (lu.rank() == 6) pinv = Hu.transpose() * lu.inverse();  // H⁺ = Hᵀ(HHᵀ)⁻¹ [38]
    it = pinv_cache_.emplace(mask, pinv).first;
  }
  return it->second.size() > 0 ? &it->second : nullptr;
}

bool PropulsiveSplit::SplitCommand(const uvms_telemetry_t &tl, const Eigen::Matrix3d &R0,
                                   std::uint32_t mask, Eigen::VectorXd *t_ff, Eigen::VectorXd *t_fb) {
  const Eigen::MatrixXd *pinv = PseudoInverse(mask);
  if (pinv == nullptr) return false;
  const Eigen::Matrix3d Rt = R0.transpose();
  Eigen::Matrix<double, 6, 1> w_ff, w_fb;  // body frame (SPEC §7.3: blockdiag(R0ᵀ, R0ᵀ))
  w_ff << Rt * plant::Vec3(tl.force_ff_N[0], tl.force_ff_N[1], tl.force_ff_N[2]),
      Rt * plant::Vec3(tl.moment_ff_Nm[0], tl.moment_ff_Nm[1], tl.moment_ff_Nm[2]);
  w_fb << Rt * plant::Vec3(tl.force_fb_N[0], tl.force_fb_N[1], tl.force_fb_N[2]),
      Rt * plant::Vec3(tl.moment_fb_Nm[0], tl.moment_fb_Nm[1], tl.moment_fb_Nm[2]);
  *t_ff = *pinv * w_ff;
  *t_fb = *pinv * w_fb;
  return true;
}

// Tick k begins with the truth tick k-1 ended with: its sample is taken once, not twice.
void PropulsiveSplit::BeginTick(const plant::Truth &t) {
  if (have_last_end_ && last_end_.time_s == t.time_s && last_end_.energy_J == t.propulsive_energy_J)
    std::swap(begin_, last_end_);
  else
    begin_ = Take(t);
  have_last_end_ = false;
  begun_ = true;
}

void PropulsiveSplit::EndTick(const plant::Truth &t, const uvms_telemetry_t *tl, std::uint32_t mask) {
  if (!begun_) return;
  begun_ = false;
  Sample end = Take(t);
  const double dt = end.time_s - begin_.time_s;
  shaft_J_ += 0.5 * dt * (begin_.shaft_W + end.shaft_W);  // trapezoid over the tick
  friction_J_ += 0.5 * dt * (begin_.friction_W + end.friction_W);
  copper_J_ += 0.5 * dt * (begin_.copper_W + end.copper_W);

  // The plant's exact ΔE_p over the tick, shared by the trapezoid weights of P_j.
  const std::size_t n = thruster_J_.size();
  const double dE = end.energy_J - begin_.energy_J;
  double wsum = 0.0;
  for (std::size_t j = 0; j < n; ++j) wsum += begin_.power_W[j] + end.power_W[j];
  std::vector<double> e(n);
  for (std::size_t j = 0; j < n; ++j)
    e[j] = wsum > 0.0 ? dE * (begin_.power_W[j] + end.power_W[j]) / wsum : dE / double(n);
  for (std::size_t j = 0; j < n; ++j) thruster_J_[j] += e[j];

  // The commanded thrusts of the tick, and whether each split is exact.
  const bool answered = tl != nullptr && tl->status == 0;
  double scale = 1.0;  // max(1 N, max|P|)
  if (answered)
    for (std::size_t j = 0; j < n; ++j) scale = std::max(scale, std::fabs(tl->thrust_des_N[j]));
  const double tol = kSplitRelTol * scale;

  Eigen::VectorXd t_ff, t_fb;
  bool ff_exact = answered && pinv_ && tl->thrust_scale_pos == 1.0 && tl->thrust_scale_att == 1.0 &&
                  SplitCommand(*tl, begin_.R0, mask, &t_ff, &t_fb);
  for (std::size_t j = 0; ff_exact && j < n; ++j)
    ff_exact = std::fabs(t_ff[Eigen::Index(j)] + t_fb[Eigen::Index(j)] - tl->thrust_des_N[j]) <= tol;
  bool pa_exact = answered;
  for (std::size_t j = 0; pa_exact && j < n; ++j)
    pa_exact = std::fabs(tl->thrust_pos_N[j] + tl->thrust_att_N[j] - tl->thrust_des_N[j]) <= tol;

  // part_a,j = E_j·T_a,j/(T_a,j + T_b,j): the parts add up to E_j (|T|^1.5 = |T|^0.5·sign(T)·T is
  // linear in T once |T|^0.5·sign(T) is fixed). A thruster without command (T_a + T_b = 0)
  // cannot be attributed: its energy is unsplit.
  auto split = [&](bool exact, auto share_a, auto share_b, double *a, double *b, double *unsplit,
                   long *inexact) {
    if (!exact) {
      ++*inexact;
      *unsplit += dE;
      return;
    }
    for (std::size_t j = 0; j < n; ++j) {
      const double ta = share_a(j), tb = share_b(j), tc = ta + tb;
      if (tc == 0.0) {
        *unsplit += e[j];
        continue;
      }
      const double pa = e[j] * (ta / tc);
      *a += pa;
      *b += e[j] - pa;
    }
  };
  split(ff_exact, [&](std::size_t j) { return t_ff[Eigen::Index(j)]; },
        [&](std::size_t j) { return t_fb[Eigen::Index(j)]; }, &ff_J_, &fb_J_, &ff_fb_unsplit_J_,
        &ff_fb_inexact_ticks_);
  split(pa_exact, [&](std::size_t j) { return tl->thrust_pos_N[j]; },
        [&](std::size_t j) { return tl->thrust_att_N[j]; }, &pos_J_, &att_J_, &pos_att_unsplit_J_,
        &pos_att_inexact_ticks_);
  last_end_ = std::move(end);  // the next tick's begin (BeginTick)
  have_last_end_ = true;
}

void PropulsiveSplit::WriteTo(RunSummary *sum) const {
  sum->propulsive_energy_ff_J = ff_J_;
  sum->propulsive_energy_fb_J = fb_J_;
  sum->propulsive_energy_ff_fb_unsplit_J = ff_fb_unsplit_J_;
  sum->propulsive_split_inexact_ticks = ff_fb_inexact_ticks_;
  sum->propulsive_energy_pos_J = pos_J_;
  sum->propulsive_energy_att_J = att_J_;
  sum->propulsive_energy_pos_att_unsplit_J = pos_att_unsplit_J_;
  sum->propulsive_pos_att_inexact_ticks = pos_att_inexact_ticks_;
  sum->propulsive_energy_thruster_J = thruster_J_;
  sum->propulsive_energy_group_J = {0.0, 0.0, 0.0};
  for (auto &g : sum->propulsive_energy_groups) g.clear();
  for (std::size_t j = 0; j < thruster_J_.size(); ++j) {
    const int axis = group_[j][0] - 'x';
    sum->propulsive_energy_group_J[std::size_t(axis)] += thruster_J_[j];
    sum->propulsive_energy_groups[std::size_t(axis)].push_back(int(j) + 1);
  }
  sum->shaft_energy_J = shaft_J_;
  sum->friction_energy_J = friction_J_;
  sum->copper_energy_J = copper_J_;
}

}  // namespace uvms::sil
