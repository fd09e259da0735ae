// SPDX-License-Identifier: Apache-2.0
// The plant node's errors at the LCM boundary (sil/run/plant_node.hpp, sil/link/lcm_guard.hpp; issue 14)
// and the one controller-node core (sil/link/controller_node.h): a log that cannot be written ends
// the run with a failed summary instead of an exception through LCM's C frames, the
// subscriptions are released on every path, and the node's rules and publish order are the
// same whatever computes the step. The in-process transport (sil/run/inprocess_bus.hpp) delivers
// as LCM's memq provider does: the same log, byte for byte, under link faults too.
#include <catch2/catch.hpp>

#include <lcm/eventlog.h>
#include <lcm/lcm.h>
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "msg/codec.h"
#include "link/controller_node.h"
#include "link/lcm_pair.h"
#include "run/faults.hpp"
#include "link/lcm_guard.hpp"
#include "run/inprocess_bus.hpp"
#include "run/lcm_bus.hpp"
#include "run/lockstep_link.hpp"
#include "run/plant_node.hpp"
#include "run/recorder.hpp"
#include "scenario/scenario.hpp"

using Catch::Matchers::Contains;
using namespace uvms::sil;

namespace {

// A short paper scenario (1 s: 34 ticks).
Scenario ShortScenario() {
  return LoadScenario(std::string(UVMS_SCENARIO_DIR) + "/case_VII_stagnant.toml",
                      {"run.duration_s=1", "trajectory.duration_s=1"});
}

struct Memq {
  lcm_t *lcm{lcm_create("memq://")};
  ~Memq() { lcm_destroy(lcm); }
};

// The session of the runs below: one controller node serves them all in turn, so they share it
// (`uvms run` starts a node per run, with the run's own session).
constexpr int64_t kRunSession = 0x5e5510;

// The controller node attached to a memq LCM, as `uvms run --transport memq` has it.
struct MemqRun : Memq {
  std::unique_ptr<uvms_ctrl_node_t> node{std::make_unique<uvms_ctrl_node_t>()};
  MemqRun() {
    uvms_ctrl_node_init(node.get());
    uvms_ctrl_node_set_session(node.get(), kRunSession);
    REQUIRE(uvms_ctrl_node_attach(node.get(), lcm) == 0);
  }
};

std::string TempPath(const char *name) {
  return (std::filesystem::temp_directory_path() /
          (std::string("uvms-test-plant-node-") + std::to_string(getpid()) + "-" + name))
      .string();
}

template <typename T, typename Enc>
void PublishMsg(lcm_t *lcm, const char *channel, const T &msg, Enc enc) {
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
  const int n = enc(&msg, buf.data(), int(buf.size()));
  REQUIRE(n > 0);
  REQUIRE(lcm_publish(lcm, channel, buf.data(), unsigned(n)) == 0);
}

}  // namespace

TEST_CASE("ALogThatCannotBeWrittenEndsTheRunWithAFailedSummary", "[plant_node][errors]") {
  const Scenario sc = ShortScenario();
  MemqRun run;
  const long subscriptions_before = LcmSubscription::live();
  PlantNodeOptions opt;
  opt.session = kRunSession;
  opt.log_path = "/dev/full";  // every write that reaches the device fails (ENOSPC)
  RunSummary s;
  REQUIRE_NOTHROW(s = RunPlantNode(sc, run.lcm, opt));
  CHECK(s.status == "failed");
  CHECK(s.failure == "harness_error");
  CHECK_THAT(s.reason, Contains("the run log /dev/full failed") &&
                           Contains("No space left on device"));
  CHECK(s.ticks < s.ticks_planned);
  CHECK(LcmSubscription::live() == subscriptions_before);  // released on the error path

  // The controller node was told that the run ended (an unrecorded FAILED status).
  while (lcm_handle_timeout(run.lcm, 0) > 0) {
  }
  CHECK(run.node->finished);

  // The same lcm_t runs a second plant node afterwards: nothing of the first one is left on it
  // (a leftover subscription would deliver into the first run's freed link).
  opt.log_path = TempPath("second.lcmlog");
  const RunSummary again = RunPlantNode(sc, run.lcm, opt);
  CHECK(again.status == "finished");
  CHECK(again.failure.empty());
  CHECK(again.ticks == again.ticks_planned);
  CHECK(LcmSubscription::live() == subscriptions_before);
  std::remove(opt.log_path.c_str());
}

TEST_CASE("ALogThatFillsUpAtAnyEventEndsTheRunWithAFailedSummary", "[plant_node][errors]") {
  // /dev/full fails at the first event (the configuration, written by the plant itself). Here the
  // log's file size is limited (RLIMIT_FSIZE) so that the write that fails moves through the run:
  // with stdio's buffering it is whichever event overflows the buffer past the limit, often one
  // the LCM handlers write (actuators, telemetry). Every run must end in the summary, and the
  // same lcm_t must go on working (an exception unwound through lcm_handle leaves it "in
  // handle" for good: LCM asserts on the next call).
  const Scenario sc = ShortScenario();
  MemqRun run;
  const std::string path = TempPath("limited.lcmlog");
  PlantNodeOptions opt;
  opt.session = kRunSession;
  opt.log_path = path;
  rlimit saved{};
  REQUIRE(getrlimit(RLIMIT_FSIZE, &saved) == 0);
  const auto old_handler = signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of the signal
  for (rlim_t limit = 5000; limit < 60000; limit += 2900) {
    rlimit lim = saved;
    lim.rlim_cur = limit;
    REQUIRE(setrlimit(RLIMIT_FSIZE, &lim) == 0);
    const RunSummary s = RunPlantNode(sc, run.lcm, opt);
    REQUIRE(setrlimit(RLIMIT_FSIZE, &saved) == 0);
    INFO("file size limit " << limit << " B");
    CHECK(s.failure == "harness_error");
    CHECK_THAT(s.reason, Contains("File too large"));
    CHECK(LcmSubscription::live() == 0);
    // The metrics reached so far count every tick integrated: the thrusters' energies add up to
    // the truth's propulsive energy at the end (the tick measured while the controller computes
    // the next one is measured on this path too).
    double thrusters_J = 0.0;
    for (const double e : s.propulsive_energy_thruster_J) thrusters_J += e;
    CHECK(std::fabs(thrusters_J - s.propulsive_energy_J) <=
          1e-9 * std::max(1.0, std::fabs(s.propulsive_energy_J)));
    while (lcm_handle_timeout(run.lcm, 0) > 0) {
    }
  }
  signal(SIGXFSZ, old_handler);
  const RunSummary good = RunPlantNode(sc, run.lcm, opt);
  CHECK(good.status == "finished");
  std::remove(path.c_str());
}

TEST_CASE("ALogThatCannotBeCreatedEndsTheRunWithAFailedSummary", "[plant_node][errors]") {
  const Scenario sc = ShortScenario();
  MemqRun run;
  PlantNodeOptions opt;
  opt.session = kRunSession;
  opt.log_path = "/nonexistent-uvms-dir/run.lcmlog";
  RunSummary s;
  REQUIRE_NOTHROW(s = RunPlantNode(sc, run.lcm, opt));
  CHECK(s.status == "failed");
  CHECK(s.failure == "harness_error");
  CHECK_THAT(s.reason, Contains("creating the run log /nonexistent-uvms-dir/run.lcmlog"));
  CHECK(s.ticks == 0);
  CHECK(LcmSubscription::live() == 0);
}

TEST_CASE("AnErrorInsideAnLcmHandlerIsThrownAfterTheHandleCallReturns", "[plant_node][errors]") {
  // The recorder fails inside the telemetry handler (each out-of-sequence telemetry is
  // recorded); the handler is noexcept, so an exception unwinding LCM's frames would have
  // terminated the test. It must come out of the link's wait instead, and LCM must still work.
  Memq m;
  Recorder rec("/dev/full");
  FaultInjector faults(FaultSettings{}, 1, 8);
  constexpr int64_t kLinkSession = 0x11;
  uvms_telemetry_t stray{};
  stray.tick = 99;  // never the awaited tick
  stray.session = kLinkSession;
  {
    LcmBus bus(m.lcm);
    LockstepLink link(bus, rec, faults, 0, kLinkSession);
    CHECK(LcmSubscription::live() == 2);
    link.BeginTick(0);
    for (int i = 0; i < 200; ++i)  // far more than stdio buffers before it writes
      PublishMsg(m.lcm, UVMS_CH_TELEMETRY, stray, uvms_telemetry_t_encode_sealed);
    bool thrown = false;
    for (int i = 0; i < 200 && !thrown; ++i) {
      try {
        const uvms_telemetry_t *taken = link.CollectTelemetry(true, std::chrono::milliseconds(1));
        CHECK(taken == nullptr);
      } catch (const std::runtime_error &e) {
        thrown = true;
        CHECK_THAT(e.what(), Contains("writing an event to the run log /dev/full failed"));
      }
    }
    CHECK(thrown);
    CHECK(link.rx_out_of_sequence() > 1);
  }
  CHECK(LcmSubscription::live() == 0);  // the link is gone: its subscriptions too
  // LCM still handles messages (a handler that unwound through it could have left it broken);
  // the old link's handlers are not called any more.
  int delivered = 0;
  auto count = [](const lcm_recv_buf_t *, const char *, void *user) { ++*static_cast<int *>(user); };
  {
    LcmSubscription sub(m.lcm, UVMS_CH_TELEMETRY, count, &delivered);
    while (lcm_handle_timeout(m.lcm, 0) > 0) {
    }
    delivered = 0;
    PublishMsg(m.lcm, UVMS_CH_TELEMETRY, stray, uvms_telemetry_t_encode_sealed);
    CHECK(lcm_handle_timeout(m.lcm, 100) > 0);
    CHECK(delivered == 1);
  }
  CHECK(LcmSubscription::live() == 0);
}

TEST_CASE("TheLinkDropsAnotherSessionsMessagesUncountedByFaultsAndUnrecorded", "[plant_node][session]") {
  constexpr int64_t kOwn = 0xa11ce, kOther = 0xb0b;
  const std::string path = TempPath("session.lcmlog");
  Memq m;
  {
    Recorder rec(path);
    FaultSettings lossy{};
    lossy.link.drop_rate = 0.5;  // a foreign message must not draw from the link faults
    FaultInjector faults(lossy, 1, 8);
    FaultInjector reference(lossy, 1, 8);
    LcmBus bus(m.lcm);
    LockstepLink link(bus, rec, faults, 0, kOwn);
    link.BeginTick(0);
    uvms_actuators_t act{};
    act.tick = 0;
    act.session = kOther;
    act.motor_voltage_V[0] = 99.0;
    uvms_telemetry_t tel{};
    tel.tick = 0;
    tel.session = kOther;
    for (int i = 0; i < 5; ++i) {
      PublishMsg(m.lcm, UVMS_CH_ACTUATORS, act, uvms_actuators_t_encode_sealed);
      PublishMsg(m.lcm, UVMS_CH_TELEMETRY, tel, uvms_telemetry_t_encode_sealed);
    }
    CHECK_FALSE(link.AwaitActuators(std::chrono::milliseconds(20)));
    CHECK(link.CollectTelemetry(true, std::chrono::milliseconds(5)) == nullptr);
    CHECK(link.rx_foreign_session() == 10);
    CHECK(link.rx_out_of_sequence() == 0);
    // The run's own answer draws the first link-fault decision, as if nothing else had come.
    act.session = kOwn;
    act.motor_voltage_V[0] = 1.0;
    const bool delivered = reference.NextActuatorsAction() == LinkAction::kDeliver;
    PublishMsg(m.lcm, UVMS_CH_ACTUATORS, act, uvms_actuators_t_encode_sealed);
    CHECK(link.AwaitActuators(std::chrono::milliseconds(50)) == delivered);
    if (delivered) CHECK(link.actuators().motor_voltage_V[0] == 1.0);
    // What the link sends carries its session, whatever the message said.
    uvms_run_status_t st{};
    st.session = kOther;
    st.state = UVMS_RUN_STATUS_T_FINISHED;
    link.SendStatus(st, 0);
    rec.Close();
  }
  int events = 0;
  lcm_eventlog_t *log = lcm_eventlog_create(path.c_str(), "r");
  REQUIRE(log != nullptr);
  for (lcm_eventlog_event_t *ev; (ev = lcm_eventlog_read_next_event(log)) != nullptr;
       lcm_eventlog_free_event(ev)) {
    ++events;
    int64_t session = 0;
    REQUIRE(uvms_msg_session(static_cast<const uint8_t *>(ev->data), ev->datalen, &session) == 1);
    CHECK(session == kOwn);  // nothing foreign was recorded
  }
  lcm_eventlog_destroy(log);
  CHECK(events >= 1);  // the status (and the own actuators when the fault delivered them)
  std::remove(path.c_str());
}

// The plant sends a tick's sensors before it records the tick's truth (it records while the
// controller computes): the link holds the records of what it sent back until ReleaseRecords,
// or until it waits, so that the log keeps the order truth k, then what tick k sent, as when
// the truth was recorded first: also for sensors a link fault duplicates or delays a tick.
namespace {
// Two ticks of sending as the plant does (sensors, truth, release), or with tick 1 waiting
// before its truth (`wait_first`: the wait releases what is held). The log's events as
// "channel@utime".
std::vector<std::string> HeldRecordOrder(const FaultSettings &faults_settings, bool wait_first) {
  const std::string path = TempPath("held.lcmlog");
  Memq m;
  {
    Recorder rec(path);
    FaultInjector faults(faults_settings, 1, 8);
    LcmBus bus(m.lcm);
    LockstepLink link(bus, rec, faults, 0, kRunSession);
    uvms_sensors_t sensors{};
    uvms_truth_t truth{};
    char pair[] = "a|b";
    truth.closest_pair = pair;
    for (long k = 0; k < 2; ++k) {
      sensors.tick = truth.tick = k;
      link.BeginTick(k);
      link.SendSensors(sensors, 1000 * k);
      if (k == 0 || !wait_first) {
        link.SendTruth(truth, 1000 * k, false);
        link.ReleaseRecords();
      } else {
        CHECK_FALSE(link.AwaitActuators(std::chrono::milliseconds(1)));  // a wait releases them
        link.SendTruth(truth, 1000 * k, false);
      }
    }
    rec.Close();
  }
  std::vector<std::string> order;
  lcm_eventlog_t *log = lcm_eventlog_create(path.c_str(), "r");
  REQUIRE(log != nullptr);
  for (lcm_eventlog_event_t *ev; (ev = lcm_eventlog_read_next_event(log)) != nullptr;
       lcm_eventlog_free_event(ev))
    order.push_back(std::string(ev->channel) + "@" + std::to_string(ev->timestamp));
  lcm_eventlog_destroy(log);
  std::remove(path.c_str());
  return order;
}
}  // namespace

TEST_CASE("TheLinkRecordsWhatItSentAfterTheTruthRecordedMeanwhile", "[plant_node][log]") {
  const std::string t = UVMS_CH_TRUTH, s = UVMS_CH_SENSORS;
  FaultSettings none{};
  CHECK(HeldRecordOrder(none, false) ==
        std::vector<std::string>{t + "@0", s + "@0", t + "@1000", s + "@1000"});
  // Tick 1 waits before its truth: its sensors are released first.
  CHECK(HeldRecordOrder(none, true) ==
        std::vector<std::string>{t + "@0", s + "@0", s + "@1000", t + "@1000"});
  FaultSettings duplicated{};
  duplicated.link.duplicate_rate = 1.0;
  CHECK(HeldRecordOrder(duplicated, false) ==
        std::vector<std::string>{t + "@0", s + "@0", s + "@0", t + "@1000", s + "@1000", s + "@1000"});
  FaultSettings delayed{};  // each tick's sensors go out at the start of the next, after its truth
  delayed.link.delay_rate = 1.0;
  CHECK(HeldRecordOrder(delayed, false) == std::vector<std::string>{t + "@0", t + "@1000", s + "@0"});
}

TEST_CASE("AFailedFlushIsAFailedLog", "[plant_node][errors]") {
  Recorder rec("/dev/full");
  const uint8_t byte = 0;
  rec.Write("X", &byte, 1, 0);  // buffered: nothing reached the device yet
  CHECK_THROWS_WITH(rec.Flush(), Contains("flushing the run log /dev/full failed"));
}

TEST_CASE("SubscriptionGuardsReleaseOnEveryPath", "[plant_node][errors]") {
  Memq m;
  auto nop = [](const lcm_recv_buf_t *, const char *, void *) {};
  try {
    LcmSubscription a(m.lcm, "A", nop, nullptr);
    LcmSubscription b(m.lcm, "B", nop, nullptr);
    CHECK(LcmSubscription::live() == 2);
    throw std::runtime_error("leaving early");
  } catch (const std::runtime_error &) {
  }
  CHECK(LcmSubscription::live() == 0);
}

// ---- the one controller-node core ----

namespace {

// A compute step standing in for the PIL target: fixed outputs, scripted failures.
struct FakeTarget {
  int configures{0}, steps{0};
  int fail_at_step{-1};  // this step (0-based) fails; -1: none
  static int Configure(void *ctx, const uvms_controller_config_t *, int32_t *status,
                       int32_t *config_error) {
    ++static_cast<FakeTarget *>(ctx)->configures;
    *status = UVMS_OK;
    *config_error = 0;
    return 0;
  }
  static int Step(void *ctx, const uvms_sensors_t *msg, int32_t *status, uvms_ctrl_command_t *cmd,
                  uvms_ctrl_telemetry_t *, int64_t *instructions) {
    auto *t = static_cast<FakeTarget *>(ctx);
    if (t->steps++ == t->fail_at_step) return -1;
    *status = UVMS_OK;
    cmd->motor_voltage_V[0] = uvms_real_t(msg->tick);
    *instructions = 1000 + msg->tick;
    return 0;
  }
};

constexpr int64_t kSession = 0x7e57;  // the session of these node tests' messages

std::vector<uint8_t> Encoded(const uvms_sensors_t &s) {
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
  buf.resize(size_t(uvms_sensors_t_encode_sealed(&s, buf.data(), int(buf.size()))));
  return buf;
}

std::vector<uint8_t> PaperConfig() {
  uvms_ctrl_config_t cfg;
  REQUIRE(uvms_ctrl_config_paper(&cfg, 7) == UVMS_OK);
  uvms_controller_config_t msg;
  uvms_config_to_msg(&cfg, &msg);
  msg.session = kSession;
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
  buf.resize(size_t(uvms_controller_config_t_encode_sealed(&msg, buf.data(), int(buf.size()))));
  return buf;
}

uvms_sensors_t SensorsOfTick(long k) {
  uvms_sensors_t s{};
  s.tick = k;
  s.session = kSession;
  s.utime = k * 30000;
  s.quaternion_wxyz[0] = 1.0;
  s.thruster_usable_mask = 0xFF;
  return s;
}

}  // namespace

TEST_CASE("AnotherComputeStepGetsTheSameRulesAndPublishOrder", "[controller_node]") {
  Memq m;
  auto node = std::make_unique<uvms_ctrl_node_t>();
  uvms_ctrl_node_init(node.get());
  FakeTarget target;
  const uvms_ctrl_node_compute_t compute = {FakeTarget::Configure, FakeTarget::Step, &target};
  uvms_ctrl_node_set_compute(node.get(), &compute);
  REQUIRE(uvms_ctrl_node_attach(node.get(), m.lcm) == 0);
  std::vector<std::string> order;  // channels, as a plant receives them
  auto record = [](const lcm_recv_buf_t *, const char *ch, void *user) {
    static_cast<std::vector<std::string> *>(user)->push_back(ch);
  };
  LcmSubscription act(m.lcm, UVMS_CH_ACTUATORS, record, &order);
  LcmSubscription tel(m.lcm, UVMS_CH_TELEMETRY, record, &order);
  auto deliver = [&](const char *ch, const std::vector<uint8_t> &bytes) {
    REQUIRE(lcm_publish(m.lcm, ch, bytes.data(), unsigned(bytes.size())) == 0);
    while (lcm_handle_timeout(m.lcm, 0) > 0) {
    }
  };

  deliver(UVMS_CH_SENSORS, Encoded(SensorsOfTick(0)));  // before any configuration
  CHECK(node->rx_unconfigured == 1);
  deliver(UVMS_CH_CONFIG, PaperConfig());
  CHECK(target.configures == 1);
  CHECK(order == std::vector<std::string>{UVMS_CH_TELEMETRY});  // the configuration's answer
  order.clear();
  deliver(UVMS_CH_SENSORS, Encoded(SensorsOfTick(0)));
  CHECK(order == std::vector<std::string>{UVMS_CH_ACTUATORS, UVMS_CH_TELEMETRY});
  deliver(UVMS_CH_SENSORS, Encoded(SensorsOfTick(0)));  // the same tick again
  CHECK(node->rx_out_of_sequence == 1);
  std::vector<uint8_t> junk = Encoded(SensorsOfTick(1));
  junk[10] ^= 1;
  deliver(UVMS_CH_SENSORS, junk);
  CHECK(node->rx_rejected == 1);
  CHECK(target.steps == 1);
  CHECK(order.size() == 2);

  // The answer carries the step's instruction count and the node's counters.
  auto out = std::make_unique<uvms_ctrl_node_out_t>();
  const std::vector<uint8_t> s2 = Encoded(SensorsOfTick(2));
  uvms_ctrl_node_on_sensors(node.get(), s2.data(), int(s2.size()), out.get());
  REQUIRE(out->has_actuators);
  CHECK(out->actuators.motor_voltage_V[0] == 2.0);
  CHECK(out->telemetry.target_instructions == 1002);
  CHECK(out->telemetry.rx_rejected == 1);
  CHECK(out->telemetry.rx_out_of_sequence == 1);
  CHECK(out->telemetry.rx_unconfigured == 1);

  // A failing compute step stops the node: no answer, nothing handled or counted after it.
  target.fail_at_step = target.steps;
  const std::vector<uint8_t> s3 = Encoded(SensorsOfTick(3));
  uvms_ctrl_node_on_sensors(node.get(), s3.data(), int(s3.size()), out.get());
  CHECK_FALSE(out->has_actuators);
  CHECK(node->failed);
  const long steps = node->steps;
  uvms_ctrl_node_on_sensors(node.get(), junk.data(), int(junk.size()), out.get());
  CHECK(node->rx_rejected == 1);
  CHECK(node->steps == steps);
  CHECK(uvms_ctrl_node_serve(node.get(), 1.0, 0, nullptr) == UVMS_CTRL_NODE_FAILED);
  uvms_ctrl_node_detach(node.get());
}

TEST_CASE("ADetachedControllerNodeAnswersNothing", "[controller_node]") {
  Memq m;
  auto node = std::make_unique<uvms_ctrl_node_t>();
  uvms_ctrl_node_init(node.get());
  REQUIRE(uvms_ctrl_node_attach(node.get(), m.lcm) == 0);
  uvms_ctrl_node_detach(node.get());
  uvms_ctrl_node_detach(node.get());  // safe twice
  const std::vector<uint8_t> cfg = PaperConfig();
  REQUIRE(lcm_publish(m.lcm, UVMS_CH_CONFIG, cfg.data(), unsigned(cfg.size())) == 0);
  while (lcm_handle_timeout(m.lcm, 0) > 0) {
  }
  CHECK_FALSE(node->configured);
  CHECK(node->rx_rejected == 0);
}

// An end's LCM instances (sil/link/lcm_pair.h): one instance for one URL, two for two, and a
// URL LCM cannot start on named with nothing left open.
TEST_CASE("AnEndOpensOneLcmInstancePerUrl", "[controller_node]") {
  uvms_lcm_pair_t pair;
  const char *failed = nullptr;
  REQUIRE(uvms_lcm_pair_open(&pair, "memq://", nullptr, &failed) == 0);
  CHECK(pair.listen != nullptr);
  CHECK(pair.publish == pair.listen);
  uvms_lcm_pair_close(&pair);
  uvms_lcm_pair_close(&pair);  // safe twice
  CHECK(pair.listen == nullptr);
  REQUIRE(uvms_lcm_pair_open(&pair, "memq://", "memq://", &failed) == 0);
  CHECK(pair.publish == pair.listen);  // the same URL given twice
  uvms_lcm_pair_close(&pair);
  REQUIRE(uvms_lcm_pair_open(&pair, "memq://", "memq://?x=1", &failed) == 0);
  CHECK(pair.publish != pair.listen);
  uvms_lcm_pair_close(&pair);
  CHECK(uvms_lcm_pair_open(&pair, "memq://", "nosuchprovider://", &failed) == -1);
  CHECK(std::string(failed) == "nosuchprovider://");
  CHECK(pair.listen == nullptr);
  CHECK(pair.publish == nullptr);
  CHECK(uvms_lcm_pair_open(&pair, "nosuchprovider://", nullptr, &failed) == -1);
  CHECK(std::string(failed) == "nosuchprovider://");
}

// A node attached to two LCM instances (the two URLs of `uvms run`'s private link) listens on
// the first only and answers on the second only.
TEST_CASE("ASplitControllerNodeListensOnOneInstanceAndAnswersOnTheOther", "[controller_node]") {
  Memq rx, tx;  // two memq:// instances: two separate buses
  auto node = std::make_unique<uvms_ctrl_node_t>();
  uvms_ctrl_node_init(node.get());
  REQUIRE(uvms_ctrl_node_attach_split(node.get(), rx.lcm, tx.lcm) == 0);
  std::vector<std::string> on_rx, on_tx;
  auto record = [](const lcm_recv_buf_t *, const char *ch, void *user) {
    static_cast<std::vector<std::string> *>(user)->push_back(ch);
  };
  LcmSubscription rx_tel(rx.lcm, UVMS_CH_TELEMETRY, record, &on_rx);
  LcmSubscription tx_tel(tx.lcm, UVMS_CH_TELEMETRY, record, &on_tx);
  LcmSubscription tx_act(tx.lcm, UVMS_CH_ACTUATORS, record, &on_tx);
  auto handle_all = [&] {
    while (lcm_handle_timeout(rx.lcm, 0) > 0 || lcm_handle_timeout(tx.lcm, 0) > 0) {
    }
  };
  const std::vector<uint8_t> cfg = PaperConfig();
  // The configuration on the answer side is not heard.
  REQUIRE(lcm_publish(tx.lcm, UVMS_CH_CONFIG, cfg.data(), unsigned(cfg.size())) == 0);
  handle_all();
  CHECK_FALSE(node->configured);
  REQUIRE(lcm_publish(rx.lcm, UVMS_CH_CONFIG, cfg.data(), unsigned(cfg.size())) == 0);
  handle_all();
  CHECK(node->configured);
  const std::vector<uint8_t> s0 = Encoded(SensorsOfTick(0));
  REQUIRE(lcm_publish(rx.lcm, UVMS_CH_SENSORS, s0.data(), unsigned(s0.size())) == 0);
  handle_all();
  CHECK(on_rx.empty());
  CHECK(on_tx == std::vector<std::string>{UVMS_CH_TELEMETRY, UVMS_CH_ACTUATORS, UVMS_CH_TELEMETRY});
  uvms_ctrl_node_detach(node.get());
}

namespace {

// A controller node and the in-process bus in front of it, as `uvms run --transport memq` has
// them (members in that order: the bus refers to the node).
struct InProcess {
  std::unique_ptr<uvms_ctrl_node_t> node{NewNode()};
  InProcessBus bus{*node};
  static std::unique_ptr<uvms_ctrl_node_t> NewNode() {
    auto n = std::make_unique<uvms_ctrl_node_t>();
    uvms_ctrl_node_init(n.get());
    return n;
  }
};

// What a plant's end received from a bus: channel and tick, in order.
struct Received {
  std::vector<std::string> channels;
  std::vector<int64_t> ticks;
  static void Take(void *user, const char *channel, const uint8_t *data, int n) noexcept {
    auto *r = static_cast<Received *>(user);
    r->channels.push_back(channel);
    int64_t tick = -99;  // fingerprint, utime, then the tick (big-endian int64)
    if (n >= 24) {
      uint64_t bits = 0;
      for (int i = 16; i < 24; ++i) bits = (bits << 8) | data[i];
      tick = int64_t(bits);
    }
    r->ticks.push_back(tick);
  }
};

template <typename T, typename Enc>
std::vector<uint8_t> Sealed(const T &msg, Enc enc) {
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
  buf.resize(size_t(enc(&msg, buf.data(), int(buf.size()))));
  return buf;
}

std::vector<uint8_t> FileBytes(const std::string &path) {
  std::FILE *f = std::fopen(path.c_str(), "rb");
  REQUIRE(f != nullptr);
  std::vector<uint8_t> bytes;
  for (int c; (c = std::fgetc(f)) != EOF;) bytes.push_back(uint8_t(c));
  std::fclose(f);
  return bytes;
}

}  // namespace

TEST_CASE("TheInProcessBusKeepsLcmMemqsDeliveryRules", "[plant_node][inprocess]") {
  InProcess local;
  auto &node = local.node;  // references, not a structured binding: lambdas capture them
  InProcessBus &bus = local.bus;
  uvms_telemetry_t tel{};
  tel.session = kSession;

  // A channel nobody takes is dropped at publish time: truth and scene always, the plant's
  // channels while no receiver is set. Waiting on an empty queue returns at once.
  const std::vector<uint8_t> t0 = Sealed(tel, uvms_telemetry_t_encode_sealed);
  CHECK(bus.Publish(UVMS_CH_TRUTH, t0.data(), int(t0.size())) == 0);
  CHECK(bus.Publish(UVMS_CH_SCENE, t0.data(), int(t0.size())) == 0);
  CHECK(bus.Publish(UVMS_CH_TELEMETRY, t0.data(), int(t0.size())) == 0);
  CHECK(bus.queued() == 0);
  CHECK_FALSE(bus.MayReceive());
  const auto before = std::chrono::steady_clock::now();
  CHECK(bus.Wait(100, 0) == 0);
  CHECK(std::chrono::steady_clock::now() - before < std::chrono::milliseconds(50));

  // First in, first out, through a queue that grows past its first slots.
  Received got;
  bus.SetReceiver(&Received::Take, &got);
  for (int k = 0; k < 11; ++k) {
    tel.tick = k;
    const std::vector<uint8_t> b = Sealed(tel, uvms_telemetry_t_encode_sealed);
    const char *ch = (k % 2) ? UVMS_CH_ACTUATORS : UVMS_CH_TELEMETRY;  // bytes: any
    REQUIRE(bus.Publish(ch, b.data(), int(b.size())) == 0);
  }
  CHECK(bus.queued() == 11);
  CHECK(bus.MayReceive());
  CHECK(bus.Wait(0, 0) == 1);
  CHECK(bus.queued() == 10);
  bus.Drain();
  CHECK(bus.queued() == 0);
  REQUIRE(got.ticks.size() == 11);
  for (int k = 0; k < 11; ++k) {
    CHECK(got.ticks[size_t(k)] == k);
    CHECK(got.channels[size_t(k)] == ((k % 2) ? UVMS_CH_ACTUATORS : UVMS_CH_TELEMETRY));
  }

  // The controller node takes config and sensors; its answers queue behind what was queued
  // before them, in the publish order of controller_node.h.
  got = Received{};
  const std::vector<uint8_t> cfg = PaperConfig();
  REQUIRE(bus.Publish(UVMS_CH_CONFIG, cfg.data(), int(cfg.size())) == 0);
  tel.tick = 77;
  const std::vector<uint8_t> before_answer = Sealed(tel, uvms_telemetry_t_encode_sealed);
  REQUIRE(bus.Publish(UVMS_CH_TELEMETRY, before_answer.data(), int(before_answer.size())) == 0);
  const std::vector<uint8_t> s0 = Encoded(SensorsOfTick(0));
  REQUIRE(bus.Publish(UVMS_CH_SENSORS, s0.data(), int(s0.size())) == 0);
  bus.Drain();
  CHECK(node->configured);
  CHECK(node->steps == 1);
  CHECK(got.channels == std::vector<std::string>{UVMS_CH_TELEMETRY, UVMS_CH_TELEMETRY,
                                                 UVMS_CH_ACTUATORS, UVMS_CH_TELEMETRY});
  CHECK(got.ticks == std::vector<int64_t>{77, -1, 0, 0});

  // A message queued while the receiver was set, but handled after it was cleared, reaches
  // nobody (LCM dispatches to the subscriptions alive when it handles). The status reaches the
  // controller node.
  REQUIRE(bus.Publish(UVMS_CH_TELEMETRY, before_answer.data(), int(before_answer.size())) == 0);
  bus.SetReceiver(nullptr, nullptr);
  uvms_run_status_t st{};
  st.session = kSession;
  st.state = UVMS_RUN_STATUS_T_FINISHED;
  const std::vector<uint8_t> sb = Sealed(st, uvms_run_status_t_encode_sealed);
  REQUIRE(bus.Publish(UVMS_CH_STATUS, sb.data(), int(sb.size())) == 0);
  CHECK(bus.queued() == 2);
  bus.Drain();
  CHECK(got.channels.size() == 4);
  CHECK(node->finished);
}

TEST_CASE("ARunLogsTheSameBytesInProcessAsOverLcmMemq", "[plant_node][inprocess]") {
  // A lossy link in both directions (every kind of link fault at 5 %: each acts several times
  // in 3 s, 100 ticks): the in-process queue must deliver what LCM's memq delivers, in its order.
  const Scenario sc = LoadScenario(std::string(UVMS_SCENARIO_DIR) + "/../faults/link_faults.toml",
                                   {"run.duration_s=3", "trajectory.duration_s=3",
                                    "faults.link.drop_rate=0.05", "faults.link.delay_rate=0.05",
                                    "faults.link.duplicate_rate=0.05",
                                    "faults.link.corrupt_rate=0.05"});
  PlantNodeOptions opt;
  opt.session = kRunSession;
  opt.log_path = TempPath("over-lcm.lcmlog");
  RunSummary over_lcm;
  {
    MemqRun run;
    over_lcm = RunPlantNode(sc, run.lcm, opt);
  }
  const std::string lcm_log = opt.log_path;
  opt.log_path = TempPath("in-process.lcmlog");
  InProcess local;
  auto &node = local.node;  // references, not a structured binding: lambdas capture them
  InProcessBus &bus = local.bus;
  uvms_ctrl_node_set_session(node.get(), kRunSession);
  const RunSummary in_process = RunPlantNode(sc, bus, opt);
  bus.Drain();
  CHECK(node->finished);

  CHECK(over_lcm.status == "finished");
  CHECK(in_process.status == "finished");
  CHECK(in_process.ticks == over_lcm.ticks);
  CHECK(in_process.missed_ticks == over_lcm.missed_ticks);
  CHECK(in_process.rx_rejected == over_lcm.rx_rejected);
  CHECK(in_process.rx_out_of_sequence == over_lcm.rx_out_of_sequence);
  CHECK(over_lcm.missed_ticks > 5);  // the faults did act
  CHECK(over_lcm.rx_out_of_sequence > 0);
  const std::vector<uint8_t> a = FileBytes(lcm_log), b = FileBytes(opt.log_path);
  CHECK(a.size() > 10000);
  CHECK(a == b);
  std::remove(lcm_log.c_str());
  std::remove(opt.log_path.c_str());
}

TEST_CASE("TheInProcessQueueGrowsInOrderWhenItHasWrapped", "[plant_node][inprocess]") {
  InProcess local;
  auto &node = local.node;  // references, not a structured binding: lambdas capture them
  InProcessBus &bus = local.bus;
  Received got;
  bus.SetReceiver(&Received::Take, &got);
  uvms_telemetry_t tel{};
  tel.session = kSession;
  auto publish = [&](int64_t tick) {
    tel.tick = tick;
    const std::vector<uint8_t> b = Sealed(tel, uvms_telemetry_t_encode_sealed);
    REQUIRE(bus.Publish(UVMS_CH_TELEMETRY, b.data(), int(b.size())) == 0);
  };
  // Growth from a wrapped ring: 3 in, 2 out (the head moves on), then 6 more (the first 4-slot
  // ring wraps and grows with its head inside).
  for (int64_t t = 0; t < 3; ++t) publish(t);
  CHECK(bus.Wait(0, 0) == 1);
  CHECK(bus.Wait(0, 0) == 1);
  for (int64_t t = 3; t < 9; ++t) publish(t);
  CHECK(bus.queued() == 7);
  bus.Drain();
  CHECK(got.ticks == std::vector<int64_t>{0, 1, 2, 3, 4, 5, 6, 7, 8});

  // Growth while a message is being handled: the controller's two answers to sensors find the
  // ring full behind them. (Configured first; then a full ring of sensors and 7 telemetries.)
  const std::vector<uint8_t> cfg = PaperConfig();
  REQUIRE(bus.Publish(UVMS_CH_CONFIG, cfg.data(), int(cfg.size())) == 0);
  bus.Drain();
  REQUIRE(node->configured);
  got = Received{};
  const std::vector<uint8_t> s0 = Encoded(SensorsOfTick(0));
  REQUIRE(bus.Publish(UVMS_CH_SENSORS, s0.data(), int(s0.size())) == 0);
  for (int64_t t = 100; t < 107; ++t) publish(t);
  CHECK(bus.queued() == 8);  // the ring's 8 slots, all taken
  bus.Drain();
  CHECK(got.ticks == std::vector<int64_t>{100, 101, 102, 103, 104, 105, 106, 0, 0});
  CHECK(got.channels.at(7) == UVMS_CH_ACTUATORS);
  CHECK(got.channels.at(8) == UVMS_CH_TELEMETRY);
}

TEST_CASE("TheInProcessBusTakesOnePlantEndAndOneMessageAtATime", "[plant_node][inprocess]") {
  InProcess local;
  InProcessBus &bus = local.bus;
  Received first;
  bus.SetReceiver(&Received::Take, &first);
  CHECK_THROWS_AS(bus.SetReceiver(&Received::Take, &first), std::logic_error);
  const uint8_t byte = 0;
  CHECK(bus.Publish(UVMS_CH_TELEMETRY, &byte, -1) == -1);
  // A taker that waits on the bus while it handles a message is refused (-1), and the message
  // it would have taken stays queued.
  static InProcessBus *reentrant = nullptr;
  static int inner = 0;
  reentrant = &bus;
  auto nested = [](void *, const char *, const uint8_t *, int) noexcept {
    inner = reentrant->Wait(0, 0);
  };
  bus.SetReceiver(nullptr, nullptr);
  bus.SetReceiver(nested, nullptr);
  uvms_telemetry_t tel{};
  const std::vector<uint8_t> b = Sealed(tel, uvms_telemetry_t_encode_sealed);
  REQUIRE(bus.Publish(UVMS_CH_TELEMETRY, b.data(), int(b.size())) == 0);
  REQUIRE(bus.Publish(UVMS_CH_TELEMETRY, b.data(), int(b.size())) == 0);
  CHECK(bus.Wait(0, 0) == 1);
  CHECK(inner == -1);
  CHECK(bus.queued() == 1);
}

TEST_CASE("AnInProcessControllerThatDoesNotAnswerEndsTheHandshakeAtOnce", "[plant_node][inprocess]") {
  // A compute step that fails its configuration: the node answers nothing, ever. Over LCM the
  // plant re-sends every 20 ms until its startup timeout; in process nothing can answer later,
  // so the handshake ends after the first try instead of spinning until the deadline.
  const Scenario sc = ShortScenario();
  InProcess local;
  auto &node = local.node;  // references, not a structured binding: lambdas capture them
  InProcessBus &bus = local.bus;
  uvms_ctrl_node_set_session(node.get(), kRunSession);
  auto refuse = [](void *, const uvms_controller_config_t *, int32_t *, int32_t *) { return -1; };
  const uvms_ctrl_node_compute_t compute = {refuse, FakeTarget::Step, nullptr};
  uvms_ctrl_node_set_compute(node.get(), &compute);
  PlantNodeOptions opt;
  opt.session = kRunSession;
  opt.startup_timeout_s = 5.0;
  const auto t0 = std::chrono::steady_clock::now();
  const RunSummary s = RunPlantNode(sc, bus, opt);
  const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(s.status == "failed");
  CHECK(s.failure == "no_controller");
  CHECK(s.config_retries == 0);
  CHECK(took_s < 2.5);  // not the 5 s startup timeout (a bound on a hang, not a timing claim)
  CHECK(node->failed);
}
