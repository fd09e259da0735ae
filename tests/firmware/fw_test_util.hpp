// SPDX-License-Identifier: Apache-2.0
// Shared helpers for firmware tests: conversions between the firmware's real type and Eigen
// (double), and the tolerance scale of the build's real type.
#pragma once

#include <Eigen/Dense>
#include <stdexcept>
#include <string>
#include <vector>

#include "uvms/arm_model.h"
#include "uvms/linalg.h"

namespace fwtest {

// Unit roundoff of the controller's real type (float: 2^-24, double: 2^-53).
constexpr double kEps = UVMS_REAL_IS_FLOAT ? 5.96e-8 : 1.11e-16;
constexpr bool kFloat = UVMS_REAL_IS_FLOAT != 0;

inline Eigen::Vector3d V(const uvms_real_t *a) { return {double(a[0]), double(a[1]), double(a[2])}; }

inline Eigen::Matrix3d M(const uvms_real_t *R) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = double(R[3 * r + c]);
  return m;
}

inline void Put(const Eigen::Vector3d &v, uvms_real_t *out) {
  for (int i = 0; i < 3; ++i) out[i] = uvms_real_t(v[i]);
}

inline void Put(const Eigen::Matrix3d &m, uvms_real_t *out) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out[3 * r + c] = uvms_real_t(m(r, c));
}

/// A model together with the parameters it points to (uvms_arm_model_t does not copy them,
/// arm_model.h). Neither copyable nor movable, so the pointer cannot outlive the parameters;
/// pass it where a uvms_arm_model_t * is expected (derived-to-base). Declare it `auto` (or
/// OwnedModel): copying it into a plain uvms_arm_model_t would keep a dangling pointer.
/// Throws when uvms_arm_model_init refuses the parameters (a test failure under Catch).
struct OwnedModel : uvms_arm_model_t {
  uvms_arm_params_t params;
  explicit OwnedModel(const uvms_arm_params_t &p) : uvms_arm_model_t{}, params(p) {
    const uvms_status_t st = uvms_arm_model_init(&params, this);
    if (st != UVMS_OK) throw std::runtime_error(std::string("uvms_arm_model_init: ") + uvms_status_str(st));
  }
  OwnedModel(const OwnedModel &) = delete;
  OwnedModel &operator=(const OwnedModel &) = delete;
};

inline OwnedModel PaperModel(double payload_kg = 10.0) {
  uvms_arm_params_t p;
  uvms_arm_params_paper(&p);
  p.payload_kg = uvms_real_t(payload_kg);
  return OwnedModel(p);
}

}  // namespace fwtest
