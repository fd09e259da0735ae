// SPDX-License-Identifier: Apache-2.0
// faults.hpp: fault injection by the harness (the fault model is docs/FAULTS.md).
// Thruster faults act on the plant's inputs (off, stuck voltage, efficiency loss) and on the
// health mask the controller is told; sensor faults add bias and seeded Gaussian noise to the
// sensors message; link faults drop, delay by one tick, duplicate or corrupt (one random bit)
// sensors and actuators messages. Every random draw comes from the run seed, so a faulty run
// is as deterministic as a clean one.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "msg/codec.h"
#include "scenario/scenario.hpp"

namespace uvms::sil {

/// What happens to one message on a faulty link.
enum class LinkAction { kDeliver, kDrop, kDelay, kDuplicate, kCorrupt };

/// The link faults injected into one direction's messages (summary.json "faults":
/// sensors_dropped, ..., actuators_corrupted).
struct LinkCounters {
  long dropped{0}, delayed{0}, duplicated{0}, corrupted{0};
  void Count(LinkAction a);  ///< one more of a's kind (kDeliver: none)
};

/// Counts of everything injected (summary.json "faults").
struct FaultCounters {
  LinkCounters sensors, actuators;   ///< link faults by direction
  long sensor_samples_perturbed{0};  ///< sensors messages that got noise or bias
  long thruster_fault_ticks{0};      ///< ticks with at least one thruster fault active
};

class FaultInjector {
 public:
  FaultInjector(const FaultSettings &settings, std::uint64_t seed, int num_thrusters);

  /// Health mask for the sensors of time t: bit j clear once thruster j+1's fault is active,
  /// reported, and its detection delay has passed.
  std::uint32_t HealthMask(double t_s) const;
  /// Apply the thruster faults active at time t to the inputs held over the next tick.
  void ApplyThrusterFaults(double t_s, plant::PlantInputs &in);
  /// Add bias and noise to a sensors message (no-op without sensor faults).
  void PerturbSensors(uvms_sensors_t &s);
  /// Draw the fate of the next sensors / actuators message (kDeliver when the link is clean).
  LinkAction NextSensorsAction();
  LinkAction NextActuatorsAction();
  /// Flip one random bit of bytes[0, n).
  void Corrupt(std::uint8_t *bytes, int n);

  const FaultCounters &counters() const { return counters_; }
  FaultCounters &counters() { return counters_; }

 private:
  /// The fate of the next message of a direction (applies: the link faults act on it), counted.
  LinkAction Draw(bool applies, LinkCounters &counted);
  double Gauss(const SensorNoise &n);

  FaultSettings s_;
  int nt_;
  std::mt19937_64 noise_rng_, link_rng_;
  FaultCounters counters_;
};

}  // namespace uvms::sil
