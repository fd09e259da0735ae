// SPDX-License-Identifier: Apache-2.0
// plant_messages.cpp: the plant's truth as LCM messages (plant_messages.hpp).
#include "run/plant_messages.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace uvms::sil {
namespace {

void Copy3(double *dst, const plant::Vec3 &v) {
  for (int k = 0; k < 3; ++k) dst[k] = v[k];
}
void CopyQuat(double *wxyz, const Eigen::Quaterniond &q) {
  wxyz[0] = q.w();
  wxyz[1] = q.x();
  wxyz[2] = q.y();
  wxyz[3] = q.z();
}

// What sensors_t and truth_t share: tick, time, the vehicle's state, the joints, the motors.
template <typename Msg>
void FillMeasurable(const plant::Truth &t, long k, std::int64_t utime, Msg &m) {
  m.utime = utime;
  m.tick = k;
  Copy3(m.position_m, t.r0_m);
  CopyQuat(m.quaternion_wxyz, t.attitude);
  Copy3(m.velocity_m_s, t.v0_m_s);
  Copy3(m.angular_velocity_rad_s, t.w0_rad_s);
  for (size_t i = 0; i < t.q_rad.size() && i < 7; ++i) {
    m.joint_position_rad[i] = t.q_rad[i];
    m.joint_velocity_rad_s[i] = t.qd_rad_s[i];
  }
  for (size_t j = 0; j < t.motor_speed_rad_s.size() && j < 8; ++j) {
    m.motor_speed_rad_s[j] = t.motor_speed_rad_s[j];
    m.motor_current_A[j] = t.motor_current_A[j];
  }
}

}  // namespace

std::int64_t TickUtime(long k, double tick_s) { return std::llround(double(k) * tick_s * 1e6); }

void FillSensors(const plant::Truth &t, long k, std::int64_t utime, uvms_sensors_t &s) {
  std::memset(&s, 0, sizeof s);
  FillMeasurable(t, k, utime, s);
}

void FillTruthMsg(const plant::Truth &t, long k, std::int64_t utime, const std::string &pair,
                  uvms_truth_t &m) {
  std::memset(&m, 0, sizeof m);
  FillMeasurable(t, k, utime, m);
  Copy3(m.acceleration_m_s2, t.accel_m_s2);
  Copy3(m.angular_acceleration_rad_s2, t.alpha_rad_s2);
  for (size_t i = 0; i < t.q_rad.size() && i < 7; ++i)
    m.joint_torque_Nm[i] = i < t.joint_torque_Nm.size() ? t.joint_torque_Nm[i] : 0.0;
  for (size_t j = 0; j < t.motor_speed_rad_s.size() && j < 8; ++j) {
    m.motor_voltage_V[j] = t.motor_voltage_V[j];
    m.thrust_N[j] = t.thrust_N[j];
  }
  Copy3(m.thrust_force_N, t.thrust_force_N);
  Copy3(m.thrust_moment_Nm, t.thrust_moment_Nm);
  Copy3(m.ee_position_m, t.ee_m);
  Copy3(m.barycenter_m, t.barycenter_m);
  Copy3(m.barycenter_velocity_m_s, t.barycenter_v_m_s);
  Copy3(m.flow_velocity_m_s, t.flow_m_s);
  m.thruster_energy_J = t.thruster_energy_J;
  m.thruster_energy_signed_J = t.thruster_energy_signed_J;
  m.manipulator_energy_J = t.manipulator_energy_J;
  m.propulsive_energy_J = t.propulsive_energy_J;
  m.min_clearance_m = t.min_clearance_m;
  m.closest_pair = const_cast<char *>(pair.c_str());
}

SceneMessage::SceneMessage(const plant::PlantParams &p) {
  constexpr size_t kLinks = sizeof msg_.link_a_m / sizeof msg_.link_a_m[0];
  constexpr size_t kThrusters = sizeof msg_.thruster_direction / sizeof msg_.thruster_direction[0];
  if (p.links.size() > kLinks || p.thrusters.size() > kThrusters)
    throw std::length_error("the scene message holds at most " + std::to_string(kLinks) + " links and " +
                            std::to_string(kThrusters) + " thrusters; the plant has " +
                            std::to_string(p.links.size()) + " and " + std::to_string(p.thrusters.size()));
  std::memset(&msg_, 0, sizeof msg_);
  msg_.tick = -1;
  FillBody(p);
  FillObstacles(p.contact);
}

// Hull, arm kinematics and thrusters (fixed-size fields).
void SceneMessage::FillBody(const plant::PlantParams &p) {
  Copy3(msg_.hull_size_m, p.vehicle.hull_size_m);
  Copy3(msg_.hull_center_m, p.vehicle.hull_center_m);
  Copy3(msg_.base_offset_m, p.vehicle.base_offset_m);
  Copy3(msg_.base_rotvec_rad, p.vehicle.base_rotvec_rad);
  msg_.num_joints = std::int32_t(p.links.size());
  for (int i = 0; i < msg_.num_joints; ++i) {
    const plant::LinkParams &L = p.links[size_t(i)];
    msg_.link_alpha_rad[i] = L.alpha_rad;
    msg_.link_a_m[i] = L.a_m;
    msg_.link_d_m[i] = L.d_m;
    Copy3(msg_.link_placement_m[i], L.placement_m);
    Copy3(msg_.link_placement_rotvec_rad[i], L.placement_rotvec_rad);
    msg_.link_diameter_m[i] = L.diameter_m;
  }
  msg_.payload_kg = p.payload_kg;
  Copy3(msg_.payload_offset_m, p.payload_offset_m);
  msg_.num_thrusters = std::int32_t(p.thrusters.size());
  for (int j = 0; j < msg_.num_thrusters; ++j) {
    Copy3(msg_.thruster_position_m[j], p.thrusters[size_t(j)].position_m);
    Copy3(msg_.thruster_direction[j], p.thrusters[size_t(j)].direction);
  }
}

// The contact monitor's settings and obstacles (variable-length fields point into this object).
void SceneMessage::FillObstacles(const plant::ContactParams &c) {
  msg_.contact_enabled = c.enabled ? 1 : 0;
  msg_.self_collision = c.self_collision ? 1 : 0;
  msg_.clearance_m = c.clearance_m;
  const size_t n = c.obstacles.size();
  names_.reserve(n);  // no reallocation below: the pointers stay valid
  centers_m_.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const plant::CylinderObstacle &o = c.obstacles[k];
    names_.push_back(o.name);
    name_ptrs_.push_back(const_cast<char *>(names_.back().c_str()));
    for (int d = 0; d < 3; ++d) centers_m_[k][size_t(d)] = o.base_center_m[d];
    center_ptrs_.push_back(centers_m_[k].data());
    heights_m_.push_back(o.height_m);
    radii_m_.push_back(o.radius_m);
  }
  msg_.num_obstacles = std::int32_t(n);
  msg_.obstacle_name = name_ptrs_.data();
  msg_.obstacle_base_center_m = center_ptrs_.data();
  msg_.obstacle_height_m = heights_m_.data();
  msg_.obstacle_radius_m = radii_m_.data();
}

}  // namespace uvms::sil
