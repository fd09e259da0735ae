// SPDX-License-Identifier: Apache-2.0
// The scene message (scene_t, sil/run/plant_messages.hpp): what the plant's parameters put in it
// reads back through LCM's own C decoder; the largest scene a scenario may declare
// (kMaxObstacles obstacles with names of kMaxObstacleName bytes, sil/scenario/scenario.hpp) encodes within
// UVMS_MAX_MSG_BYTES; one obstacle more does not fit the scenario (sil.scenario checks the error).
#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "msg/codec.h"
#include "run/plant_messages.hpp"
#include "scenario/scenario.hpp"

using uvms::sil::SceneMessage;

namespace {

uvms::plant::PlantParams WithObstacles(size_t n, size_t name_bytes) {
  uvms::plant::PlantParams p = uvms::plant::PaperPlantParams();
  for (size_t k = 0; k < n; ++k) {
    uvms::plant::CylinderObstacle o;
    o.name = std::string(name_bytes, char('a' + k % 26));
    o.base_center_m = {double(k), -double(k), 0.5 * double(k)};
    o.height_m = 1.0 + double(k);
    o.radius_m = 0.1 + 0.01 * double(k);
    p.contact.obstacles.push_back(o);
  }
  return p;
}

}  // namespace

TEST_CASE("SceneMessageReadsBackThroughLcmsDecoder", "[scene]") {
  const uvms::plant::PlantParams p = WithObstacles(3, 7);
  const SceneMessage scene(p);
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
  const int n = uvms_scene_t_encode_sealed(&scene.msg(), buf.data(), int(buf.size()));
  REQUIRE(n > 0);
  CHECK(uvms_crc_check(buf.data(), n) == 1);
  uvms_scene_t m{};
  REQUIRE(uvms_scene_t_decode(buf.data(), 0, n, &m) == n);  // LCM's decoder (allocates: test only)
  CHECK(m.tick == -1);
  CHECK(m.num_joints == int(p.links.size()));
  CHECK(m.num_thrusters == int(p.thrusters.size()));
  for (int c = 0; c < 3; ++c) {
    CHECK(m.hull_size_m[c] == p.vehicle.hull_size_m[c]);
    CHECK(m.hull_center_m[c] == p.vehicle.hull_center_m[c]);
    CHECK(m.base_offset_m[c] == p.vehicle.base_offset_m[c]);
  }
  for (int i = 0; i < m.num_joints; ++i) {
    CHECK(m.link_alpha_rad[i] == p.links[size_t(i)].alpha_rad);
    CHECK(m.link_d_m[i] == p.links[size_t(i)].d_m);
    CHECK(m.link_diameter_m[i] == p.links[size_t(i)].diameter_m);
  }
  for (int j = 0; j < m.num_thrusters; ++j)
    for (int c = 0; c < 3; ++c) CHECK(m.thruster_direction[j][c] == p.thrusters[size_t(j)].direction[c]);
  REQUIRE(m.num_obstacles == 3);
  for (int k = 0; k < 3; ++k) {
    CHECK(std::string(m.obstacle_name[k]) == p.contact.obstacles[size_t(k)].name);
    CHECK(m.obstacle_base_center_m[k][1] == p.contact.obstacles[size_t(k)].base_center_m[1]);
    CHECK(m.obstacle_radius_m[k] == p.contact.obstacles[size_t(k)].radius_m);
  }
  uvms_scene_t_decode_cleanup(&m);
}

TEST_CASE("TheLargestSceneAScenarioAllowsFitsOneMessage", "[scene]") {
  const SceneMessage scene(WithObstacles(uvms::sil::kMaxObstacles, uvms::sil::kMaxObstacleName));
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
  const int n = uvms_scene_t_encode_sealed(&scene.msg(), buf.data(), int(buf.size()));
  INFO("encoded " << n << " bytes of " << UVMS_MAX_MSG_BYTES);
  CHECK(n > 0);
  CHECK(uvms_scene_t_encoded_size(&scene.msg()) <= UVMS_MAX_MSG_BYTES);
}

TEST_CASE("APlantTheSceneMessageCannotHoldIsRefusedNotTruncated", "[scene]") {
  uvms::plant::PlantParams p = uvms::plant::PaperPlantParams();
  p.thrusters.push_back(p.thrusters.front());  // a ninth thruster
  CHECK_THROWS_WITH(SceneMessage(p), Catch::Contains("at most 7 links and 8 thrusters"));
  p = uvms::plant::PaperPlantParams();
  p.links.push_back(p.links.front());  // an eighth link
  CHECK_THROWS_AS(SceneMessage(p), std::length_error);
}
