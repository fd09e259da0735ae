// SPDX-License-Identifier: Apache-2.0
// faults.cpp: fault injection by the harness (faults.hpp, docs/FAULTS.md).
#include "run/faults.hpp"

#include <Eigen/Geometry>

namespace uvms::sil {

FaultInjector::FaultInjector(const FaultSettings &settings, std::uint64_t seed, int num_thrusters)
    : s_(settings),
      nt_(num_thrusters),
      // Independent streams: the sensor noise does not shift when link rates change.
      noise_rng_(seed * 0x9E3779B97F4A7C15ull + 0x5E4501),
      link_rng_(seed * 0x9E3779B97F4A7C15ull + 0x11A4) {}

std::uint32_t FaultInjector::HealthMask(double t_s) const {
  std::uint32_t mask = (nt_ >= 32) ? 0xFFFFFFFFu : ((1u << unsigned(nt_)) - 1u);
  for (const ThrusterFault &f : s_.thrusters) {
    if (f.reported && t_s + 1e-12 >= f.start_s + f.detect_delay_s)
      mask &= ~(1u << unsigned(f.thruster - 1));
  }
  return mask;
}

void FaultInjector::ApplyThrusterFaults(double t_s, plant::PlantInputs &in) {
  bool any = false;
  for (const ThrusterFault &f : s_.thrusters) {
    if (t_s + 1e-12 < f.start_s) continue;
    any = true;
    const auto j = size_t(f.thruster - 1);
    switch (f.mode) {
      case ThrusterFault::Mode::kOff:  // no voltage (voltage drive), no current (current drive)
        in.motor_voltage_V[j] = 0.0;
        in.motor_current_cmd_A[j] = 0.0;
        in.motor_current_rate_A_s[j] = 0.0;
        break;
      case ThrusterFault::Mode::kStuck:  // the power stage ignores the command
        in.motor_voltage_V[j] = f.stuck_voltage_V;
        in.motor_current_cmd_A[j] = f.stuck_current_A;
        in.motor_current_rate_A_s[j] = 0.0;
        break;
      case ThrusterFault::Mode::kEfficiency:
        if (in.thrust_factor.empty()) in.thrust_factor.assign(size_t(nt_), 1.0);
        in.thrust_factor[j] = f.efficiency;
        break;
    }
  }
  if (any) ++counters_.thruster_fault_ticks;
}

double FaultInjector::Gauss(const SensorNoise &n) {
  if (n.std == 0.0) return n.bias;
  std::normal_distribution<double> g(0.0, n.std);
  return n.bias + g(noise_rng_);
}

void FaultInjector::PerturbSensors(uvms_sensors_t &m) {
  const SensorFaults &f = s_.sensors;
  if (!f.any()) return;
  ++counters_.sensor_samples_perturbed;
  for (int k = 0; k < 3; ++k) {
    m.position_m[k] += Gauss(f.position_m);
    m.velocity_m_s[k] += Gauss(f.velocity_m_s);
    m.angular_velocity_rad_s[k] += Gauss(f.angular_velocity_rad_s);
  }
  // Attitude: a small rotation δ (rotation vector, inertial) applied to R0, renormalised.
  const Eigen::Vector3d d(Gauss(f.attitude_rad), Gauss(f.attitude_rad), Gauss(f.attitude_rad));
  if (d.norm() > 0.0) {
    const Eigen::Quaterniond q(m.quaternion_wxyz[0], m.quaternion_wxyz[1], m.quaternion_wxyz[2],
                               m.quaternion_wxyz[3]);
    const Eigen::Quaterniond r =
        (Eigen::Quaterniond(Eigen::AngleAxisd(d.norm(), d.normalized())) * q).normalized();
    m.quaternion_wxyz[0] = r.w();
    m.quaternion_wxyz[1] = r.x();
    m.quaternion_wxyz[2] = r.y();
    m.quaternion_wxyz[3] = r.z();
  }
  for (int i = 0; i < 7; ++i) {
    m.joint_position_rad[i] += Gauss(f.joint_position_rad);
    m.joint_velocity_rad_s[i] += Gauss(f.joint_velocity_rad_s);
  }
  for (int j = 0; j < 8; ++j) {
    m.motor_speed_rad_s[j] += Gauss(f.motor_speed_rad_s);
    m.motor_current_A[j] += Gauss(f.motor_current_A);
  }
}

void LinkCounters::Count(LinkAction a) {
  switch (a) {
    case LinkAction::kDrop: ++dropped; break;
    case LinkAction::kDelay: ++delayed; break;
    case LinkAction::kDuplicate: ++duplicated; break;
    case LinkAction::kCorrupt: ++corrupted; break;
    case LinkAction::kDeliver: break;
  }
}

LinkAction FaultInjector::Draw(bool applies, LinkCounters &counted) {
  const LinkFaults &l = s_.link;
  if (!applies || !l.any()) return LinkAction::kDeliver;
  const double u = std::uniform_real_distribution<double>(0.0, 1.0)(link_rng_);
  double c = l.drop_rate;
  LinkAction a = LinkAction::kDeliver;
  if (u < c)
    a = LinkAction::kDrop;
  else if (u < (c += l.delay_rate))
    a = LinkAction::kDelay;
  else if (u < (c += l.duplicate_rate))
    a = LinkAction::kDuplicate;
  else if (u < (c += l.corrupt_rate))
    a = LinkAction::kCorrupt;
  counted.Count(a);
  return a;
}

LinkAction FaultInjector::NextSensorsAction() { return Draw(s_.link.sensors, counters_.sensors); }

LinkAction FaultInjector::NextActuatorsAction() {
  return Draw(s_.link.actuators, counters_.actuators);
}

void FaultInjector::Corrupt(std::uint8_t *bytes, int n) {
  if (n <= 0) return;
  const auto bit = std::uniform_int_distribution<long>(0, long(n) * 8 - 1)(link_rng_);
  bytes[bit / 8] ^= std::uint8_t(1u << unsigned(bit % 8));
}

}  // namespace uvms::sil
