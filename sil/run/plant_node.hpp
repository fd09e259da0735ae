// SPDX-License-Identifier: Apache-2.0
// plant_node.hpp: the plant side of the SIL link (C++): the lockstep master, the recorder of
// the run's LCM log and the source of its metrics (SPEC §10) and summary.
//
// Per tick k: publish sensors(k); record truth(k) and measure tick k-1 while the controller
// computes (truth published on the link goes out before the sensors); wait (wall-clock timeout)
// for the actuators of tick k; integrate to k+1 with the command held; collect the telemetry of
// tick k.
// A message that fails to decode or its CRC is dropped and counted; one of the wrong tick is
// dropped and counted (and still recorded: it is real traffic); a tick whose actuators do not
// arrive in time is a missed tick: the last command is held, and more than `max_missed` in a
// row end the run (CONTROLLER_SILENT). Every message the plant publishes or accepts goes to the
// log with the simulated time as its event timestamp, so a run's log is a pure function of its
// scenario (no wall-clock anywhere in it).
//
// The parts, one module each, in the order a tick's data flows through them:
//   plant_messages.hpp  truth -> sensors_t / truth_t
//   faults.hpp          sensor noise, health mask, link faults, thruster faults
//   lockstep_link.hpp   publish, wait (busy-poll, sil/link/lcm_wait.h), handle
//   link_bus.hpp        the transport under it: LCM (lcm_bus.hpp) or in-process (inprocess_bus.hpp)
//   recorder.hpp        the run's LCM event log
//   run_metrics.hpp     the metrics accumulator
//   summary_writer.hpp  RunSummary and summary.json
#pragma once

#include <lcm/lcm.h>

#include <cstdint>
#include <string>

#include "run/link_bus.hpp"
#include "run/run_metrics.hpp"
#include "run/summary_writer.hpp"
#include "scenario/scenario.hpp"

namespace uvms::sil {

/// Options of the plant side that are not part of the scenario.
struct PlantNodeOptions {
  std::string log_path;        ///< the run's LCM log (empty: no log)
  double startup_timeout_s{10.0};  ///< wait for the controller's configuration answer [s]
  int spin_us{0};  ///< busy-poll before blocking on the link [µs] (sil/link/lcm_wait.h; udpm only)
  /// The run's session (sil/msg/session.h), stamped on every message; UVMS_SESSION_NONE (0): drawn
  /// at random when the run starts.
  std::int64_t session{0};
};

/// Install handlers for SIGTERM and SIGINT (also what a parent's death sends, PR_SET_PDEATHSIG)
/// that ask a running RunPlantNode to stop: it ends the run at the next tick with code
/// INTERRUPTED (failure "interrupted"), logs the end record, closes the log and returns its
/// summary. A second signal of either kind terminates the process at once (default action).
void InstallPlantStopHandlers();

/// The signal that asked the run to stop (0: none). For tests: RequestPlantStop(SIGTERM).
int PlantStopSignal();
void RequestPlantStop(int signal_number);

/// Run the plant side of a scenario on the transport `bus` (link_bus.hpp): LCM for a controller
/// in another process, the in-process queue for the controller node of this one (memq mode).
///
/// Never throws for run-time failures: every one ends in the summary's status "failed" with
/// `failure` and `reason`. A failure of the run (the controller silent, a contact, ...) has its
/// run_status_t code's name. A failure of the harness itself (the log cannot be created,
/// written or flushed, an LCM subscription refused, ...) is `failure` "harness_error" with the
/// error's text as `reason`, the counters and metrics reached so far, and an unrecorded
/// run_status_t FAILED (code HARNESS_ERROR) on the link so that the controller node stops.
/// A run that completed its ticks is judged (scenario.verdict): too many controller error ticks, a
/// non-finite metric, commanded thrust not produced for too long or a divergence makes it FAILED
/// (CONTROLLER_ERRORS, NON_FINITE, THRUST_LOST, DIVERGED),
/// and that end status is the log's end record. Every log that could be written ends with the
/// final run_status_t (FINISHED or FAILED): `uvms replay` checks it. Errors raised inside LCM
/// handlers never cross the transport's frames (LCM's C frames: sil/link/lcm_guard.hpp), and the
/// node stops receiving (its subscriptions are released) on every path before it returns.
RunSummary RunPlantNode(const Scenario &scenario, LinkBus &bus, const PlantNodeOptions &opt);
/// The same on the LCM instance `lcm` (an LcmBus of its own).
RunSummary RunPlantNode(const Scenario &scenario, lcm_t *lcm, const PlantNodeOptions &opt);

}  // namespace uvms::sil
