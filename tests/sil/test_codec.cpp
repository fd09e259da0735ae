// SPDX-License-Identifier: Apache-2.0
// The SIL message layer (sil/msg/codec.h) and the controller node's message logic
// (sil/link/controller_node.h): CRC against the standard check value, every single-bit corruption
// and every truncation rejected, configuration mapping round trip, and the node's drop-and-
// count rules under arbitrary bytes.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "msg/codec.h"
#include "link/controller_node.h"
#include "link/lcm_wait.h"
#include "msg/session.h"

namespace {

constexpr int64_t kSession = 0x5e55104e2026abcdLL;  // this file's run session

std::vector<uint8_t> EncodeSensors(const uvms_sensors_t &s) {
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
  const int n = uvms_sensors_t_encode_sealed(&s, buf.data(), int(buf.size()));
  REQUIRE(n > 0);
  buf.resize(size_t(n));
  return buf;
}

std::vector<uint8_t> PaperConfigBytes(int case_number, int64_t session = kSession) {
  uvms_ctrl_config_t cfg;
  REQUIRE(uvms_ctrl_config_paper(&cfg, case_number) == UVMS_OK);
  uvms_controller_config_t msg;
  uvms_config_to_msg(&cfg, &msg);
  msg.session = session;
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
  const int n = uvms_controller_config_t_encode_sealed(&msg, buf.data(), int(buf.size()));
  REQUIRE(n > 0);
  buf.resize(size_t(n));
  return buf;
}

// A plausible sensor message: the paper's stowed pose, vehicle at rest at the origin.
uvms_sensors_t RestSensors(int64_t tick, int64_t session = kSession) {
  uvms_sensors_t s{};
  s.utime = tick * 30000;
  s.tick = tick;
  s.session = session;
  s.quaternion_wxyz[0] = 1.0;
  const double q[7] = {M_PI, M_PI / 2, M_PI, M_PI, 0, 0, 0};
  for (int i = 0; i < 7; ++i) s.joint_position_rad[i] = q[i];
  s.thruster_usable_mask = 0xff;
  return s;
}

}  // namespace

TEST_CASE("Crc32MatchesTheStandardCheckValue", "[codec]") {
  // CRC-32/ISO-HDLC check value of "123456789" (the catalogue value, not our output).
  const char *s = "123456789";
  CHECK(uvms_crc32(reinterpret_cast<const uint8_t *>(s), 9) == 0xCBF43926u);
  CHECK(uvms_crc32(nullptr, 0) == 0u);
}

TEST_CASE("Crc32EqualsABitAtATimeCrcForEveryLengthAndAlignment", "[codec]") {
  // The codec's CRC comes from a library (ISA-L's carry-less multiply folding, or zlib's; the
  // build says which); the reference here shifts one bit at a time through the reflected
  // polynomial, with no table at all.
  auto bitwise = [](const uint8_t *d, size_t n) {
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i) {
      c ^= d[i];
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
  };
  std::mt19937 rng(20261123);  // fixed seed
  std::vector<uint8_t> buf(4096 + 16);
  for (auto &b : buf) b = uint8_t(rng());
  for (size_t offset = 0; offset < 8; ++offset) {
    for (size_t n = 0; n <= 70; ++n) CHECK(uvms_crc32(buf.data() + offset, n) == bitwise(buf.data() + offset, n));
    CHECK(uvms_crc32(buf.data() + offset, 4096) == bitwise(buf.data() + offset, 4096));
  }
}

TEST_CASE("EverySingleBitFlipAndEveryTruncationIsRejected", "[codec]") {
  uvms_sensors_t s = RestSensors(7);
  s.velocity_m_s[1] = 0.125;
  const std::vector<uint8_t> good = EncodeSensors(s);
  uvms_sensors_t out;
  REQUIRE(uvms_sensors_t_decode_checked(good.data(), int(good.size()), &out) == int(good.size()));
  CHECK(out.tick == 7);
  CHECK(out.velocity_m_s[1] == 0.125);
  long rejected = 0, total = 0;
  for (size_t byte = 0; byte < good.size(); ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<uint8_t> bad = good;
      bad[byte] ^= uint8_t(1u << bit);
      ++total;
      rejected += uvms_sensors_t_decode_checked(bad.data(), int(bad.size()), &out) < 0;
    }
  }
  CHECK(rejected == total);
  for (size_t len = 0; len < good.size(); ++len) {
    CHECK(uvms_sensors_t_decode_checked(good.data(), int(len), &out) < 0);
  }
  std::vector<uint8_t> longer = good;
  longer.push_back(0);
  CHECK(uvms_sensors_t_decode_checked(longer.data(), int(longer.size()), &out) == -1);
}

TEST_CASE("ConfigurationSurvivesTheMessageBitForBit", "[codec]") {
  for (int c = 1; c <= 8; ++c) {
    uvms_ctrl_config_t cfg;
    REQUIRE(uvms_ctrl_config_paper(&cfg, c) == UVMS_OK);
    cfg.arm.vehicle.ballast_kg = 1.25;  // fields the paper leaves zero must travel too
    cfg.arm.vehicle.ballast_offset_m[0] = -0.75;
    cfg.fluid.gravity_m_s2[2] = -1.315;
    cfg.traj_mode = UVMS_TRAJ_CARTESIAN_LINE;
    const std::vector<uint8_t> bytes = [&] {
      uvms_controller_config_t msg;
      uvms_config_to_msg(&cfg, &msg);
      std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
      const int n = uvms_controller_config_t_encode_sealed(&msg, buf.data(), int(buf.size()));
      buf.resize(size_t(n));
      return buf;
    }();
    uvms_controller_config_t msg;
    REQUIRE(uvms_controller_config_t_decode_checked(bytes.data(), int(bytes.size()), &msg) > 0);
    uvms_ctrl_config_t back;
    REQUIRE(uvms_config_from_msg(&msg, &back) == 0);
    // Byte for byte (both zero their padding): also catches a firmware field that no row of
    // sil/msg/config_table.h carries, which the paper configuration sets and the message drops.
    CHECK(std::memcmp(&cfg, &back, sizeof cfg) == 0);
    // And through a second encoding.
    uvms_controller_config_t msg2;
    uvms_config_to_msg(&back, &msg2);
    std::vector<uint8_t> again(UVMS_MAX_MSG_BYTES);
    const int n2 = uvms_controller_config_t_encode_sealed(&msg2, again.data(), int(again.size()));
    again.resize(size_t(n2));
    CHECK(again == bytes);
    CHECK(back.switches.position_reference == cfg.switches.position_reference);
    CHECK(back.traj_mode == UVMS_TRAJ_CARTESIAN_LINE);
    CHECK(back.arm.vehicle.ballast_kg == 1.25);
    CHECK(back.arm.vehicle.ballast_offset_m[0] == -0.75);
    CHECK(back.arm.num_joints == 7);
  }
}

TEST_CASE("ConfigurationWithImpossibleCountsIsRefused", "[codec]") {
  uvms_ctrl_config_t cfg;
  REQUIRE(uvms_ctrl_config_paper(&cfg, 4) == UVMS_OK);
  uvms_controller_config_t msg;
  uvms_config_to_msg(&cfg, &msg);
  uvms_ctrl_config_t back;
  msg.num_joints = 8;
  CHECK(uvms_config_from_msg(&msg, &back) == -1);
  msg.num_joints = 7;
  msg.position_reference = 2;
  CHECK(uvms_config_from_msg(&msg, &back) == -1);
  msg.position_reference = 1;
  msg.traj_mode = 3;
  CHECK(uvms_config_from_msg(&msg, &back) == -1);
}

TEST_CASE("NodeAnswersConfigThenSensorsAndDropsWhatItMust", "[node]") {
  auto node = std::make_unique<uvms_ctrl_node_t>();
  auto out = std::make_unique<uvms_ctrl_node_out_t>();
  uvms_ctrl_node_init(node.get());

  const std::vector<uint8_t> s0 = EncodeSensors(RestSensors(0));
  uvms_ctrl_node_on_sensors(node.get(), s0.data(), int(s0.size()), out.get());
  CHECK_FALSE(out->has_actuators);
  CHECK(node->rx_unconfigured == 1);

  const std::vector<uint8_t> cfg = PaperConfigBytes(7);
  uvms_ctrl_node_on_config(node.get(), cfg.data(), int(cfg.size()), out.get());
  REQUIRE(out->has_telemetry);
  CHECK(out->telemetry.tick == -1);
  CHECK(out->telemetry.status == UVMS_OK);
  CHECK(out->telemetry.rx_unconfigured == 1);

  uvms_ctrl_node_on_sensors(node.get(), s0.data(), int(s0.size()), out.get());
  REQUIRE(out->has_actuators);
  CHECK(out->actuators.tick == 0);
  CHECK(out->telemetry.tick == 0);
  // Same tick again, then an older one: both dropped, counted, unanswered.
  uvms_ctrl_node_on_sensors(node.get(), s0.data(), int(s0.size()), out.get());
  CHECK_FALSE(out->has_actuators);
  CHECK(node->rx_out_of_sequence == 1);
  const std::vector<uint8_t> s2 = EncodeSensors(RestSensors(2));
  uvms_ctrl_node_on_sensors(node.get(), s2.data(), int(s2.size()), out.get());
  REQUIRE(out->has_actuators);
  CHECK((uint32_t(out->actuators.flags) & UVMS_FLAG_TICK_GAP) != 0);  // firmware saw the gap
  const std::vector<uint8_t> s1 = EncodeSensors(RestSensors(1));
  uvms_ctrl_node_on_sensors(node.get(), s1.data(), int(s1.size()), out.get());
  CHECK_FALSE(out->has_actuators);
  CHECK(node->rx_out_of_sequence == 2);
  CHECK(node->steps == 2);
}

TEST_CASE("SensorsFarAheadOfTheExpectedTickAreRejected", "[node][session]") {
  auto node = std::make_unique<uvms_ctrl_node_t>();
  auto out = std::make_unique<uvms_ctrl_node_out_t>();
  uvms_ctrl_node_init(node.get());
  const std::vector<uint8_t> cfg = PaperConfigBytes(7);
  uvms_ctrl_node_on_config(node.get(), cfg.data(), int(cfg.size()), out.get());
  REQUIRE(out->telemetry.status == UVMS_OK);
  // A negative tick, and a first record beyond the window: dropped, counted.
  for (int64_t k : {int64_t{-5}, int64_t{UVMS_CTRL_NODE_TICK_WINDOW} + 1}) {
    const std::vector<uint8_t> s = EncodeSensors(RestSensors(k));
    uvms_ctrl_node_on_sensors(node.get(), s.data(), int(s.size()), out.get());
    CHECK_FALSE(out->has_actuators);
  }
  CHECK(node->rx_out_of_sequence == 2);
  const std::vector<uint8_t> s0 = EncodeSensors(RestSensors(0));
  uvms_ctrl_node_on_sensors(node.get(), s0.data(), int(s0.size()), out.get());
  REQUIRE(out->has_actuators);
  // A forged far-future record (tick 1e12) is dropped and does not lock out tick 1.
  const std::vector<uint8_t> far = EncodeSensors(RestSensors(1000000000000));
  uvms_ctrl_node_on_sensors(node.get(), far.data(), int(far.size()), out.get());
  CHECK_FALSE(out->has_actuators);
  CHECK(node->rx_out_of_sequence == 3);
  const std::vector<uint8_t> s1 = EncodeSensors(RestSensors(1));
  uvms_ctrl_node_on_sensors(node.get(), s1.data(), int(s1.size()), out.get());
  CHECK(out->has_actuators);
  // Within the window a gap is passed on (the firmware flags it).
  const std::vector<uint8_t> sw = EncodeSensors(RestSensors(1 + UVMS_CTRL_NODE_TICK_WINDOW));
  uvms_ctrl_node_on_sensors(node.get(), sw.data(), int(sw.size()), out.get());
  CHECK(out->has_actuators);
  CHECK(node->steps == 3);
}

namespace {

// Case IV's configuration with a negative position gain: uvms_ctrl_init refuses it (gains).
std::vector<uint8_t> RefusedConfigBytes(int64_t session) {
  uvms_ctrl_config_t cfg;
  REQUIRE(uvms_ctrl_config_paper(&cfg, 4) == UVMS_OK);
  cfg.gains.kpf_N_m = -1.0;
  uvms_controller_config_t msg;
  uvms_config_to_msg(&cfg, &msg);
  msg.session = session;
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
  const int n = uvms_controller_config_t_encode_sealed(&msg, buf.data(), int(buf.size()));
  REQUIRE(n > 0);
  buf.resize(size_t(n));
  return buf;
}

std::vector<uint8_t> StatusBytes(int8_t state, int64_t session) {
  uvms_run_status_t st{};
  st.state = state;
  st.session = session;
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
  const int n = uvms_run_status_t_encode_sealed(&st, buf.data(), int(buf.size()));
  REQUIRE(n > 0);
  buf.resize(size_t(n));
  return buf;
}

}  // namespace

TEST_CASE("MessagesOfAnotherSessionAreDroppedCountedAndNeverObeyed", "[node][session]") {
  constexpr int64_t kOther = 0x0123456789abcdefLL;
  auto node = std::make_unique<uvms_ctrl_node_t>();
  auto out = std::make_unique<uvms_ctrl_node_out_t>();
  uvms_ctrl_node_init(node.get());
  uvms_ctrl_node_set_session(node.get(), kSession);
  // Another run's configuration (valid in every other respect) is not taken, nor answered.
  const std::vector<uint8_t> foreign_cfg = PaperConfigBytes(7, kOther);
  uvms_ctrl_node_on_config(node.get(), foreign_cfg.data(), int(foreign_cfg.size()), out.get());
  CHECK_FALSE(out->has_telemetry);
  CHECK_FALSE(node->configured);
  CHECK(node->rx_foreign_session == 1);
  const std::vector<uint8_t> cfg = PaperConfigBytes(7);
  uvms_ctrl_node_on_config(node.get(), cfg.data(), int(cfg.size()), out.get());
  REQUIRE(out->has_telemetry);
  CHECK(out->telemetry.session == kSession);
  CHECK(out->telemetry.status == UVMS_OK);
  // Sensors of another session, or of none: dropped, counted, unanswered.
  for (int64_t other : {kOther, int64_t{UVMS_SESSION_NONE}}) {
    const std::vector<uint8_t> s = EncodeSensors(RestSensors(0, other));
    uvms_ctrl_node_on_sensors(node.get(), s.data(), int(s.size()), out.get());
    CHECK_FALSE(out->has_actuators);
    CHECK_FALSE(out->has_telemetry);
  }
  CHECK(node->rx_foreign_session == 3);
  CHECK(node->rx_out_of_sequence == 0);  // they did not consume tick 0
  // Another run's end status does not stop the node.
  for (int8_t state : {int8_t{UVMS_RUN_STATUS_T_FINISHED}, int8_t{UVMS_RUN_STATUS_T_FAILED}}) {
    const std::vector<uint8_t> st = StatusBytes(state, kOther);
    uvms_ctrl_node_on_status(node.get(), st.data(), int(st.size()));
  }
  CHECK_FALSE(node->finished);
  CHECK(node->rx_foreign_session == 5);
  // Its own tick 0 is answered, stamped with its session, and reports the count.
  const std::vector<uint8_t> s0 = EncodeSensors(RestSensors(0));
  uvms_ctrl_node_on_sensors(node.get(), s0.data(), int(s0.size()), out.get());
  REQUIRE(out->has_actuators);
  CHECK(out->actuators.session == kSession);
  CHECK(out->telemetry.session == kSession);
  CHECK(out->telemetry.rx_foreign_session == 5);
  const std::vector<uint8_t> end = StatusBytes(UVMS_RUN_STATUS_T_FINISHED, kSession);
  uvms_ctrl_node_on_status(node.get(), end.data(), int(end.size()));
  CHECK(node->finished);
}

TEST_CASE("NodeWithoutASessionAdoptsTheFirstAcceptedConfiguration", "[node][session]") {
  constexpr int64_t kOther = 0x0123456789abcdefLL;
  auto node = std::make_unique<uvms_ctrl_node_t>();
  auto out = std::make_unique<uvms_ctrl_node_out_t>();
  uvms_ctrl_node_init(node.get());
  // Before any configuration no status is obeyed.
  const std::vector<uint8_t> early = StatusBytes(UVMS_RUN_STATUS_T_FINISHED, kSession);
  uvms_ctrl_node_on_status(node.get(), early.data(), int(early.size()));
  CHECK_FALSE(node->finished);
  // A configuration without a session is foreign.
  const std::vector<uint8_t> none = PaperConfigBytes(7, UVMS_SESSION_NONE);
  uvms_ctrl_node_on_config(node.get(), none.data(), int(none.size()), out.get());
  CHECK_FALSE(out->has_telemetry);
  // A refused configuration is answered in its session but not adopted ...
  const std::vector<uint8_t> refused = RefusedConfigBytes(kOther);
  uvms_ctrl_node_on_config(node.get(), refused.data(), int(refused.size()), out.get());
  REQUIRE(out->has_telemetry);
  CHECK(out->telemetry.session == kOther);
  CHECK(out->telemetry.status != UVMS_OK);
  CHECK(node->session == UVMS_SESSION_NONE);
  // ... the first accepted one is, and then another session's configuration is foreign.
  const std::vector<uint8_t> cfg = PaperConfigBytes(7);
  uvms_ctrl_node_on_config(node.get(), cfg.data(), int(cfg.size()), out.get());
  REQUIRE(out->has_telemetry);
  CHECK(node->session == kSession);
  const std::vector<uint8_t> later = PaperConfigBytes(7, kOther);
  uvms_ctrl_node_on_config(node.get(), later.data(), int(later.size()), out.get());
  CHECK_FALSE(out->has_telemetry);
  CHECK(node->session == kSession);
  CHECK(node->rx_foreign_session == 3);  // the early status, the sessionless and the later config
  const std::vector<uint8_t> s0 = EncodeSensors(RestSensors(0));
  uvms_ctrl_node_on_sensors(node.get(), s0.data(), int(s0.size()), out.get());
  CHECK(out->has_actuators);
}

TEST_CASE("SessionPeekAgreesWithTheDecoderForEveryMessageType", "[codec][session]") {
  // Every type begins with utime, tick, session: uvms_msg_session reads it without decoding.
  constexpr int64_t kNegative = int64_t(0xfedcba9876543210ULL);  // top bit set: sign survives
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
  int64_t got = 0;
  uvms_sensors_t s{};
  s.session = kNegative;
  int n = uvms_sensors_t_encode_sealed(&s, buf.data(), int(buf.size()));
  REQUIRE(uvms_msg_session(buf.data(), n, &got) == 1);
  CHECK(got == kNegative);
  uvms_actuators_t a{};
  a.session = kSession;
  n = uvms_actuators_t_encode_sealed(&a, buf.data(), int(buf.size()));
  REQUIRE(uvms_msg_session(buf.data(), n, &got) == 1);
  CHECK(got == kSession);
  uvms_telemetry_t t{};
  t.session = 7;
  n = uvms_telemetry_t_encode_sealed(&t, buf.data(), int(buf.size()));
  REQUIRE(uvms_msg_session(buf.data(), n, &got) == 1);
  CHECK(got == 7);
  const std::vector<uint8_t> st = StatusBytes(UVMS_RUN_STATUS_T_RUNNING, kNegative);
  REQUIRE(uvms_msg_session(st.data(), int(st.size()), &got) == 1);
  CHECK(got == kNegative);
  const std::vector<uint8_t> cfg = PaperConfigBytes(4, 42);
  REQUIRE(uvms_msg_session(cfg.data(), int(cfg.size()), &got) == 1);
  CHECK(got == 42);
  uvms_truth_t tr{};
  tr.session = kSession;
  char pair[] = "";
  tr.closest_pair = pair;
  n = uvms_truth_t_encode_sealed(&tr, buf.data(), int(buf.size()));
  REQUIRE(uvms_msg_session(buf.data(), n, &got) == 1);
  CHECK(got == kSession);
  CHECK(uvms_msg_session(buf.data(), 31, &got) == 0);  // too short to hold it
}

TEST_CASE("SessionTextIsSixteenHexDigitsAndDrawsAreNonzero", "[session]") {
  char text[UVMS_SESSION_TEXT_BYTES];
  int64_t s = 0;
  uvms_session_format(int64_t(0xfedcba9876543210ULL), text);
  CHECK(std::string(text) == "fedcba9876543210");
  REQUIRE(uvms_session_parse(text, &s) == 1);
  CHECK(s == int64_t(0xfedcba9876543210ULL));
  REQUIRE(uvms_session_parse("1F", &s) == 1);
  CHECK(s == 31);
  for (const char *bad : {"", "0", "0000", "0x1f", "-1", " 1", "1 ", "g", "12345678901234567"}) {
    INFO(bad);
    CHECK(uvms_session_parse(bad, &s) == 0);
    CHECK(s == UVMS_SESSION_NONE);
  }
  int64_t a = 0, b = 0;
  REQUIRE(uvms_session_draw(&a) == 0);
  REQUIRE(uvms_session_draw(&b) == 0);
  CHECK(a != UVMS_SESSION_NONE);
  CHECK(a != b);  // two 64-bit draws collide with probability 2^-64
}

TEST_CASE("NodeRejectsAConfigurationTheFirmwareRefuses", "[node]") {
  const std::vector<uint8_t> refused = RefusedConfigBytes(kSession);
  auto node = std::make_unique<uvms_ctrl_node_t>();
  auto out = std::make_unique<uvms_ctrl_node_out_t>();
  uvms_ctrl_node_init(node.get());
  uvms_ctrl_node_on_config(node.get(), refused.data(), int(refused.size()), out.get());
  REQUIRE(out->has_telemetry);
  CHECK(out->telemetry.status != UVMS_OK);
  CHECK(out->telemetry.config_error == UVMS_CFG_GAINS);
  CHECK_FALSE(node->configured);
}

TEST_CASE("ArbitraryBytesOnEveryChannelAreCountedNeverAnswered", "[node]") {
  auto node = std::make_unique<uvms_ctrl_node_t>();
  auto out = std::make_unique<uvms_ctrl_node_out_t>();
  uvms_ctrl_node_init(node.get());
  const std::vector<uint8_t> cfg = PaperConfigBytes(4);
  uvms_ctrl_node_on_config(node.get(), cfg.data(), int(cfg.size()), out.get());
  REQUIRE(node->configured);
  const std::vector<uint8_t> valid = EncodeSensors(RestSensors(0));
  std::mt19937 rng(20261123);
  long sent = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::vector<uint8_t> bytes;
    switch (trial % 3) {
      case 0: {  // random length, random content
        bytes.resize(size_t(rng() % 600));
        for (auto &b : bytes) b = uint8_t(rng());
        break;
      }
      case 1: {  // a valid message with random bytes overwritten
        bytes = valid;
        for (int k = 0; k < 1 + int(rng() % 4); ++k) bytes[rng() % bytes.size()] ^= uint8_t(1 + rng() % 255);
        break;
      }
      default: {  // a valid message cut short
        bytes.assign(valid.begin(), valid.begin() + long(rng() % valid.size()));
      }
    }
    ++sent;
    switch (trial % 4) {
      case 0: uvms_ctrl_node_on_sensors(node.get(), bytes.data(), int(bytes.size()), out.get()); break;
      case 1: uvms_ctrl_node_on_config(node.get(), bytes.data(), int(bytes.size()), out.get()); break;
      case 2: uvms_ctrl_node_on_status(node.get(), bytes.data(), int(bytes.size())); break;
      default: uvms_ctrl_node_on_sensors(node.get(), nullptr, int(bytes.size()), out.get());
    }
    if (trial % 4 != 2) CHECK_FALSE(out->has_actuators);
  }
  CHECK(node->rx_rejected == sent);
  CHECK(node->configured);  // garbage never replaced the configuration
  CHECK_FALSE(node->finished);
  // The node still works.
  uvms_ctrl_node_on_sensors(node.get(), valid.data(), int(valid.size()), out.get());
  CHECK(out->has_actuators);
}

TEST_CASE("LinkWaitHandlesMessagesAndKeepsItsDeadline", "[link]") {
  // sil/link/lcm_wait.h on a memq provider (thread-safe publish). Outcomes only: that the busy-poll
  // makes udpm faster is the benchmark's to show (bench/sil_bench.sh).
  using Clock = std::chrono::steady_clock;
  auto ms_since = [](Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  };
  lcm_t *lcm = lcm_create("memq://");
  REQUIRE(lcm != nullptr);
  int received = 0;
  lcm_subscription_t *sub = lcm_subscribe(
      lcm, "PING", [](const lcm_recv_buf_t *, const char *, void *user) { ++*static_cast<int *>(user); },
      &received);
  REQUIRE(sub != nullptr);
  const uint8_t payload[3] = {1, 2, 3};
  // Queued before the wait: handled at the first poll.
  REQUIRE(lcm_publish(lcm, "PING", payload, sizeof payload) == 0);
  CHECK(uvms_lcm_wait(lcm, 100, 2000) == 1);
  CHECK(received == 1);
  // Published by another thread 5 ms into a 50 ms spin: handled.
  std::thread peer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    lcm_publish(lcm, "PING", payload, sizeof payload);
  });
  const int r = uvms_lcm_wait(lcm, 1000, 50000);
  peer.join();
  CHECK(r == 1);
  CHECK(received == 2);
  // Silence: a 5 ms spin, then the rest of the 20 ms timeout blocked; nothing handled.
  Clock::time_point t0 = Clock::now();
  CHECK(uvms_lcm_wait(lcm, 20, 5000) == 0);
  CHECK(ms_since(t0) >= 19.0);  // the spin does not shorten the wait (1 ms: rounding)
  // A spin longer than the timeout is cut to it: the wait is the timeout, not the spin.
  t0 = Clock::now();
  CHECK(uvms_lcm_wait(lcm, 3, UVMS_SPIN_US_MAX) == 0);
  CHECK(ms_since(t0) < 0.9e-3 * UVMS_SPIN_US_MAX);
  // No spin: the plain blocking wait.
  REQUIRE(lcm_publish(lcm, "PING", payload, sizeof payload) == 0);
  CHECK(uvms_lcm_wait(lcm, 100, 0) == 1);
  CHECK(received == 3);
  lcm_unsubscribe(lcm, sub);
  lcm_destroy(lcm);
}

TEST_CASE("SpinBudgetParsingAcceptsOnlyWholeMicrosecondsInRange", "[link]") {
  int v = -7;
  for (const char *good : {"0", "2000", UVMS_SPIN_US_MAX_STR}) {
    INFO(good);
    CHECK(uvms_parse_spin_us(good, &v) == 1);
    CHECK(v == std::atoi(good));
  }
  v = 42;
  for (const char *bad : {"", "-1", "100001", "1.5", "abc", "12x", " 5"}) {  // 100001: UVMS_SPIN_US_MAX + 1
    INFO(bad);
    CHECK(uvms_parse_spin_us(bad, &v) == 0);
    CHECK(v == 42);  // untouched
  }
  CHECK(uvms_parse_spin_us(nullptr, &v) == 0);
}
