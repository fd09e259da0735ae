// SPDX-License-Identifier: Apache-2.0
// plant_node.cpp: the plant side of a run (plant_node.hpp): a PlantRun wires the parts together
// and RunPlantNode runs it: handshake, lockstep ticks, end, summary.
#include "run/plant_node.hpp"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include "msg/codec.h"
#include "msg/session.h"
#include "run/faults.hpp"
#include "run/lcm_bus.hpp"
#include "run/lockstep_link.hpp"
#include "run/plant_messages.hpp"
#include "run/recorder.hpp"
#include "run/run_metrics.hpp"

namespace uvms::sil {

namespace {
volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void OnStopSignal(int sig) {
  g_stop_signal = sig;
  std::signal(SIGTERM, SIG_DFL);  // a second signal ends the process
  std::signal(SIGINT, SIG_DFL);
}
}  // namespace

void InstallPlantStopHandlers() {
  struct sigaction sa {};
  sa.sa_handler = OnStopSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a blocking wait returns early with EINTR
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
}

int PlantStopSignal() { return int(g_stop_signal); }
void RequestPlantStop(int signal_number) { g_stop_signal = signal_number; }

namespace {

using Clock = std::chrono::steady_clock;

Clock::duration Seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

// How a run ended: a run_status_t code (OK: it has not ended early) and a readable cause.
struct Outcome {
  int32_t code{UVMS_RUN_STATUS_T_OK};
  std::string reason;
  bool ok() const { return code == UVMS_RUN_STATUS_T_OK; }
};

// Start the plant at t = 0; its truth there.
const plant::Truth &ResetPlant(plant::Plant &plant, const plant::InitialState &initial) {
  plant.Reset(initial);
  return plant.truth();
}

// The plant's inputs from the controller's actuators (held over the tick: zero-order hold).
void TakeCommand(const uvms_actuators_t &a, plant::PlantInputs &held) {
  for (size_t j = 0; j < held.motor_voltage_V.size(); ++j) {
    held.motor_voltage_V[j] = a.motor_voltage_V[j];
    held.motor_current_cmd_A[j] = a.motor_current_cmd_A[j];
    held.motor_current_rate_A_s[j] = a.motor_current_rate_A_s[j];
  }
  for (size_t i = 0; i < held.joint_accel_rad_s2.size(); ++i)
    held.joint_accel_rad_s2[i] = a.joint_acceleration_rad_s2[i];
}

// A missed tick holds the last command. The current drive holds the current its ramp reached
// (rate 0), as a power stage holds its last set point; it does not extrapolate. (If the
// controller did step, its I* is one ramp ahead: the next command jumps there.)
void HoldCommand(double tick_s, plant::PlantInputs &held) {
  for (size_t j = 0; j < held.motor_current_cmd_A.size(); ++j) {
    held.motor_current_cmd_A[j] += held.motor_current_rate_A_s[j] * tick_s;
    held.motor_current_rate_A_s[j] = 0.0;
  }
}

Outcome PlantFailure(const plant::StepStatus &ps) {
  if (ps.ok()) return {};
  return {ps.code == plant::StepStatus::Code::kContact    ? UVMS_RUN_STATUS_T_CONTACT
          : ps.code == plant::StepStatus::Code::kBadInput ? UVMS_RUN_STATUS_T_BAD_INPUT
                                                          : UVMS_RUN_STATUS_T_INTEGRATOR_FAILURE,
          ps.message};
}

// The end of a run as a run_status_t (state FINISHED or FAILED).
uvms_run_status_t EndStatus(const Outcome &out, long ticks, int64_t utime, const RunSummary &counts) {
  uvms_run_status_t st{};
  st.utime = utime;
  st.tick = ticks;
  st.state = out.ok() ? UVMS_RUN_STATUS_T_FINISHED : UVMS_RUN_STATUS_T_FAILED;
  st.code = out.code;
  st.missed_ticks = int32_t(counts.missed_ticks);
  st.rx_rejected = int32_t(counts.rx_rejected);
  st.rx_out_of_sequence = int32_t(counts.rx_out_of_sequence);
  st.rx_foreign_session = int32_t(counts.rx_foreign_session);
  std::strncpy(reinterpret_cast<char *>(st.reason), out.reason.c_str(), sizeof st.reason - 1);
  return st;
}

// One run of the plant side: the parts of plant_node.hpp, wired together.
class PlantRun {
 public:
  PlantRun(const Scenario &sc, LinkBus &bus, const PlantNodeOptions &opt)
      : sc_(sc),
        rec_(opt.log_path),
        faults_(sc.faults, sc.seed, int(sc.plant.thrusters.size())),
        link_(bus, rec_, faults_, opt.spin_us, opt.session),
        plant_(sc.plant),
        metrics_(sc, plant_.params(), ResetPlant(plant_, sc.initial)),
        timeout_(Seconds(sc.link.timeout_s)) {
    held_.motor_voltage_V.assign(sc.plant.thrusters.size(), 0.0);
    held_.motor_current_cmd_A.assign(sc.plant.thrusters.size(), 0.0);
    held_.motor_current_rate_A_s.assign(sc.plant.thrusters.size(), 0.0);
    held_.joint_accel_rad_s2.assign(sc.plant.links.size(), 0.0);
  }

  Outcome Handshake(Clock::time_point deadline, double timeout_s, long *retries);
  Outcome Lockstep(long ticks_planned);
  Outcome Judge(const VerdictLimits &limits) const {
    const Verdict v = metrics_.Judge(limits, ticks_, plant_.truth());
    return {v.code, v.reason};
  }
  void End(const Outcome &out);
  void Summarize(const Outcome &out, RunSummary *sum) const;

 private:
  struct TickResult {
    Outcome outcome;
    bool integrated;  // the tick was integrated (counts as done even if the run ends)
  };
  TickResult Tick(long k);
  void MeasureIntegrated();
  void PaceToRealTime(long k) const;
  void SendTruth(long k, int64_t utime);
  uvms_sensors_t Sense(long k, int64_t utime);
  Outcome MissTick(long k);
  plant::StepStatus Integrate(long k);

  const Scenario &sc_;
  Recorder rec_;
  FaultInjector faults_;
  LockstepLink link_;
  plant::Plant plant_;
  RunMetrics metrics_;
  plant::PlantInputs held_;  // the last command, held over each tick
  Clock::duration timeout_;
  Clock::time_point loop_wall0_;
  long ticks_{0}, consecutive_missed_{0};
  double plant_wall_s_{0.0};  // wall time inside plant_.Step [s]
  std::string pair_;  // the truth message's closest pair (outlives its encoding)
  struct Integrated {  // the last tick integrated, not yet measured (MeasureIntegrated)
    bool pending{false};
    long tick{-1};
    plant::Vec3 ee_truth_m;  // the truth's EE at the tick's start [m]
    bool has_telemetry{false};
    std::uint32_t usable_mask{0};  // the usable-thruster mask its sensors carried
    uvms_telemetry_t telemetry;    // its telemetry (if has_telemetry)
  } integrated_;
};

// --- Handshake: the configuration, re-sent until the controller answers. ---
Outcome PlantRun::Handshake(Clock::time_point deadline, double timeout_s, long *retries) {
  uvms_controller_config_t cfg;
  uvms_config_to_msg(&sc_.controller, &cfg);
  const uvms_telemetry_t *answer = link_.Configure(cfg, deadline, retries);
  if (answer == nullptr)
    return {UVMS_RUN_STATUS_T_NO_CONTROLLER, "the controller did not answer its configuration within " +
                                                 std::to_string(timeout_s) + " s"};
  if (answer->status != 0)
    return {UVMS_RUN_STATUS_T_CONFIG_REJECTED,
            std::string("the controller rejected its configuration: ") +
                uvms_status_str(uvms_status_t(answer->status)) + " in " +
                uvms_cfg_field_str(uvms_cfg_field_t(answer->config_error))};
  return {};
}

// --- The lockstep loop. ---
Outcome PlantRun::Lockstep(long ticks_planned) {
  loop_wall0_ = Clock::now();
  link_.SendScene(SceneMessage(plant_.params()).msg(), sc_.link.publish_truth);
  uvms_run_status_t running{};
  running.state = UVMS_RUN_STATUS_T_RUNNING;
  link_.SendStatus(running, 0);
  for (long k = 0; k < ticks_planned; ++k) {
    if (const int sig = PlantStopSignal(); sig != 0) {
      MeasureIntegrated();
      return {UVMS_RUN_STATUS_T_INTERRUPTED, std::string("interrupted by ") +
                                                 (sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal") +
                                                 " at tick " + std::to_string(k)};
    }
    TickResult r;
    try {
      r = Tick(k);
    } catch (...) {  // a harness error (a log write): the summary counts the ticks integrated
      if (integrated_.pending && integrated_.tick == k) ticks_ = k + 1;
      MeasureIntegrated();
      throw;
    }
    ticks_ = r.integrated ? k + 1 : k;
    if (!r.outcome.ok()) {
      MeasureIntegrated();
      return r.outcome;
    }
  }
  MeasureIntegrated();
  return {};
}

// One tick: the data flow of SPEC §5, in order. The sensors go out first; the plant's
// bookkeeping (the truth to the log, the measurement of tick k-1) is done while the controller
// computes tick k, so that over a link to another process it costs no wall time. Truth that is
// also published goes out before the sensors, as before every other message of its tick: a
// listener (lcm-logger, then `uvms replay`) sees each tick open with its truth.
PlantRun::TickResult PlantRun::Tick(long k) {
  const int64_t utime = TickUtime(k, sc_.tick_s);
  PaceToRealTime(k);
  const bool truth_on_link = sc_.link.publish_truth;
  if (truth_on_link) SendTruth(k, utime);               // truth(k) to the link and the log
  const uvms_sensors_t sensors = Sense(k, utime);       // truth + health mask + noise
  link_.BeginTick(k);                                   // late messages of tick k-1 first
  const bool sensors_sent = link_.SendSensors(sensors, utime);
  if (!truth_on_link) SendTruth(k, utime);  // truth(k) to the log, before what the link held back
  link_.ReleaseRecords();
  MeasureIntegrated();    // tick k-1
  // A tick whose sensors the link lost gets no answer: it is missed without waiting.
  const bool answered = sensors_sent && link_.AwaitActuators(timeout_);
  if (answered) {
    consecutive_missed_ = 0;
    TakeCommand(link_.actuators(), held_);
    metrics_.OnActuators(link_.actuators());
  } else if (Outcome silent = MissTick(k); !silent.ok()) {
    return {silent, false};
  }
  const plant::Vec3 ee_truth_k = plant_.truth().ee_m;  // for the metrics of tick k
  metrics_.OnTruth(plant_.truth());
  const plant::StepStatus ps = Integrate(k);            // k -> k+1, command held
  integrated_.pending = true;  // measured in the next tick (MeasureIntegrated)
  integrated_.tick = k;
  integrated_.ee_truth_m = ee_truth_k;
  integrated_.usable_mask = uint32_t(sensors.thruster_usable_mask);
  integrated_.has_telemetry = false;
  if (const uvms_telemetry_t *telemetry = link_.CollectTelemetry(answered, timeout_)) {
    integrated_.has_telemetry = true;
    integrated_.telemetry = *telemetry;
  }
  const Outcome failed = PlantFailure(ps);
  return {failed, failed.ok() || ps.code == plant::StepStatus::Code::kContact};
}

// The measurement of the last tick integrated, against the truth it ended in (unchanged until
// the next step): in the next tick while the controller computes, or at the end of the run.
void PlantRun::MeasureIntegrated() {
  if (!integrated_.pending) return;
  integrated_.pending = false;
  const uvms_telemetry_t *telemetry = integrated_.has_telemetry ? &integrated_.telemetry : nullptr;
  metrics_.OnTelemetry(integrated_.ee_truth_m, telemetry);
  metrics_.OnTickIntegrated(plant_.truth(), telemetry, integrated_.usable_mask);
}

void PlantRun::PaceToRealTime(long k) const {
  if (sc_.link.realtime_factor <= 0.0) return;
  std::this_thread::sleep_until(loop_wall0_ +
                                Seconds(double(k) * sc_.tick_s / sc_.link.realtime_factor));
}

void PlantRun::SendTruth(long k, int64_t utime) {
  if (!rec_.recording() && !sc_.link.publish_truth) return;  // nobody takes it (--no-log)
  pair_ = plant_.truth().closest_a + "|" + plant_.truth().closest_b;
  uvms_truth_t tm;
  FillTruthMsg(plant_.truth(), k, utime, pair_, tm);
  link_.SendTruth(tm, utime, sc_.link.publish_truth);
}

uvms_sensors_t PlantRun::Sense(long k, int64_t utime) {
  uvms_sensors_t sm;
  FillSensors(plant_.truth(), k, utime, sm);
  sm.thruster_usable_mask = int32_t(faults_.HealthMask(double(k) * sc_.tick_s));
  faults_.PerturbSensors(sm);
  return sm;
}

Outcome PlantRun::MissTick(long k) {
  HoldCommand(sc_.tick_s, held_);
  metrics_.OnMissedTick();
  if (++consecutive_missed_ <= sc_.link.max_missed) return {};
  return {UVMS_RUN_STATUS_T_CONTROLLER_SILENT,
          "no actuators for " + std::to_string(consecutive_missed_) + " consecutive ticks (timeout " +
              std::to_string(sc_.link.timeout_s) + " s, max_missed " +
              std::to_string(sc_.link.max_missed) + ") at tick " + std::to_string(k)};
}

// What reaches the plant is the held command with the thruster faults applied.
plant::StepStatus PlantRun::Integrate(long k) {
  plant::PlantInputs applied = held_;
  faults_.ApplyThrusterFaults(double(k) * sc_.tick_s, applied);
  const auto t0 = Clock::now();
  plant::StepStatus st = plant_.Step(applied, sc_.tick_s);
  plant_wall_s_ += std::chrono::duration<double>(Clock::now() - t0).count();
  return st;
}

// --- The end: the final truth and status, on the link and in the log. ---
void PlantRun::End(const Outcome &out) {
  const int64_t utime_end = TickUtime(ticks_, sc_.tick_s);
  SendTruth(ticks_, utime_end);
  RunSummary counts;
  counts.missed_ticks = metrics_.missed_ticks();
  counts.rx_rejected = link_.rx_rejected();
  counts.rx_out_of_sequence = link_.rx_out_of_sequence();
  counts.rx_foreign_session = link_.rx_foreign_session();
  link_.SendStatus(EndStatus(out, ticks_, utime_end, counts), utime_end);
  rec_.Close();  // checked: a log that cannot be completed is a harness error
}

void PlantRun::Summarize(const Outcome &out, RunSummary *sum) const {
  sum->ticks = ticks_;
  sum->duration_s = double(ticks_) * sc_.tick_s;
  sum->status = out.ok() ? "finished" : "failed";
  sum->failure = FailureName(out.code);
  sum->reason = out.reason;
  sum->faults = faults_.counters();
  sum->rx_rejected = link_.rx_rejected();
  sum->rx_out_of_sequence = link_.rx_out_of_sequence();
  sum->rx_foreign_session = link_.rx_foreign_session();
  metrics_.WriteTo(plant_.truth(), sum);
  const auto stats = plant_.integrator_stats();
  sum->integrator_steps = stats.steps;
  sum->integrator_rhs_evals = stats.rhs_evals;
  sum->plant_wall_s = plant_wall_s_;
}

// A harness error: the run is over. The controller node is told (unrecorded: the log may be
// what failed), and the summary says why.
void EndOnHarnessError(LinkBus &bus, const PlantRun *run, double run_tick_s, std::int64_t session,
                       const std::string &what, RunSummary *sum) {
  Outcome out{UVMS_RUN_STATUS_T_HARNESS_ERROR, "harness error: " + what};
  if (run != nullptr) run->Summarize(out, sum);
  sum->status = "failed";
  sum->failure = "harness_error";
  sum->reason = what;
  uvms_run_status_t st = EndStatus(out, sum->ticks, TickUtime(sum->ticks, run_tick_s), *sum);
  st.state = UVMS_RUN_STATUS_T_FAILED;
  st.session = session;
  std::vector<uint8_t> buf(UVMS_MAX_MSG_BYTES);
  const int n = uvms_run_status_t_encode_sealed(&st, buf.data(), int(buf.size()));
  if (n > 0) bus.Publish(UVMS_CH_STATUS, buf.data(), n);
}

}  // namespace

RunSummary RunPlantNode(const Scenario &sc, lcm_t *lcm, const PlantNodeOptions &opt) {
  LcmBus bus(lcm);
  return RunPlantNode(sc, bus, opt);
}

RunSummary RunPlantNode(const Scenario &sc, LinkBus &bus, const PlantNodeOptions &options) {
  const auto wall0 = Clock::now();
  PlantNodeOptions opt = options;
  if (opt.session == UVMS_SESSION_NONE && uvms_session_draw(&opt.session) != 0) {
    RunSummary failed;
    failed.name = sc.name;
    failed.scenario = sc.source;
    failed.failure = "harness_error";
    failed.reason = std::string("cannot draw a session: ") + std::strerror(errno);
    return failed;
  }
  RunSummary sum;
  sum.scenario = sc.source;
  sum.name = sc.name;
  sum.drive = uvms_drive_str(sc.controller.drive);
  sum.ticks_planned = long(ScenarioTicks(sc));  // round up: the run covers duration_s
  char session_hex[UVMS_SESSION_TEXT_BYTES];
  uvms_session_format(opt.session, session_hex);
  sum.session = session_hex;
  std::unique_ptr<PlantRun> run;
  try {
    run = std::make_unique<PlantRun>(sc, bus, opt);
    Outcome out = run->Handshake(wall0 + Seconds(opt.startup_timeout_s), opt.startup_timeout_s,
                                 &sum.config_retries);
    if (out.ok()) out = run->Lockstep(sum.ticks_planned);
    if (out.ok()) out = run->Judge(sc.verdict);
    run->End(out);
    run->Summarize(out, &sum);
  } catch (const std::exception &e) {
    EndOnHarnessError(bus, run.get(), sc.tick_s, opt.session, e.what(), &sum);
  } catch (...) {
    EndOnHarnessError(bus, run.get(), sc.tick_s, opt.session, "unknown error", &sum);
  }
  run.reset();  // releases the subscriptions and closes the log
  sum.wall_time_s = std::chrono::duration<double>(Clock::now() - wall0).count();
  sum.real_time_factor = sum.wall_time_s > 0 ? sum.duration_s / sum.wall_time_s : 0.0;
  return sum;
}

}  // namespace uvms::sil
