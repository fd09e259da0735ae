// SPDX-License-Identifier: Apache-2.0
// Generated C encoder -> generated C++ decoder round trip for every message type, with
// decoded size equal to encoded size, and rejection of truncated buffers.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

extern "C" {
#include "uvms_actuators_t.h"
#include "uvms_sensors_t.h"
}
#include "uvms/actuators_t.hpp"
#include "uvms/sensors_t.hpp"

namespace {
template <size_t N>
void Fill(double (&a)[N], std::mt19937 &rng) {
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (auto &x : a) x = u(rng);
}
}  // namespace

TEST_CASE("SensorsCEncodeCppDecodeIsExact", "[lcm]") {
  std::mt19937 rng(2024);
  uvms_sensors_t c{};
  c.utime = 30000;
  c.tick = 1;
  c.session = int64_t(0xfedcba9876543210ULL);
  Fill(c.position_m, rng);
  Fill(c.quaternion_wxyz, rng);
  Fill(c.velocity_m_s, rng);
  Fill(c.angular_velocity_rad_s, rng);
  Fill(c.joint_position_rad, rng);
  Fill(c.joint_velocity_rad_s, rng);
  Fill(c.motor_speed_rad_s, rng);
  Fill(c.motor_current_A, rng);
  std::vector<uint8_t> buf(static_cast<size_t>(uvms_sensors_t_encoded_size(&c)));
  const int n = uvms_sensors_t_encode(buf.data(), 0, static_cast<int>(buf.size()), &c);
  REQUIRE(n == static_cast<int>(buf.size()));

  uvms::sensors_t cpp;
  REQUIRE(cpp.decode(buf.data(), 0, n) == n);
  CHECK(cpp.utime == c.utime);
  CHECK(cpp.tick == c.tick);
  CHECK(cpp.session == c.session);
  for (int i = 0; i < 3; ++i) CHECK(cpp.position_m[i] == c.position_m[i]);
  for (int i = 0; i < 4; ++i) CHECK(cpp.quaternion_wxyz[i] == c.quaternion_wxyz[i]);
  for (int i = 0; i < 7; ++i) CHECK(cpp.joint_position_rad[i] == c.joint_position_rad[i]);
  for (int i = 0; i < 8; ++i) CHECK(cpp.motor_current_A[i] == c.motor_current_A[i]);
  CHECK(cpp.NUM_JOINTS == 7);
  CHECK(cpp.NUM_THRUSTERS == 8);

  // A truncated buffer must be rejected, not decoded into garbage.
  uvms::sensors_t cut;
  CHECK(cut.decode(buf.data(), 0, n - 1) < 0);
}

TEST_CASE("ActuatorsCppEncodeCDecodeIsExact", "[lcm]") {
  std::mt19937 rng(7);
  uvms::actuators_t cpp{};
  cpp.utime = 60000;
  cpp.tick = 2;
  Fill(cpp.motor_voltage_V, rng);
  Fill(cpp.joint_acceleration_rad_s2, rng);
  Fill(cpp.motor_current_cmd_A, rng);
  Fill(cpp.motor_current_rate_A_s, rng);
  cpp.status = -2;
  std::vector<uint8_t> buf(static_cast<size_t>(cpp.getEncodedSize()));
  REQUIRE(cpp.encode(buf.data(), 0, static_cast<int>(buf.size())) == static_cast<int>(buf.size()));
  uvms_actuators_t c{};
  REQUIRE(uvms_actuators_t_decode(buf.data(), 0, static_cast<int>(buf.size()), &c) ==
          static_cast<int>(buf.size()));
  for (int i = 0; i < 8; ++i) CHECK(c.motor_voltage_V[i] == cpp.motor_voltage_V[i]);
  for (int i = 0; i < 7; ++i) CHECK(c.joint_acceleration_rad_s2[i] == cpp.joint_acceleration_rad_s2[i]);
  for (int i = 0; i < 8; ++i) CHECK(c.motor_current_cmd_A[i] == cpp.motor_current_cmd_A[i]);
  for (int i = 0; i < 8; ++i) CHECK(c.motor_current_rate_A_s[i] == cpp.motor_current_rate_A_s[i]);
  CHECK(c.status == -2);
  uvms_actuators_t_decode_cleanup(&c);
}
