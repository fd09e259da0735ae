// SPDX-License-Identifier: Apache-2.0
// alloc_potential.hpp: the static potential of the minimum-power allocation, accumulated tick
// by tick during a run (docs/MODEL.md §7.3), so that every run's summary.json says what the
// allocator could save on the wrenches that run commanded, whichever allocator it used.
//
// Per tick with a commanded thrust T (telemetry thrust_des_N, status UVMS_OK):
//   - P = H_u⁺·H_u·T, the pseudoinverse thrust of T's delivered wrench (= T itself in a
//     pseudoinverse run; the P a min_power run started from, since its T = P + N·z);
//   - T* = the least Σ|T|^1.5 with P's wrench within the thrust limit: the firmware's
//     uvms_alloc_min_power, started cold each tick (no warm start), on the controller's own
//     geometry and the usable mask the controller was sent.
// A tick whose optimum is not found (solver error, not converged, P above the limit by more
// than rounding) counts with C_opt = C_pinv (no saving) and is counted in
// alloc_potential_unsolved_ticks. Accumulated: C_pinv = ∫Σ|P_j|^1.5 dt, C_opt = ∫Σ|T*_j|^1.5 dt, C_cmd = ∫Σ|T_j|^1.5 dt
// [N^1.5·s]. static potential = 1 − C_opt/C_pinv (what the optimum saves on these wrenches),
// realised = 1 − C_cmd/C_pinv (what the run's own allocation saved on them).
// No I/O: a pure function of what it is fed.
#pragma once

#include <cstdint>

#include "msg/codec.h"
#include "run/summary_writer.hpp"
#include "uvms/controller.h"

namespace uvms::sil {

class AllocationPotential {
 public:
  /// The controller's thruster geometry and per-thruster thrust limits (0: none), and its
  /// tick [s].
  AllocationPotential(const uvms_ctrl_config_t &cfg);
  /// Tick k's telemetry (nullptr or a failed tick: nothing) and the usable mask sent.
  void OnTick(const uvms_telemetry_t *tl, std::uint32_t usable_mask);
  void WriteTo(RunSummary *sum) const;

 private:
  uvms_alloc_t alloc_{};
  bool ready_{false};
  uvms_real_t limit_N_[UVMS_MAX_THRUSTERS]{};  ///< the limits as the solver takes them (+inf: none) [N]
  uvms_real_t weight_[UVMS_MAX_THRUSTERS]{};  ///< the controller's cost weights w_j (uvms_power_weights) [1]
  double tick_s_{0};
  double pinv_{0}, opt_{0}, cmd_{0};  // C_pinv, C_opt, C_cmd [N^1.5·s]
  long unsolved_ticks_{0};
  /// P may exceed the limit by this fraction: the rounding of H_u⁺·H_u·T, and of the float
  /// build's thrusts (relative ~1e-6) [-]
  static constexpr double kLimitRounding = 1e-5;
};

}  // namespace uvms::sil
