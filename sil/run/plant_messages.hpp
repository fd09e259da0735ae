// SPDX-License-Identifier: Apache-2.0
// plant_messages.hpp: the plant's truth as LCM messages (sensors_t, truth_t, scene_t; lcmtypes/).
#pragma once

#include <cstdint>
#include <array>
#include <string>
#include <vector>

#include "msg/codec.h"
#include "uvms_plant/plant.hpp"

namespace uvms::sil {

/// Simulated time of tick k as LCM utime [µs].
std::int64_t TickUtime(long k, double tick_s);

/// The sensors message of tick k from the truth (exact values: noise and the health mask are
/// the fault injector's, sil/run/faults.hpp).
void FillSensors(const plant::Truth &t, long k, std::int64_t utime, uvms_sensors_t &s);

/// The truth message of tick k. m.closest_pair points into `pair`, which must outlive m.
void FillTruthMsg(const plant::Truth &t, long k, std::int64_t utime, const std::string &pair,
                  uvms_truth_t &m);

/// The scene message (scene_t) of the plant's parameters: hull, arm kinematics, thrusters and
/// contact scene, the geometry a viewer draws (tools/uvmsviz.py). Owns the storage that the
/// message's variable-length fields (obstacles) point into, so it is neither copied nor moved.
class SceneMessage {
 public:
  explicit SceneMessage(const plant::PlantParams &p);
  SceneMessage(const SceneMessage &) = delete;
  SceneMessage &operator=(const SceneMessage &) = delete;
  const uvms_scene_t &msg() const { return msg_; }

 private:
  void FillBody(const plant::PlantParams &p);
  void FillObstacles(const plant::ContactParams &c);

  std::vector<std::string> names_;
  std::vector<char *> name_ptrs_;
  std::vector<std::array<double, 3>> centers_m_;
  std::vector<double *> center_ptrs_;
  std::vector<double> heights_m_, radii_m_;
  uvms_scene_t msg_{};
};

}  // namespace uvms::sil
