// SPDX-License-Identifier: Apache-2.0
// Shared helpers of the truth-model tests: the paper's joint poses (the firmware's SPEC §8
// table: tests that include this link uvms::firmware), the SPEC §8 cycloid acceleration, idle
// inputs and the stowed initial state.
#pragma once

#include <cmath>
#include <vector>

#include "uvms/trajectory.h"
#include "uvms_plant/plant.hpp"

// 1 when this file is compiled with AddressSanitizer (preset host-asan), where long simulations
// exceed the test timeout. GCC defines __SANITIZE_ADDRESS__; clang 14 only answers
// __has_feature(address_sanitizer).
#if defined(__SANITIZE_ADDRESS__)
#define UVMS_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UVMS_TEST_UNDER_ASAN 1
#endif
#endif
#ifndef UVMS_TEST_UNDER_ASAN
#define UVMS_TEST_UNDER_ASAN 0
#endif

namespace plant_test {
using namespace uvms::plant;

constexpr double kTick = 0.03;  // controller period [s] (SPEC §3.5)
const double kDeg = M_PI / 180.0;
// One column of SPEC §8's joint-angle table [rad].
inline std::vector<double> JointTableRad(uvms_joint_table_column_t column) {
  const uvms_real_t *deg = uvms_joint_table_deg(column);
  std::vector<double> rad(UVMS_JOINT_TABLE_JOINTS);
  for (size_t j = 0; j < rad.size(); ++j) rad[j] = double(deg[j]) * kDeg;
  return rad;
}
const std::vector<double> kThetaI = JointTableRad(UVMS_JOINT_TABLE_START);
const std::vector<double> kThetaVeh = JointTableRad(UVMS_JOINT_TABLE_VEHICLE);

// SPEC §8 cycloid acceleration θ̈ = (2πΔ/tF²)·sin(2πt/tF), θI → Veh. over tF.
inline std::vector<double> CycloidAccel(double t, double tf) {
  std::vector<double> a(7);
  for (int j = 0; j < 7; ++j)
    a[size_t(j)] = (t < tf) ? 2 * M_PI * (kThetaVeh[size_t(j)] - kThetaI[size_t(j)]) / (tf * tf) *
                                  std::sin(2 * M_PI * t / tf)
                            : 0.0;
  return a;
}

inline PlantInputs Idle(const Plant &p) {
  PlantInputs in;
  in.motor_voltage_V.assign(p.params().thrusters.size(), 0.0);
  in.motor_current_cmd_A.assign(p.params().thrusters.size(), 0.0);
  in.motor_current_rate_A_s.assign(p.params().thrusters.size(), 0.0);
  in.joint_accel_rad_s2.assign(p.params().links.size(), 0.0);
  return in;
}

inline InitialState Stowed() {
  InitialState s;
  s.q_rad = kThetaI;
  return s;
}

// The paper's vehicle with a massless, hydrodynamically inert arm and no payload: the vehicle
// alone, for analytic cases.
inline PlantParams VehicleOnlyParams() {
  PlantParams pp = PaperPlantParams();
  for (auto &l : pp.links) {
    l.mass_kg = 0;
    l.inertia_kg_m2.setZero();
    l.diameter_m = 0;
  }
  pp.payload_kg = 0;
  pp.contact.enabled = false;
  return pp;
}
}  // namespace plant_test
