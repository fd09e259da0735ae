// SPDX-License-Identifier: Apache-2.0
// SPEC §8: every final column of the joint-angle table is meant to put the EE at the same
// inertial point: the "Veh." pose with the vehicle held still, each barycenter pose with the
// barycenter held at its initial value (attitude held) and the vehicle displaced accordingly.
// This test computes each column's miss distance with the firmware kinematics and prints the
// table; it asserts the physics that must hold whatever the table says (see each CHECK).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "fw_test_util.hpp"
#include "uvms/kinematics.h"
#include "uvms/trajectory.h"

using namespace fwtest;

namespace {
constexpr double kDeg = M_PI / 180.0;
// The firmware's SPEC §8 table: θI, then the final columns Veh., Bary 0, 1, 2, 5, 10 kg.
const uvms_real_t *const kThetaI = uvms_joint_table_deg(UVMS_JOINT_TABLE_START);
double ThetaF(int col, int j) {  // col 0: Veh., 1..5: barycenter columns [deg]
  return double(uvms_joint_table_deg(uvms_joint_table_column_t(UVMS_JOINT_TABLE_VEHICLE + col))[j]);
}
double Payload(int col) {  // the model payload of column col [kg] (Veh.: 0)
  return col == 0 ? 0.0
                  : double(uvms_joint_table_payload_kg(
                        uvms_joint_table_column_t(UVMS_JOINT_TABLE_VEHICLE + col)));
}
}  // namespace

TEST_CASE("JointTableColumnsReachTheVehicleReferenceEePoint", "[kinematics][table]") {
  static uvms_arm_data_t d;
  const uvms_real_t origin[3] = {0, 0, 0};
  uvms_real_t I3[9];
  uvms_m3_identity(I3);
  uvms_real_t qI[7], qF[7];
  for (int j = 0; j < 7; ++j) qI[j] = uvms_real_t(double(kThetaI[j]) * kDeg);

  // Vehicle reference: vehicle at the origin, identity attitude, final "Veh." angles.
  const auto m_veh = PaperModel(Payload(0));
  for (int j = 0; j < 7; ++j) qF[j] = uvms_real_t(ThetaF(0, j) * kDeg);
  REQUIRE(uvms_arm_fk(&m_veh, &d, origin, I3, qF) == UVMS_OK);
  const Eigen::Vector3d ee_target = V(d.ee_m);
  REQUIRE(uvms_arm_fk(&m_veh, &d, origin, I3, qI) == UVMS_OK);
  const Eigen::Vector3d ee_start = V(d.ee_m);
  std::printf("SPEC §8 table check: EE start (0,0,0 vehicle) = (%.4f, %.4f, %.4f) m, "
              "Veh. target = (%.4f, %.4f, %.4f) m, reach %.4f m\n",
              ee_start.x(), ee_start.y(), ee_start.z(), ee_target.x(), ee_target.y(),
              ee_target.z(), (ee_target - ee_start).norm());

  for (int col = 1; col < 6; ++col) {
    const auto m = PaperModel(Payload(col));
    REQUIRE(uvms_arm_fk(&m, &d, origin, I3, qI) == UVMS_OK);
    const Eigen::Vector3d cm0 = V(d.barycenter_m);
    for (int j = 0; j < 7; ++j) qF[j] = uvms_real_t(ThetaF(col, j) * kDeg);
    uvms_real_t rel[3];
    REQUIRE(uvms_arm_ee_minus_barycenter(&m, &d, I3, qF, rel) == UVMS_OK);
    const Eigen::Vector3d ee_final = cm0 + V(rel);  // [4]
    // The vehicle displacement that holds the barycenter: r0 = cm0 − (p_cm − r0)(θF).
    REQUIRE(uvms_arm_fk(&m, &d, origin, I3, qF) == UVMS_OK);
    const Eigen::Vector3d r0_final = cm0 - V(d.barycenter_m);
    const double miss = (ee_final - ee_target).norm();
    std::printf("  Bary. %4.1f kg: EE (%.4f, %.4f, %.4f) m, vehicle moved (%.4f, %.4f, %.4f) m, "
                "miss vs Veh. target %.4f m\n",
                Payload(col), ee_final.x(), ee_final.y(), ee_final.z(), r0_final.x(),
                r0_final.y(), r0_final.z(), miss);
    // Physics that must hold: with the vehicle placed at r0_final the ordinary kinematics [3]
    // reproduce the virtual-manipulator estimate [4] ...
    uvms_real_t r0f[3];
    Put(r0_final, r0f);
    REQUIRE(uvms_arm_fk(&m, &d, r0f, I3, qF) == UVMS_OK);
    CHECK((V(d.ee_m) - ee_final).norm() < (kFloat ? 1e-5 : 1e-12));
    CHECK((V(d.barycenter_m) - cm0).norm() < (kFloat ? 1e-5 : 1e-12));
    // ... and the arm reaching forward (+x) pushes the vehicle back (−x).
    CHECK(r0_final.x() < 0.0);
    // If this fails, the table or the kinematics changed: re-check both and update the note
    // in docs/MODEL.md (C26).
    // The table's intent holds to 1 mm for every column (the 10 kg column's joint 1 carries
    // the documented correction, C26; its printed value is checked below).
    CHECK(miss < 1e-3);
  }
}

namespace {
// The EE of the "Veh." column with the vehicle at the origin, level (the columns' target) [m].
Eigen::Vector3d VehColumnEe() {
  static uvms_arm_data_t d;
  const uvms_real_t origin[3] = {0, 0, 0};
  uvms_real_t I3[9], qF[7];
  uvms_m3_identity(I3);
  for (int j = 0; j < 7; ++j) qF[j] = uvms_real_t(ThetaF(0, j) * kDeg);
  const auto m_veh = PaperModel(0.0);
  REQUIRE(uvms_arm_fk(&m_veh, &d, origin, I3, qF) == UVMS_OK);
  return V(d.ee_m);
}

// The 10 kg column's miss [m] of the target ee_target with its joint 1 set to q1_deg (the other
// six as printed).
double Miss10kg(double q1_deg, const Eigen::Vector3d &ee_target) {
  static uvms_arm_data_t d;
  const uvms_real_t origin[3] = {0, 0, 0};
  uvms_real_t I3[9], qI[7], qF[7];
  uvms_m3_identity(I3);
  for (int j = 0; j < 7; ++j) qI[j] = uvms_real_t(double(kThetaI[j]) * kDeg);
  const auto m = PaperModel(10.0);
  REQUIRE(uvms_arm_fk(&m, &d, origin, I3, qI) == UVMS_OK);
  const Eigen::Vector3d cm0 = V(d.barycenter_m);
  for (int j = 0; j < 7; ++j) qF[j] = uvms_real_t(ThetaF(5, j) * kDeg);
  qF[0] = uvms_real_t(q1_deg * kDeg);
  uvms_real_t rel[3];
  REQUIRE(uvms_arm_ee_minus_barycenter(&m, &d, I3, qF, rel) == UVMS_OK);
  return (cm0 + V(rel) - ee_target).norm();
}
}  // namespace

// SPEC §8 (round 3) and docs/MODEL.md C26: the printed 10 kg column's joint 1 (176.19°) breaks
// the column's trend; the joint-1 value that best meets the column's intent is found here by a
// sweep, independently of the candidate correction 173.19° (a transposed digit). The check:
// the sweep's minimum lies within 0.05° of 173.19°, there it misses by < 1 mm, and the printed
// value misses by centimetres.
TEST_CASE("TenKgColumnJointOneMisprintIsFoundBySweep", "[kinematics][table]") {
  const Eigen::Vector3d target = VehColumnEe();
  double best_deg = 0.0, best_miss = 1e9;
  for (int i = 0; i <= 2000; ++i) {  // 170.00° … 180.00° in 0.005° steps
    const double q1 = 170.0 + 0.005 * i;
    const double miss = Miss10kg(q1, target);
    if (miss < best_miss) {
      best_miss = miss;
      best_deg = q1;
    }
  }
  const double printed_miss = Miss10kg(double(UVMS_JOINT_TABLE_BARY_10KG_J1_PRINTED_DEG), target);
  const double corrected_miss = Miss10kg(ThetaF(5, 0), target);
  std::printf("10 kg column, joint 1: sweep minimum %.3f deg (miss %.4f m); table %.2f deg "
              "(miss %.4f m); printed %.2f deg (miss %.4f m)\n",
              best_deg, best_miss, ThetaF(5, 0), corrected_miss,
              double(UVMS_JOINT_TABLE_BARY_10KG_J1_PRINTED_DEG), printed_miss);
  CHECK(std::fabs(best_deg - 173.19) < 0.05);
  CHECK(ThetaF(5, 0) == Approx(173.19).margin(1e-4));  // the table carries the correction
  CHECK(corrected_miss < 1e-3);
  CHECK(printed_miss > 1e-2);
}

// docs/MODEL.md §10: the paper's target point (2.428, 0.250, 0.404) m, inertial, and the EE of
// its "Veh." column with the vehicle at the origin differ by exactly the arm-base offset s0, so
// the paper's frame puts the vehicle's CoM at s0; the task-space error's default target
// (sil/scenario/scenario.hpp, metrics.ee_target_m = (1.514, 0.250, 0.252) m) is the paper's point less
// s0. Checked to the paper's printed 1 mm.
TEST_CASE("PaperTargetPointIsVehColumnEePlusBaseOffset", "[kinematics][table]") {
  uvms_arm_params_t p;
  uvms_arm_params_paper(&p);
  const Eigen::Vector3d ee = VehColumnEe();
  const Eigen::Vector3d paper_point(2.428, 0.250, 0.404);
  const Eigen::Vector3d s0 = V(p.vehicle.base_offset_m);
  CHECK((ee + s0 - paper_point).norm() < 1e-3);
  CHECK((ee - Eigen::Vector3d(1.514, 0.250, 0.252)).norm() < 1e-3);
}
