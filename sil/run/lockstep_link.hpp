// SPDX-License-Identifier: Apache-2.0
// lockstep_link.hpp: the plant's end of the SIL link: publish, wait and handle.
//
// The link publishes what the plant sends (configuration, truth, sensors, run status) and
// takes in what the controller answers (telemetry, actuators), recording both (recorder.hpp),
// with the link faults of the scenario applied in between (faults.hpp: every random draw is
// taken for valid messages only, so stray junk never shifts them). Its rules:
//  - every message sent carries the run's session (sil/msg/session.h); a message received with
//    another session is dropped and counted (rx_foreign_session), never recorded, and draws
//    nothing from the link faults;
//  - a message that fails to decode or its CRC is dropped and counted (rx_rejected);
//  - actuators: recorded, then taken if they are the awaited tick's first, else dropped and
//    counted (rx_out_of_sequence: still recorded, it is real traffic);
//  - telemetry: taken and recorded if it is the awaited tick's first; otherwise dropped, and
//    counted and recorded unless it repeats a configuration answer (tick -1: handshake noise);
//  - sensors or actuators a fault delays go out (or come in) first in the next tick.
// The controller answers each tick in the publish order sil/link/controller_node.h documents: the
// plant integrates as soon as the actuators are in and collects the telemetry after its step,
// so the log order (truth k, sensors k, actuators k, telemetry k, truth k+1, ...) does not
// depend on timing. The sensors go out before the truth is recorded (the plant records it while
// the controller computes): the link holds their records back until ReleaseRecords.
//
// The transport is a LinkBus (link_bus.hpp): LCM (lcm_bus.hpp), or the controller node in this
// process (inprocess_bus.hpp). Waiting busy-polls the link for spin_us before blocking
// (sil/link/lcm_wait.h), and ends at once when the bus says nothing more can arrive. The handlers
// never let an exception cross the transport's frames (LCM's are C: lcm_guard.hpp): an error
// raised while handling (a log write that failed) is thrown by the wait that handled it. The
// link stops receiving when it goes (its LCM subscriptions are released), on every path.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "link/lcm_guard.hpp"
#include "msg/codec.h"
#include "run/faults.hpp"
#include "run/link_bus.hpp"
#include "run/recorder.hpp"

namespace uvms::sil {

class LockstepLink {
 public:
  using Clock = std::chrono::steady_clock;

  /// Receives actuators and telemetry from bus (not owned: it outlives the link); `session` is
  /// the run's (sil/msg/session.h). Throws std::runtime_error if the transport refuses.
  LockstepLink(LinkBus &bus, Recorder &rec, FaultInjector &faults, int spin_us,
               std::int64_t session);
  /// Records still held back (BeginTick without ReleaseRecords or a wait: only when an error
  /// ended the tick) are dropped, as the log they were for has failed or is being abandoned.
  ~LockstepLink();
  LockstepLink(const LockstepLink &) = delete;
  LockstepLink &operator=(const LockstepLink &) = delete;

  /// Handshake: publish the configuration every 20 ms (recorded once, at utime 0) until the
  /// controller answers it (telemetry of tick -1) or the deadline passes, or at once when the
  /// bus says no answer can come (in-process: the node handled it and said nothing). Returns
  /// the answer, or nullptr; *retries counts the re-sends.
  const uvms_telemetry_t *Configure(const uvms_controller_config_t &cfg, Clock::time_point deadline,
                                    long *retries);

  /// Start tick k: await its answer, and let out what a fault held back one tick. From here
  /// until ReleaseRecords, what the link sends and accepts goes out (or in) at once but its
  /// records are held back: the plant records the truth of tick k while the controller
  /// computes, and the truth keeps its place before them in the log.
  void BeginTick(long k);
  /// Publish tick k's sensors through the faulty link. Returns false when the link lost them
  /// (dropped, delayed or corrupted): the controller cannot answer this tick.
  bool SendSensors(const uvms_sensors_t &msg, std::int64_t utime);
  /// Wait up to timeout for the tick's actuators. Returns whether they came (actuators()).
  bool AwaitActuators(Clock::duration timeout);
  /// After the plant's step: if the controller answered (or its actuators were lost on the way),
  /// wait up to timeout for the tick's telemetry. Returns it, or nullptr.
  const uvms_telemetry_t *CollectTelemetry(bool answered, Clock::duration timeout);
  const uvms_actuators_t &actuators() const { return in_.actuators; }

  /// Record truth (at once, records held back or not); publish it too if `publish`
  /// (link.publish_truth).
  void SendTruth(const uvms_truth_t &msg, std::int64_t utime, bool publish);
  /// Write the records held back since BeginTick, in the order they were made.
  void ReleaseRecords();
  /// Record and publish a run status.
  void SendStatus(const uvms_run_status_t &msg, std::int64_t utime);
  /// The scene (scene_t) to the log at utime 0; also on the link when `publish` (as truth).
  void SendScene(const uvms_scene_t &msg, bool publish);

  long rx_rejected() const { return in_.rx_rejected; }
  long rx_out_of_sequence() const { return in_.rx_out_of_sequence; }
  long rx_foreign_session() const { return in_.rx_foreign_session; }
  std::int64_t session() const { return session_; }

 private:
  struct Inbox {
    long expect_tick{-2};  // tick whose actuators/telemetry are awaited (-1: config answer)
    bool have_actuators{false};
    bool actuators_lost{false};  // the awaited actuators were lost on the (faulty) link
    bool have_telemetry{false};
    uvms_actuators_t actuators{};
    uvms_telemetry_t telemetry{};
    std::vector<std::uint8_t> delayed_actuators;  // held back one tick by a link fault
    long rx_rejected{0}, rx_out_of_sequence{0}, rx_foreign_session{0};
  };

  static void OnMessageRaw(void *user, const char *ch, const std::uint8_t *data, int n) noexcept;
  void OnActuators(const std::uint8_t *data, int n);
  void OnTelemetry(const char *ch, const std::uint8_t *data, int n);
  void AcceptActuators(const uvms_actuators_t &m, const std::uint8_t *data, int n);
  void PublishRecorded(const char *channel, const std::uint8_t *data, int n, std::int64_t utime);
  /// To the log now, or held back until ReleaseRecords (between BeginTick and it).
  void Record(const char *channel, const std::uint8_t *data, int n, std::int64_t utime);
  /// Whether a decoded message is this run's; counts it as foreign when not.
  bool OwnSession(std::int64_t session);
  /// msg with the run's session, encoded into buf_. Returns the byte count.
  template <typename T, typename Enc>
  int EncodeOwn(T msg, Enc enc, const char *channel);
  /// Handle messages until pred() or the deadline; rethrows a handler's error. Returns pred().
  template <typename Pred>
  bool HandleUntil(Clock::time_point deadline, Pred pred);

  LinkBus &bus_;
  Recorder &rec_;
  FaultInjector &faults_;
  int spin_us_;
  std::int64_t session_;
  Inbox in_;
  std::vector<std::uint8_t> buf_;
  std::vector<std::uint8_t> delayed_sensors_;  // held back one tick by a link fault
  std::int64_t delayed_utime_{0};
  HandlerErrors errors_;
  struct HeldRecord {
    std::string channel;
    std::vector<std::uint8_t> bytes;
    std::int64_t utime{0};
  };
  bool holding_{false};
  std::vector<HeldRecord> held_;  // grows to the most one tick holds, then is reused
  std::size_t held_count_{0};     // records held now: held_[0, held_count_)
};

}  // namespace uvms::sil
