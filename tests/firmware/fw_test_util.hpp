// SPDX-License-Identifier: Apache-2.0
// Shared helpers for firmware tests: conversions between the firmware's real type and Eigen
// (double), and the tolerance scale of the build's real type.
#pragma once

#include <Eigen/Dense>
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

inline uvms_arm_model_t PaperModel(double payload_kg = 10.0) {
  uvms_arm_params_t p;
  uvms_arm_params_paper(&p);
  p.payload_kg = uvms_real_t(payload_kg);
  uvms_arm_model_t m;
  uvms_arm_model_init(&p, &m);
  return m;
}

}  // namespace fwtest
