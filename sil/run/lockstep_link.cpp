// SPDX-License-Identifier: Apache-2.0
// lockstep_link.cpp: the plant's end of the SIL link (lockstep_link.hpp).
#include "run/lockstep_link.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>


namespace uvms::sil {

// Encode one message with the run's session into buf_; throws if it does not fit (never, for
// these types).
template <typename T, typename Enc>
int LockstepLink::EncodeOwn(T msg, Enc enc, const char *channel) {
  msg.session = session_;
  const int n = enc(&msg, buf_.data(), int(buf_.size()));
  if (n < 0) throw std::runtime_error(std::string("encoding for ") + channel + " failed");
  return n;
}

bool LockstepLink::OwnSession(std::int64_t session) {
  if (session == session_) return true;
  ++in_.rx_foreign_session;
  return false;
}

LockstepLink::LockstepLink(LinkBus &bus, Recorder &rec, FaultInjector &faults, int spin_us,
                           std::int64_t session)
    : bus_(bus),
      rec_(rec),
      faults_(faults),
      spin_us_(spin_us),
      session_(session),
      buf_(UVMS_MAX_MSG_BYTES) {
  bus_.SetReceiver(&LockstepLink::OnMessageRaw, this);
}

LockstepLink::~LockstepLink() { bus_.SetReceiver(nullptr, nullptr); }

// ---- handlers (called from the transport's frames, LCM's C code among them: nothing may
// propagate) ----

void LockstepLink::OnMessageRaw(void *user, const char *ch, const std::uint8_t *data,
                                int n) noexcept {
  auto *self = static_cast<LockstepLink *>(user);
  self->errors_.Guard([&] {
    if (std::strcmp(ch, UVMS_CH_ACTUATORS) == 0) self->OnActuators(data, n);
    else if (std::strcmp(ch, UVMS_CH_TELEMETRY) == 0) self->OnTelemetry(ch, data, n);
  });
}

// A valid actuators message that made it through the link: recorded, then taken if it is the
// awaited tick's first, else dropped and counted.
void LockstepLink::AcceptActuators(const uvms_actuators_t &m, const std::uint8_t *data, int n) {
  Record(UVMS_CH_ACTUATORS, data, n, m.utime);
  if (m.tick != in_.expect_tick || in_.have_actuators) {
    ++in_.rx_out_of_sequence;
    return;
  }
  in_.actuators = m;
  in_.have_actuators = true;
}

void LockstepLink::OnActuators(const std::uint8_t *data, int n) {
  uvms_actuators_t m;
  if (uvms_actuators_t_decode_checked(data, n, &m) < 0) {
    ++in_.rx_rejected;
    return;
  }
  if (!OwnSession(m.session)) return;
  // Link faults act on valid messages only, so that stray junk never shifts the random draws.
  const bool awaited = m.tick == in_.expect_tick;
  switch (faults_.NextActuatorsAction()) {
    case LinkAction::kDeliver: AcceptActuators(m, data, n); break;
    case LinkAction::kDuplicate:
      AcceptActuators(m, data, n);
      AcceptActuators(m, data, n);
      break;
    case LinkAction::kDrop: in_.actuators_lost = in_.actuators_lost || awaited; break;
    case LinkAction::kDelay:
      in_.delayed_actuators.assign(data, data + n);
      in_.actuators_lost = in_.actuators_lost || awaited;
      break;
    case LinkAction::kCorrupt: {
      std::vector<std::uint8_t> bad(data, data + n);
      faults_.Corrupt(bad.data(), n);
      uvms_actuators_t mm;
      if (uvms_actuators_t_decode_checked(bad.data(), n, &mm) < 0) {
        ++in_.rx_rejected;  // the CRC caught it, as it catches every single-bit error
        in_.actuators_lost = in_.actuators_lost || awaited;
      } else {
        AcceptActuators(mm, bad.data(), n);
      }
      break;
    }
  }
}

void LockstepLink::OnTelemetry(const char *ch, const std::uint8_t *data, int n) {
  uvms_telemetry_t m;
  if (uvms_telemetry_t_decode_checked(data, n, &m) < 0) {
    ++in_.rx_rejected;
    return;
  }
  if (!OwnSession(m.session)) return;
  if (m.tick != in_.expect_tick || in_.have_telemetry) {
    // Config acknowledgements repeated after a config re-send are expected handshake noise;
    // anything else is out of sequence. Neither is recorded twice.
    if (m.tick != -1) {
      ++in_.rx_out_of_sequence;
      Record(ch, data, n, m.utime);
    }
    return;
  }
  Record(ch, data, n, m.utime);
  in_.telemetry = m;
  in_.have_telemetry = true;
}

// ---- waiting ----

template <typename Pred>
bool LockstepLink::HandleUntil(Clock::time_point deadline, Pred pred) {
  ReleaseRecords();  // what arrives now is recorded after what was sent
  while (!pred()) {
    const long long left_ms =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    // Past the deadline the wait is one non-blocking look (a message may be queued already).
    const int r = bus_.Wait(int(std::clamp<long long>(left_ms, 0, 100)), spin_us_);
    errors_.Rethrow();  // what a handler raised, now that the transport's frames are gone
    if (r < 0 || (r == 0 && (left_ms <= 0 || !bus_.MayReceive()))) return pred();
  }
  return true;
}

const uvms_telemetry_t *LockstepLink::Configure(const uvms_controller_config_t &cfg,
                                                Clock::time_point deadline, long *retries) {
  in_.expect_tick = -1;
  bool first = true;
  while (!in_.have_telemetry && Clock::now() < deadline) {
    const int n = EncodeOwn(cfg, uvms_controller_config_t_encode_sealed, UVMS_CH_CONFIG);
    if (first) rec_.Write(UVMS_CH_CONFIG, buf_.data(), n, 0);
    else ++*retries;
    first = false;
    bus_.Publish(UVMS_CH_CONFIG, buf_.data(), n);
    HandleUntil(std::min(deadline, Clock::now() + std::chrono::milliseconds(20)),
                [&] { return in_.have_telemetry; });
    if (!in_.have_telemetry && !bus_.MayReceive()) break;  // in-process: no answer can come
  }
  return in_.have_telemetry ? &in_.telemetry : nullptr;
}

bool LockstepLink::AwaitActuators(Clock::duration timeout) {
  return HandleUntil(Clock::now() + timeout,
                     [&] { return in_.have_actuators || in_.actuators_lost; }) &&
         in_.have_actuators;
}

const uvms_telemetry_t *LockstepLink::CollectTelemetry(bool answered, Clock::duration timeout) {
  if ((answered || in_.actuators_lost) && !in_.have_telemetry)
    HandleUntil(Clock::now() + timeout, [&] { return in_.have_telemetry; });
  return in_.have_telemetry ? &in_.telemetry : nullptr;
}

// ---- sending ----

void LockstepLink::Record(const char *channel, const std::uint8_t *data, int n,
                          std::int64_t utime) {
  if (!holding_) {
    rec_.Write(channel, data, n, utime);
    return;
  }
  if (held_count_ == held_.size()) held_.emplace_back();
  HeldRecord &h = held_[held_count_++];
  h.channel.assign(channel);
  h.bytes.assign(data, data + n);
  h.utime = utime;
}

void LockstepLink::ReleaseRecords() {
  holding_ = false;
  const std::size_t count = held_count_;
  held_count_ = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const HeldRecord &h = held_[i];
    rec_.Write(h.channel.c_str(), h.bytes.data(), int(h.bytes.size()), h.utime);
  }
}

void LockstepLink::PublishRecorded(const char *channel, const std::uint8_t *data, int n,
                                   std::int64_t utime) {
  Record(channel, data, n, utime);
  bus_.Publish(channel, data, n);
}

void LockstepLink::BeginTick(long k) {
  holding_ = rec_.recording();  // nothing to hold back without a log
  in_.expect_tick = k;
  in_.have_actuators = in_.have_telemetry = in_.actuators_lost = false;
  // Messages a link fault held back one tick go out (or come in) first.
  if (!delayed_sensors_.empty()) {
    PublishRecorded(UVMS_CH_SENSORS, delayed_sensors_.data(), int(delayed_sensors_.size()),
                    delayed_utime_);
    delayed_sensors_.clear();
  }
  if (!in_.delayed_actuators.empty()) {
    std::vector<std::uint8_t> late;
    late.swap(in_.delayed_actuators);
    uvms_actuators_t m;
    if (uvms_actuators_t_decode_checked(late.data(), int(late.size()), &m) > 0)
      AcceptActuators(m, late.data(), int(late.size()));
  }
}

bool LockstepLink::SendSensors(const uvms_sensors_t &msg, std::int64_t utime) {
  const int n = EncodeOwn(msg, uvms_sensors_t_encode_sealed, UVMS_CH_SENSORS);
  const LinkAction action = faults_.NextSensorsAction();
  switch (action) {
    case LinkAction::kDeliver: PublishRecorded(UVMS_CH_SENSORS, buf_.data(), n, utime); return true;
    case LinkAction::kDuplicate:  // the controller drops the copy (same tick) and counts it
      PublishRecorded(UVMS_CH_SENSORS, buf_.data(), n, utime);
      PublishRecorded(UVMS_CH_SENSORS, buf_.data(), n, utime);
      return true;
    case LinkAction::kDrop: return false;
    case LinkAction::kDelay:
      delayed_sensors_.assign(buf_.begin(), buf_.begin() + n);
      delayed_utime_ = utime;
      return false;
    case LinkAction::kCorrupt:
      faults_.Corrupt(buf_.data(), n);
      PublishRecorded(UVMS_CH_SENSORS, buf_.data(), n, utime);
      return false;  // the controller's CRC check rejects it
  }
  return false;
}

void LockstepLink::SendTruth(const uvms_truth_t &msg, std::int64_t utime, bool publish) {
  const int n = EncodeOwn(msg, uvms_truth_t_encode_sealed, UVMS_CH_TRUTH);
  rec_.Write(UVMS_CH_TRUTH, buf_.data(), n, utime);
  if (publish) bus_.Publish(UVMS_CH_TRUTH, buf_.data(), n);
}

void LockstepLink::SendScene(const uvms_scene_t &msg, bool publish) {
  const int n = EncodeOwn(msg, uvms_scene_t_encode_sealed, UVMS_CH_SCENE);
  rec_.Write(UVMS_CH_SCENE, buf_.data(), n, 0);
  if (publish) bus_.Publish(UVMS_CH_SCENE, buf_.data(), n);
}

void LockstepLink::SendStatus(const uvms_run_status_t &msg, std::int64_t utime) {
  ReleaseRecords();
  const int n = EncodeOwn(msg, uvms_run_status_t_encode_sealed, UVMS_CH_STATUS);
  PublishRecorded(UVMS_CH_STATUS, buf_.data(), n, utime);
}

}  // namespace uvms::sil
