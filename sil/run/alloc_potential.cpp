// SPDX-License-Identifier: Apache-2.0
// alloc_potential.cpp: the minimum-power allocation's static potential (alloc_potential.hpp).
#include "run/alloc_potential.hpp"

#include <cmath>
#include <limits>

namespace uvms::sil {

AllocationPotential::AllocationPotential(const uvms_ctrl_config_t &cfg)
    : tick_s_(double(cfg.tick_s)) {
  for (std::size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    const uvms_real_t limit_N = cfg.limits.thrust_limit_N[j];
    limit_N_[j] = limit_N > 0 ? limit_N : std::numeric_limits<uvms_real_t>::infinity();
  }
  ready_ = uvms_alloc_init(&alloc_, &cfg.thrusters) == UVMS_OK &&
           uvms_power_weights(cfg.thruster, cfg.thrusters.num_thrusters, weight_) == UVMS_OK;
}

void AllocationPotential::OnTick(const uvms_telemetry_t *tl, std::uint32_t usable_mask) {
  if (!ready_ || tl == nullptr || tl->status != 0) return;
  if (uvms_alloc_set_usable(&alloc_, usable_mask) != UVMS_OK) return;
  uvms_real_t T[UVMS_MAX_THRUSTERS] = {}, w[UVMS_ALLOC_WRENCH_DIM], P[UVMS_MAX_THRUSTERS] = {};
  const std::size_t n = alloc_.geom.num_thrusters;
  for (std::size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j)
    T[j] = ((usable_mask >> j) & 1u) ? uvms_real_t(tl->thrust_des_N[j]) : uvms_real_t(0);
  if (uvms_alloc_wrench_body(&alloc_, T, w) != UVMS_OK) return;
  // P = H_u⁺·(H_u·T): the allocation of T's own body wrench (identity attitude).
  static const uvms_real_t kIdentity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  if (uvms_alloc_step(&alloc_, kIdentity, &w[0], &w[3], P, nullptr, nullptr) != UVMS_OK) return;
  // The limits as the controller applied them; P is the limited P the controller started
  // from, so it exceeds a limit by rounding at most: clamped back onto it (more: unsolved).
  bool within = true;
  for (std::size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    const double limit = double(limit_N_[j]);
    const double a = std::abs(double(P[j]));
    if (a > limit * (1.0 + kLimitRounding)) within = false;
    else if (a > limit) P[j] = uvms_real_t(std::copysign(limit, double(P[j])));
  }
  // The controller's cost: Σ w_j·|T_j|^1.5 (alloc_power.h; w_j = 1 for thrusters alike).
  const double c_pinv = double(uvms_power_cost_weighted(n, weight_, P));
  const double c_cmd = double(uvms_power_cost_weighted(n, weight_, T));
  double c_opt = c_pinv;  // an unsolved tick: no saving counted
  if (within) {
    uvms_real_t opt[UVMS_MAX_THRUSTERS];
    uvms_power_info_t info;
    if (uvms_alloc_min_power_each(&alloc_, limit_N_, weight_, P, nullptr, opt, &info) == UVMS_OK &&
        info.converged)
      c_opt = double(info.cost);
    else
      ++unsolved_ticks_;
  } else {
    ++unsolved_ticks_;
  }
  pinv_ += c_pinv * tick_s_;
  opt_ += c_opt * tick_s_;
  cmd_ += c_cmd * tick_s_;
}

void AllocationPotential::WriteTo(RunSummary *sum) const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  sum->alloc_cost_pinv = pinv_;
  sum->alloc_cost_optimal = opt_;
  sum->alloc_cost_commanded = cmd_;
  sum->alloc_static_potential = pinv_ > 0 ? 1.0 - opt_ / pinv_ : nan;
  sum->alloc_realised_saving = pinv_ > 0 ? 1.0 - cmd_ / pinv_ : nan;
  sum->alloc_potential_unsolved_ticks = unsolved_ticks_;
}

}  // namespace uvms::sil
