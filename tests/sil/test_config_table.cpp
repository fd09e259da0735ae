// SPDX-License-Identifier: Apache-2.0
// The table of configuration fields (sil/msg/config_table.h) drives the codec in both directions
// and the PIL record. Every field gets a distinct value and must survive
//   config → controller_config_t (encoded and decoded) → config → PIL record (→ config)
// in the build's precision: the host build checks the double chain up to the record (the PIL
// record → config leg needs the float firmware: tests/pil/test_pil_map.cpp runs the whole chain
// against it), the host-float build the whole float chain. A field dropped by either direction
// comes back as 0; a field of the message without a row of the table fails the size check (and
// a firmware field without one, test_codec.cpp's paper configurations byte for byte).
#include <catch2/catch.hpp>

#include <cstring>
#include <functional>

#include "msg/codec.h"
#include "config_fill.hpp"

using config_fill::FirstDifference;

TEST_CASE("EveryFieldOfTheMessageHasARowInTheTable", "[config_table]") {
  uvms_controller_config_t m{};
  CHECK(config_fill::EncodedBytesOfTheTable() ==
        static_cast<std::size_t>(uvms_controller_config_t_encoded_size(&m)));
}

TEST_CASE("EveryFieldWithADistinctValueSurvivesMessageAndPilRecord", "[config_table]") {
  config_fill::CheckDistinctRoundTrip();
}

TEST_CASE("OutOfRangeCountsAndEnumsAreRejected", "[config_table]") {
  uvms_ctrl_config_t cfg;
  REQUIRE(uvms_ctrl_config_paper(&cfg, 7) == UVMS_OK);
  uvms_controller_config_t good;
  uvms_config_to_msg(&cfg, &good);
  uvms_ctrl_config_t zero;
  std::memset(&zero, 0, sizeof zero);
  const std::function<void(uvms_controller_config_t &)> breakers[] = {
      [](auto &m) { m.num_joints = 0; },        [](auto &m) { m.num_thrusters = 9; },
      [](auto &m) { m.position_reference = 2; }, [](auto &m) { m.cart_reference = -1; },
      [](auto &m) { m.traj_mode = 3; },          [](auto &m) { m.drive = 2; },
      [](auto &m) { m.alloc_mode = 3; },
      [](auto &m) { m.sensor_hold_max_ticks = -1; }};
  for (const auto &breaker : breakers) {
    uvms_controller_config_t m = good;
    breaker(m);
    uvms_ctrl_config_t out;
    CHECK(uvms_config_from_msg(&m, &out) == -1);
    CHECK(FirstDifference(out, zero) == -1);  // zeroed: uvms_ctrl_init rejects it
  }
}
