// plant_node.cpp: lockstep master, recorder and metrics of a run (plant_node.hpp).
#include "plant_node.hpp"

#include <lcm/eventlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "codec.h"
#include "faults.hpp"
#include "lcm_wait.h"

namespace uvms::sil {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Simulated time of tick k as LCM utime [µs].
int64_t TickUtime(long k, double tick_s) { return std::llround(double(k) * tick_s * 1e6); }

// The run's LCM log, written directly (lcm_eventlog): event timestamps are the messages'
// simulated times, so the log is deterministic.
class Recorder {
 public:
  explicit Recorder(const std::string &path) {
    if (path.empty()) return;
    log_ = lcm_eventlog_create(path.c_str(), "w");
    if (log_ == nullptr) throw std::runtime_error("cannot create log file " + path);
  }
  ~Recorder() {
    if (log_ != nullptr) lcm_eventlog_destroy(log_);
  }
  Recorder(const Recorder &) = delete;
  Recorder &operator=(const Recorder &) = delete;

  void Write(const char *channel, const uint8_t *data, int len, int64_t utime) {
    if (log_ == nullptr) return;
    lcm_eventlog_event_t ev{};
    ev.eventnum = next_++;
    ev.timestamp = utime;
    ev.channellen = int32_t(std::strlen(channel));
    ev.datalen = len;
    ev.channel = const_cast<char *>(channel);
    ev.data = const_cast<uint8_t *>(data);
    if (lcm_eventlog_write_event(log_, &ev) != 0) throw std::runtime_error("log write failed");
  }

 private:
  lcm_eventlog_t *log_{nullptr};
  int64_t next_{0};
};

// What the subscriptions deliver into; the loop below reads it.
struct Inbox {
  Recorder *rec{nullptr};
  FaultInjector *faults{nullptr};
  long expect_tick{-2};         // tick whose actuators/telemetry are awaited (-1: config ack)
  bool have_actuators{false};
  bool actuators_lost{false};   // the awaited actuators were lost on the (faulty) link
  bool have_telemetry{false};
  uvms_actuators_t actuators{};
  uvms_telemetry_t telemetry{};
  std::vector<uint8_t> delayed_actuators;  // held back one tick by a link fault
  long rx_rejected{0}, rx_out_of_sequence{0};
};

// A valid actuators message that made it through the link: recorded, then taken if it is the
// awaited tick's first, else dropped and counted.
void AcceptActuators(Inbox *in, const uvms_actuators_t &m, const uint8_t *data, int n) {
  in->rec->Write(UVMS_CH_ACTUATORS, data, n, m.utime);
  if (m.tick != in->expect_tick || in->have_actuators) {
    ++in->rx_out_of_sequence;
    return;
  }
  in->actuators = m;
  in->have_actuators = true;
}

void OnActuators(const lcm_recv_buf_t *rb, const char *, void *user) {
  auto *in = static_cast<Inbox *>(user);
  uvms_actuators_t m;
  const auto *data = static_cast<const uint8_t *>(rb->data);
  const int n = int(rb->data_size);
  if (uvms_actuators_t_decode_checked(data, n, &m) < 0) {
    ++in->rx_rejected;
    return;
  }
  // Link faults act on valid messages only, so that stray junk never shifts the random draws.
  const bool awaited = m.tick == in->expect_tick;
  switch (in->faults->NextActuatorsAction()) {
    case LinkAction::kDeliver: AcceptActuators(in, m, data, n); break;
    case LinkAction::kDuplicate:
      AcceptActuators(in, m, data, n);
      AcceptActuators(in, m, data, n);
      break;
    case LinkAction::kDrop: in->actuators_lost = in->actuators_lost || awaited; break;
    case LinkAction::kDelay:
      in->delayed_actuators.assign(data, data + n);
      in->actuators_lost = in->actuators_lost || awaited;
      break;
    case LinkAction::kCorrupt: {
      std::vector<uint8_t> bad(data, data + n);
      in->faults->Corrupt(bad.data(), n);
      uvms_actuators_t mm;
      if (uvms_actuators_t_decode_checked(bad.data(), n, &mm) < 0) {
        ++in->rx_rejected;  // the CRC caught it, as it catches every single-bit error
        in->actuators_lost = in->actuators_lost || awaited;
      } else {
        AcceptActuators(in, mm, bad.data(), n);
      }
      break;
    }
  }
}

void OnTelemetry(const lcm_recv_buf_t *rb, const char *ch, void *user) {
  auto *in = static_cast<Inbox *>(user);
  uvms_telemetry_t m;
  const auto *data = static_cast<const uint8_t *>(rb->data);
  if (uvms_telemetry_t_decode_checked(data, int(rb->data_size), &m) < 0) {
    ++in->rx_rejected;
    return;
  }
  if (m.tick != in->expect_tick || in->have_telemetry) {
    // Config acknowledgements repeated after a config re-send are expected handshake noise;
    // anything else is out of sequence. Neither is recorded twice.
    if (m.tick != -1) {
      ++in->rx_out_of_sequence;
      in->rec->Write(ch, data, int(rb->data_size), m.utime);
    }
    return;
  }
  in->rec->Write(ch, data, int(rb->data_size), m.utime);
  in->telemetry = m;
  in->have_telemetry = true;
}

// Encode, record, and (unless record_only) publish one message.
template <typename T, typename Enc>
int Publish(lcm_t *lcm, Recorder &rec, const char *channel, const T &msg, int64_t utime, Enc enc,
            std::vector<uint8_t> &buf, bool record_only = false) {
  const int n = enc(&msg, buf.data(), int(buf.size()));
  if (n < 0) throw std::runtime_error(std::string("encoding for ") + channel + " failed");
  rec.Write(channel, buf.data(), n, utime);
  return record_only ? 0 : lcm_publish(lcm, channel, buf.data(), unsigned(n));
}

void Copy3(double *dst, const plant::Vec3 &v) {
  for (int k = 0; k < 3; ++k) dst[k] = v[k];
}
void CopyQuat(double *wxyz, const Eigen::Quaterniond &q) {
  wxyz[0] = q.w();
  wxyz[1] = q.x();
  wxyz[2] = q.y();
  wxyz[3] = q.z();
}
std::array<double, 3> Arr3(const plant::Vec3 &v) { return {v[0], v[1], v[2]}; }

// The health mask is the caller's (FaultInjector::HealthMask).
void FillSensors(const plant::Truth &t, long k, int64_t utime, uvms_sensors_t &s) {
  std::memset(&s, 0, sizeof s);
  s.utime = utime;
  s.tick = k;
  Copy3(s.position_m, t.r0_m);
  CopyQuat(s.quaternion_wxyz, t.attitude);
  Copy3(s.velocity_m_s, t.v0_m_s);
  Copy3(s.angular_velocity_rad_s, t.w0_rad_s);
  for (size_t i = 0; i < t.q_rad.size() && i < 7; ++i) {
    s.joint_position_rad[i] = t.q_rad[i];
    s.joint_velocity_rad_s[i] = t.qd_rad_s[i];
  }
  for (size_t j = 0; j < t.motor_speed_rad_s.size() && j < 8; ++j) {
    s.motor_speed_rad_s[j] = t.motor_speed_rad_s[j];
    s.motor_current_A[j] = t.motor_current_A[j];
  }
}

void FillTruthMsg(const plant::Truth &t, long k, int64_t utime, const std::string &pair,
                  uvms_truth_t &m) {
  std::memset(&m, 0, sizeof m);
  m.utime = utime;
  m.tick = k;
  Copy3(m.position_m, t.r0_m);
  CopyQuat(m.quaternion_wxyz, t.attitude);
  Copy3(m.velocity_m_s, t.v0_m_s);
  Copy3(m.angular_velocity_rad_s, t.w0_rad_s);
  Copy3(m.acceleration_m_s2, t.accel_m_s2);
  Copy3(m.angular_acceleration_rad_s2, t.alpha_rad_s2);
  for (size_t i = 0; i < t.q_rad.size() && i < 7; ++i) {
    m.joint_position_rad[i] = t.q_rad[i];
    m.joint_velocity_rad_s[i] = t.qd_rad_s[i];
    m.joint_torque_Nm[i] = i < t.joint_torque_Nm.size() ? t.joint_torque_Nm[i] : 0.0;
  }
  for (size_t j = 0; j < t.motor_speed_rad_s.size() && j < 8; ++j) {
    m.motor_speed_rad_s[j] = t.motor_speed_rad_s[j];
    m.motor_current_A[j] = t.motor_current_A[j];
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

const char *FailureName(int32_t code) {
  switch (code) {
    case UVMS_RUN_STATUS_T_OK: return "";
    case UVMS_RUN_STATUS_T_CONTROLLER_SILENT: return "controller_silent";
    case UVMS_RUN_STATUS_T_INTEGRATOR_FAILURE: return "integrator_failure";
    case UVMS_RUN_STATUS_T_CONTACT: return "contact";
    case UVMS_RUN_STATUS_T_BAD_INPUT: return "bad_input";
    case UVMS_RUN_STATUS_T_CONFIG_REJECTED: return "config_rejected";
    case UVMS_RUN_STATUS_T_NO_CONTROLLER: return "no_controller";
    default: return "unknown";
  }
}

// Wait until pred() or the deadline, handling LCM messages; each wait busy-polls for spin_us
// first (sil/lcm_wait.h). Returns pred().
template <typename Pred>
bool HandleUntil(lcm_t *lcm, Clock::time_point deadline, int spin_us, Pred pred) {
  while (!pred()) {
    const long long left_ms =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    // Past the deadline the wait is one non-blocking look (a message may be queued already).
    const int r = uvms_lcm_wait(lcm, int(std::clamp<long long>(left_ms, 0, 100)), spin_us);
    if (r < 0 || (r == 0 && left_ms <= 0)) return pred();
  }
  return true;
}

}  // namespace

RunSummary RunPlantNode(const Scenario &sc, lcm_t *lcm, const PlantNodeOptions &opt) {
  const auto wall0 = Clock::now();
  RunSummary sum;
  sum.scenario = sc.source;
  sum.name = sc.name;
  sum.drive = uvms_drive_str(sc.controller.drive);
  sum.ticks_planned = long(ScenarioTicks(sc));  // round up: the run covers duration_s

  Recorder rec(opt.log_path);
  FaultInjector faults(sc.faults, sc.seed, int(sc.plant.thrusters.size()));
  Inbox inbox;
  inbox.rec = &rec;
  inbox.faults = &faults;
  lcm_subscription_t *sub_act = lcm_subscribe(lcm, UVMS_CH_ACTUATORS, OnActuators, &inbox);
  lcm_subscription_t *sub_tel = lcm_subscribe(lcm, UVMS_CH_TELEMETRY, OnTelemetry, &inbox);
  if (sub_act == nullptr || sub_tel == nullptr) throw std::runtime_error("LCM subscription failed");

  plant::Plant plant(sc.plant);
  plant.Reset(sc.initial);
  const int nt = int(sc.plant.thrusters.size());
  const int nj = int(sc.plant.links.size());
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);

  int32_t code = UVMS_RUN_STATUS_T_OK;
  std::string reason;

  // --- Handshake: the configuration, re-sent until the controller answers. ---
  uvms_controller_config_t cfg_msg;
  uvms_config_to_msg(&sc.controller, &cfg_msg);
  inbox.expect_tick = -1;
  {
    const auto deadline = wall0 + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(opt.startup_timeout_s));
    bool first = true;
    while (!inbox.have_telemetry && Clock::now() < deadline) {
      const int n = uvms_controller_config_t_encode_sealed(&cfg_msg, buf.data(), int(buf.size()));
      if (first) rec.Write(UVMS_CH_CONFIG, buf.data(), n, 0);
      else ++sum.config_retries;
      first = false;
      lcm_publish(lcm, UVMS_CH_CONFIG, buf.data(), unsigned(n));
      HandleUntil(lcm, std::min(deadline, Clock::now() + std::chrono::milliseconds(20)), opt.spin_us,
                  [&] { return inbox.have_telemetry; });
    }
    if (!inbox.have_telemetry) {
      code = UVMS_RUN_STATUS_T_NO_CONTROLLER;
      reason = "the controller did not answer its configuration within " +
               std::to_string(opt.startup_timeout_s) + " s";
    } else if (inbox.telemetry.status != 0) {
      code = UVMS_RUN_STATUS_T_CONFIG_REJECTED;
      reason = std::string("the controller rejected its configuration: ") +
               uvms_status_str(uvms_status_t(inbox.telemetry.status)) + " in " +
               uvms_cfg_field_str(uvms_cfg_field_t(inbox.telemetry.config_error));
    }
  }

  // --- The lockstep loop. ---
  const plant::Truth &truth = plant.truth();
  sum.initial_barycenter_m = Arr3(truth.barycenter_m);
  sum.initial_vehicle_position_m = Arr3(truth.r0_m);
  const Eigen::Quaterniond q_initial = truth.attitude;
  plant::PlantInputs held;
  held.motor_voltage_V.assign(size_t(nt), 0.0);
  held.motor_current_cmd_A.assign(size_t(nt), 0.0);
  held.motor_current_rate_A_s.assign(size_t(nt), 0.0);
  held.joint_accel_rad_s2.assign(size_t(nj), 0.0);
  double ee_err_sum = 0.0;
  long ee_samples = 0, consecutive_missed = 0;
  std::vector<int64_t> target_instructions;  // per tick, from telemetry (PIL; 0 on the host)
  const auto timeout = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(sc.link.timeout_s));
  const auto loop_wall0 = Clock::now();

  if (code == UVMS_RUN_STATUS_T_OK) {
    uvms_run_status_t st{};
    st.state = UVMS_RUN_STATUS_T_RUNNING;
    Publish(lcm, rec, UVMS_CH_STATUS, st, 0, uvms_run_status_t_encode_sealed, buf);
  }
  long k = 0;
  std::string pair;
  std::vector<uint8_t> delayed_sensors;  // held back one tick by a link fault
  int64_t delayed_utime = 0;
  for (; code == UVMS_RUN_STATUS_T_OK && k < sum.ticks_planned; ++k) {
    const int64_t utime = TickUtime(k, sc.tick_s);
    if (sc.link.realtime_factor > 0.0) {
      std::this_thread::sleep_until(loop_wall0 + std::chrono::duration_cast<Clock::duration>(
                                                     std::chrono::duration<double>(
                                                         double(k) * sc.tick_s / sc.link.realtime_factor)));
    }
    pair = truth.closest_a + "|" + truth.closest_b;
    uvms_truth_t tm;
    FillTruthMsg(truth, k, utime, pair, tm);
    Publish(lcm, rec, UVMS_CH_TRUTH, tm, utime, uvms_truth_t_encode_sealed, buf,
            !sc.link.publish_truth);
    uvms_sensors_t sm;
    FillSensors(truth, k, utime, sm);
    sm.thruster_usable_mask = int32_t(faults.HealthMask(double(k) * sc.tick_s));
    faults.PerturbSensors(sm);
    inbox.expect_tick = k;
    inbox.have_actuators = inbox.have_telemetry = inbox.actuators_lost = false;
    // Messages a link fault held back one tick go out (or come in) first.
    if (!delayed_sensors.empty()) {
      rec.Write(UVMS_CH_SENSORS, delayed_sensors.data(), int(delayed_sensors.size()), delayed_utime);
      lcm_publish(lcm, UVMS_CH_SENSORS, delayed_sensors.data(), unsigned(delayed_sensors.size()));
      delayed_sensors.clear();
    }
    if (!inbox.delayed_actuators.empty()) {
      std::vector<uint8_t> late;
      late.swap(inbox.delayed_actuators);
      uvms_actuators_t m;
      if (uvms_actuators_t_decode_checked(late.data(), int(late.size()), &m) > 0)
        AcceptActuators(&inbox, m, late.data(), int(late.size()));
    }
    bool sensors_lost = false;
    {
      const int n = uvms_sensors_t_encode_sealed(&sm, buf.data(), int(buf.size()));
      if (n < 0) throw std::runtime_error("encoding sensors failed");
      const LinkAction action = faults.NextSensorsAction();
      switch (action) {
        case LinkAction::kDeliver:
        case LinkAction::kDuplicate:  // the controller drops the copy (same tick) and counts it
          for (int copy = 0; copy < (action == LinkAction::kDuplicate ? 2 : 1); ++copy) {
            rec.Write(UVMS_CH_SENSORS, buf.data(), n, utime);
            lcm_publish(lcm, UVMS_CH_SENSORS, buf.data(), unsigned(n));
          }
          break;
        case LinkAction::kDrop: sensors_lost = true; break;
        case LinkAction::kDelay:
          delayed_sensors.assign(buf.begin(), buf.begin() + n);
          delayed_utime = utime;
          sensors_lost = true;
          break;
        case LinkAction::kCorrupt:
          faults.Corrupt(buf.data(), n);
          rec.Write(UVMS_CH_SENSORS, buf.data(), n, utime);
          lcm_publish(lcm, UVMS_CH_SENSORS, buf.data(), unsigned(n));
          sensors_lost = true;  // the controller's CRC check rejects it
          break;
      }
    }

    // A tick whose sensors the link lost gets no answer: it is missed without waiting.
    const bool got_actuators =
        !sensors_lost && HandleUntil(lcm, Clock::now() + timeout, opt.spin_us, [&] {
          return inbox.have_actuators || inbox.actuators_lost;
        }) && inbox.have_actuators;
    if (got_actuators) {
      consecutive_missed = 0;
      for (int j = 0; j < nt; ++j) {
        held.motor_voltage_V[size_t(j)] = inbox.actuators.motor_voltage_V[j];
        held.motor_current_cmd_A[size_t(j)] = inbox.actuators.motor_current_cmd_A[j];
        held.motor_current_rate_A_s[size_t(j)] = inbox.actuators.motor_current_rate_A_s[j];
      }
      for (int i = 0; i < nj; ++i)
        held.joint_accel_rad_s2[size_t(i)] = inbox.actuators.joint_acceleration_rad_s2[i];
      if (inbox.actuators.status != 0) ++sum.controller_error_ticks;
      sum.controller_flags_seen |= uint32_t(inbox.actuators.flags);
    } else {
      // A missed tick holds the last command. The current drive holds the current its ramp
      // reached (rate 0), as a power stage holds its last set point; it does not extrapolate.
      // (If the controller did step, its I* is one ramp ahead: the next command jumps there.)
      for (int j = 0; j < nt; ++j) {
        held.motor_current_cmd_A[size_t(j)] += held.motor_current_rate_A_s[size_t(j)] * sc.tick_s;
        held.motor_current_rate_A_s[size_t(j)] = 0.0;
      }
      ++sum.missed_ticks;
      if (++consecutive_missed > sc.link.max_missed) {
        code = UVMS_RUN_STATUS_T_CONTROLLER_SILENT;
        reason = "no actuators for " + std::to_string(consecutive_missed) +
                 " consecutive ticks (timeout " + std::to_string(sc.link.timeout_s) +
                 " s, max_missed " + std::to_string(sc.link.max_missed) + ") at tick " +
                 std::to_string(k);
        break;
      }
    }
    // Truth of tick k, for its metrics once the controller's telemetry k is in (below).
    const plant::Vec3 ee_truth_k = truth.ee_m;
    sum.max_attitude_error_rad =
        std::max(sum.max_attitude_error_rad, truth.attitude.angularDistance(q_initial));

    // Integrate to k+1 while the controller's telemetry of tick k is on its way (the
    // controller publishes it right after the actuators), then collect it: the log order
    // (sensors k, actuators k, telemetry k, truth k+1, ...) does not depend on timing.
    plant::PlantInputs applied = held;  // what reaches the plant: thruster faults act here
    faults.ApplyThrusterFaults(double(k) * sc.tick_s, applied);
    const plant::StepStatus ps = plant.Step(applied, sc.tick_s);
    if ((got_actuators || inbox.actuators_lost) && !inbox.have_telemetry) {
      HandleUntil(lcm, Clock::now() + timeout, opt.spin_us, [&] { return inbox.have_telemetry; });
    }
    // Metrics of tick k (SPEC §10): truth at t_k against the controller's estimate at t_k.
    if (inbox.have_telemetry) {
      const plant::Vec3 est(inbox.telemetry.ee_estimate_m[0], inbox.telemetry.ee_estimate_m[1],
                            inbox.telemetry.ee_estimate_m[2]);
      const double e = (ee_truth_k - est).norm();
      ee_err_sum += e;
      ++ee_samples;
      sum.max_ee_error_m = std::max(sum.max_ee_error_m, e);
      sum.final_ee_error_m = e;
      const uvms_telemetry_t &tl = inbox.telemetry;
      sum.alloc_min_rank = std::min(sum.alloc_min_rank, int(tl.alloc_rank));
      sum.uncontrollable_axes_seen |= uint32_t(tl.uncontrollable_axes);
      const uint32_t fl = uint32_t(tl.flags);
      sum.saturated_ticks += (fl & UVMS_FLAG_THRUST_SATURATED) != 0;
      sum.sensor_held_ticks += (fl & UVMS_FLAG_SENSOR_HELD) != 0;
      sum.sensor_hold_expired_ticks += (fl & UVMS_FLAG_SENSOR_HOLD_EXPIRED) != 0;
      double df = 0.0, dm = 0.0;
      for (int a = 0; a < 3; ++a) {
        df += std::pow(tl.force_des_N[a] - tl.force_deliverable_N[a], 2);
        dm += std::pow(tl.moment_des_Nm[a] - tl.moment_deliverable_Nm[a], 2);
      }
      if (tl.status == 0) {  // a failed tick delivers nothing by design: not a shortfall
        sum.max_force_shortfall_N = std::max(sum.max_force_shortfall_N, std::sqrt(df));
        sum.max_moment_shortfall_Nm = std::max(sum.max_moment_shortfall_Nm, std::sqrt(dm));
      }
      sum.controller_rx_rejected = inbox.telemetry.rx_rejected;
      sum.controller_rx_out_of_sequence = inbox.telemetry.rx_out_of_sequence;
      sum.controller_rx_unconfigured = inbox.telemetry.rx_unconfigured;
      target_instructions.push_back(inbox.telemetry.target_instructions);
    } else {
      ++sum.missing_telemetry;
    }
    if (!ps.ok()) {
      code = ps.code == plant::StepStatus::Code::kContact ? UVMS_RUN_STATUS_T_CONTACT
             : ps.code == plant::StepStatus::Code::kBadInput ? UVMS_RUN_STATUS_T_BAD_INPUT
                                                             : UVMS_RUN_STATUS_T_INTEGRATOR_FAILURE;
      reason = ps.message;
      if (ps.code == plant::StepStatus::Code::kContact) ++k;  // the tick was integrated
      break;
    }
  }
  sum.ticks = k;
  sum.duration_s = double(k) * sc.tick_s;
  const int64_t utime_end = TickUtime(k, sc.tick_s);
  {
    pair = truth.closest_a + "|" + truth.closest_b;
    uvms_truth_t tm;
    FillTruthMsg(truth, k, utime_end, pair, tm);
    Publish(lcm, rec, UVMS_CH_TRUTH, tm, utime_end, uvms_truth_t_encode_sealed, buf,
            !sc.link.publish_truth);
  }
  sum.faults = faults.counters();
  sum.rx_rejected = inbox.rx_rejected;
  sum.rx_out_of_sequence = inbox.rx_out_of_sequence;
  {
    uvms_run_status_t st{};
    st.utime = utime_end;
    st.tick = k;
    st.state = code == UVMS_RUN_STATUS_T_OK ? UVMS_RUN_STATUS_T_FINISHED : UVMS_RUN_STATUS_T_FAILED;
    st.code = code;
    st.missed_ticks = int32_t(sum.missed_ticks);
    st.rx_rejected = int32_t(sum.rx_rejected);
    st.rx_out_of_sequence = int32_t(sum.rx_out_of_sequence);
    std::strncpy(reinterpret_cast<char *>(st.reason), reason.c_str(), sizeof st.reason - 1);
    Publish(lcm, rec, UVMS_CH_STATUS, st, utime_end, uvms_run_status_t_encode_sealed, buf);
  }
  lcm_unsubscribe(lcm, sub_act);
  lcm_unsubscribe(lcm, sub_tel);

  sum.status = code == UVMS_RUN_STATUS_T_OK ? "finished" : "failed";
  sum.failure = FailureName(code);
  sum.reason = reason;
  sum.mean_ee_error_m = ee_samples > 0 ? ee_err_sum / double(ee_samples) : 0.0;
  if (!target_instructions.empty()) {  // median: the lower middle element (an integer count)
    std::sort(target_instructions.begin(), target_instructions.end());
    sum.target_instructions_median = long(target_instructions[(target_instructions.size() - 1) / 2]);
    sum.target_instructions_max = long(target_instructions.back());
  }
  sum.thruster_energy_J = truth.thruster_energy_J;
  sum.thruster_energy_signed_J = truth.thruster_energy_signed_J;
  sum.manipulator_energy_J = truth.manipulator_energy_J;
  sum.propulsive_energy_J = truth.propulsive_energy_J;
  sum.min_clearance_m = truth.min_clearance_m;
  sum.final_ee_position_m = Arr3(truth.ee_m);
  sum.final_barycenter_m = Arr3(truth.barycenter_m);
  sum.final_vehicle_position_m = Arr3(truth.r0_m);
  const auto stats = plant.integrator_stats();
  sum.integrator_steps = stats.steps;
  sum.integrator_rhs_evals = stats.rhs_evals;
  sum.wall_time_s = SecondsSince(wall0);
  sum.real_time_factor = sum.wall_time_s > 0 ? sum.duration_s / sum.wall_time_s : 0.0;
  return sum;
}

void WriteSummaryJson(const RunSummary &s, const std::string &path) {
  nlohmann::ordered_json j;
  j["scenario"] = s.scenario;
  j["name"] = s.name;
  j["transport"] = s.transport;
  j["drive"] = s.drive;
  j["status"] = s.status;
  j["failure"] = s.failure;
  j["reason"] = s.reason;
  j["ticks"] = s.ticks;
  j["ticks_planned"] = s.ticks_planned;
  j["missed_ticks"] = s.missed_ticks;
  j["duration_s"] = s.duration_s;
  j["mean_ee_error_m"] = s.mean_ee_error_m;
  j["max_ee_error_m"] = s.max_ee_error_m;
  j["final_ee_error_m"] = s.final_ee_error_m;
  j["thruster_energy_J"] = s.thruster_energy_J;
  j["thruster_energy_signed_J"] = s.thruster_energy_signed_J;
  j["manipulator_energy_J"] = s.manipulator_energy_J;
  j["propulsive_energy_J"] = s.propulsive_energy_J;
  j["max_attitude_error_rad"] = s.max_attitude_error_rad;
  j["min_clearance_m"] = std::isfinite(s.min_clearance_m) ? nlohmann::ordered_json(s.min_clearance_m)
                                                          : nlohmann::ordered_json(nullptr);
  j["final_ee_position_m"] = s.final_ee_position_m;
  j["final_barycenter_m"] = s.final_barycenter_m;
  j["initial_barycenter_m"] = s.initial_barycenter_m;
  j["final_vehicle_position_m"] = s.final_vehicle_position_m;
  j["initial_vehicle_position_m"] = s.initial_vehicle_position_m;
  j["rx_rejected"] = s.rx_rejected;
  j["rx_out_of_sequence"] = s.rx_out_of_sequence;
  j["missing_telemetry"] = s.missing_telemetry;
  j["config_retries"] = s.config_retries;
  j["controller_rx_rejected"] = s.controller_rx_rejected;
  j["controller_rx_out_of_sequence"] = s.controller_rx_out_of_sequence;
  j["controller_rx_unconfigured"] = s.controller_rx_unconfigured;
  j["controller_error_ticks"] = s.controller_error_ticks;
  j["controller_flags_seen"] = s.controller_flags_seen;
  j["alloc_min_rank"] = s.alloc_min_rank;
  j["uncontrollable_axes_seen"] = s.uncontrollable_axes_seen;
  j["saturated_ticks"] = s.saturated_ticks;
  j["sensor_held_ticks"] = s.sensor_held_ticks;
  j["sensor_hold_expired_ticks"] = s.sensor_hold_expired_ticks;
  j["max_force_shortfall_N"] = s.max_force_shortfall_N;
  j["max_moment_shortfall_Nm"] = s.max_moment_shortfall_Nm;
  j["target_instructions_median"] = s.target_instructions_median;
  j["target_instructions_max"] = s.target_instructions_max;
  j["integrator_steps"] = s.integrator_steps;
  j["integrator_rhs_evals"] = s.integrator_rhs_evals;
  const FaultCounters &fc = s.faults;
  j["faults"] = {{"sensors_dropped", fc.sensors_dropped},
                 {"sensors_delayed", fc.sensors_delayed},
                 {"sensors_duplicated", fc.sensors_duplicated},
                 {"sensors_corrupted", fc.sensors_corrupted},
                 {"actuators_dropped", fc.actuators_dropped},
                 {"actuators_delayed", fc.actuators_delayed},
                 {"actuators_duplicated", fc.actuators_duplicated},
                 {"actuators_corrupted", fc.actuators_corrupted},
                 {"sensor_samples_perturbed", fc.sensor_samples_perturbed},
                 {"thruster_fault_ticks", fc.thruster_fault_ticks}};
  nlohmann::ordered_json prov = nlohmann::ordered_json::object();
  for (const auto &kv : s.provenance) prov[kv.first] = kv.second;
  j["provenance"] = prov;
  j["wall_time_s"] = s.wall_time_s;
  j["real_time_factor"] = s.real_time_factor;
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << std::setw(2) << j << '\n';
  if (!f) throw std::runtime_error("writing " + path + " failed");
}

}  // namespace uvms::sil
