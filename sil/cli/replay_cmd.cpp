// SPDX-License-Identifier: Apache-2.0
// replay_cmd.cpp: `uvms replay` (replay_cmd.hpp): a log's sensors through a fresh controller,
// compared bit for bit with the logged actuators; the log checked as a whole.
#include "cli/replay_cmd.hpp"

#include <arpa/inet.h>
#include <lcm/eventlog.h>
#include <lcm/lcm.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <stdexcept>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>
#include <memory>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "link/controller_node.h"
#include "msg/codec.h"
#include "msg/config_table.h"
#include "msg/session.h"
#include "run/run_options.hpp"
#include "scenario/config_schema.hpp"

namespace uvms::sil {
namespace fs = std::filesystem;
namespace {

const char *kReplayHelp =
    "usage: uvms replay DIR | LOG\n\n"
    "DIR: a run directory (its run.lcmlog); LOG: a run's log, as the run recorded it or as\n"
    "lcm-logger recorded it from the run's LCM URL (events on other channels, such as\n"
    "LCM_SELF_TEST, are counted and ignored; the run must publish truth_t:\n"
    "--set link.publish_truth=true).\n"
    "Feeds the logged configuration and sensor messages to a fresh controller (host build)\n"
    "and compares its actuator messages with the logged ones bit for bit.\n"
    "It also verifies the log as a whole: consecutive event numbers, every message's CRC and\n"
    "session on every channel (one session: no other run's message), one truth record per tick,\n"
    "the end record (the final run_status_t) last, and no truncated or trailing bytes; and that\n"
    "every tick whose sensors are logged has its actuators and telemetry logged too, but for the\n"
    "ticks the run missed (no more ticks without actuators than the end record's missed ticks:\n"
    "link faults, a late controller), and that every logged actuators message answers logged\n"
    "sensors (else a message the recorder missed). Otherwise the log is incomplete, and the\n"
    "ticks with their sensors but not their actuators or telemetry are named (the first 10,\n"
    "and the count).\n"
    "Exit status: 0 identical and complete, 1 a difference (the first tick and field are\n"
    "printed), 2 usage, 3 unreadable, truncated, corrupt or incomplete log, 4 an intact log of\n"
    "an interrupted run (SIGTERM/SIGINT: identical as far as it goes).\n";


// The whole-log checks of `uvms replay`, fed every event in order.
struct LogCheck {
  long next_eventnum{0};           // the recorder numbers events 0, 1, 2, ...
  long truth{0};                   // one truth_t per tick and one at the end
  int64_t last_truth_utime{-1};
  std::int64_t session{UVMS_SESSION_NONE};  // the run's: the first message's
  bool have_end{false};            // the end record: the final run_status_t (FINISHED/FAILED)
  uvms_run_status_t end{};
  long bad_sensors_crc{0};         // sensors_t failing its CRC (a recorded link fault, or damage)
  std::map<std::string, long> foreign;  // events on channels that are not the run's (a log
                                        // recorded by lcm-logger: LCM_SELF_TEST, others' traffic)
  std::string error;               // the first damage found ("" none)
  // Per tick k, what its window (from truth k to truth k+1) holds of tick k's own messages:
  // kTickSensors (intact), kTickActuators, kTickTelemetry. The plant records them in that window
  // or not at all (sil/run/lockstep_link.hpp).
  std::vector<std::uint8_t> tick_msgs;
};

constexpr std::uint8_t kTickSensors = 1, kTickActuators = 2, kTickTelemetry = 4;

// A message's CRC and decoding on its channel; "" when it checks out.
// The fingerprint this build's type of a channel has (0: not a typed channel).
std::uint64_t ChannelFingerprint(const std::string &ch) {
  if (ch == UVMS_CH_SENSORS) return std::uint64_t(__uvms_sensors_t_get_hash());
  if (ch == UVMS_CH_ACTUATORS) return std::uint64_t(__uvms_actuators_t_get_hash());
  if (ch == UVMS_CH_TELEMETRY) return std::uint64_t(__uvms_telemetry_t_get_hash());
  if (ch == UVMS_CH_TRUTH) return std::uint64_t(__uvms_truth_t_get_hash());
  if (ch == UVMS_CH_CONFIG) return std::uint64_t(__uvms_controller_config_t_get_hash());
  if (ch == UVMS_CH_STATUS) return std::uint64_t(__uvms_run_status_t_get_hash());
  if (ch == UVMS_CH_SCENE) return std::uint64_t(__uvms_scene_t_get_hash());
  return 0;
}

// An intact message (its CRC checks) whose fingerprint is not this build's type's: a message
// of another version of the type (lcmtypes/fingerprints.tsv), named with both fingerprints.
std::string CheckVersion(const std::string &ch, const uint8_t *d, int n) {
  const std::uint64_t want = ChannelFingerprint(ch);
  if (want == 0 || n < 8 || !uvms_crc_check(d, n)) return "";
  std::uint64_t got = 0;
  for (int i = 0; i < 8; ++i) got = (got << 8) | d[i];
  if (got == want) return "";
  char text[160];
  std::snprintf(text, sizeof text,
                "has fingerprint 0x%016llx, and this build's type has 0x%016llx: a message of "
                "another version of its type (lcmtypes/fingerprints.tsv)",
                static_cast<unsigned long long>(got), static_cast<unsigned long long>(want));
  return text;
}

// A retired enum choice held by a logged configuration: every ENUM row of the configuration
// table (sil/msg/config_table.h), its message field against UVMS_RETIRED_CHOICES; "" when none.
#define RETIRED_ROW_(map, shape, fw, lcm, key, ...) RETIRED_##map(lcm, key)
#define RETIRED_ENUM(lcm, key)                                                     \
  if (const RetiredChoice *r = RetiredChoiceValued(key, long(m.lcm)))              \
    return std::string("names ") + (key) + " " + RetiredText(*r) + ": re-run its scenario";
#define RETIRED_REAL(lcm, key)
#define RETIRED_LINK(lcm, key)
#define RETIRED_THR(lcm, key)
#define RETIRED_COUNT(lcm, key)
#define RETIRED_FLAG(lcm, key)
#define RETIRED_SWITCH(lcm, key)
#define RETIRED_U32(lcm, key)
#define RETIRED_NONE(lcm, key)
std::string RetiredChoiceIn(const uvms_controller_config_t &m) {
  UVMS_CONFIG_TABLE(RETIRED_ROW_)
  return "";
}
#undef RETIRED_ROW_
#undef RETIRED_ENUM
#undef RETIRED_REAL
#undef RETIRED_LINK
#undef RETIRED_THR
#undef RETIRED_COUNT
#undef RETIRED_FLAG
#undef RETIRED_SWITCH
#undef RETIRED_U32
#undef RETIRED_NONE

std::string CheckMessage(const std::string &ch, const uint8_t *d, int n, LogCheck &lc) {
  if (std::string v = CheckVersion(ch, d, n); !v.empty()) return v;
  if (ch == UVMS_CH_SENSORS) {  // a link fault records corrupted sensors: the comparison decides
    if (!uvms_crc_check(d, n)) ++lc.bad_sensors_crc;
    return "";
  }
  if (ch == UVMS_CH_TRUTH || ch == UVMS_CH_SCENE) return uvms_crc_check(d, n) ? "" : "fails its CRC";
  if (ch == UVMS_CH_CONFIG) {
    auto m = std::make_unique<uvms_controller_config_t>();
    if (uvms_controller_config_t_decode_checked(d, n, m.get()) < 0) return "does not decode or fails its CRC";
    return RetiredChoiceIn(*m);
  }
  if (ch == UVMS_CH_ACTUATORS) {
    uvms_actuators_t m;
    return uvms_actuators_t_decode_checked(d, n, &m) < 0 ? "does not decode or fails its CRC" : "";
  }
  if (ch == UVMS_CH_TELEMETRY) {
    uvms_telemetry_t m;
    return uvms_telemetry_t_decode_checked(d, n, &m) < 0 ? "does not decode or fails its CRC" : "";
  }
  if (ch == UVMS_CH_STATUS) {
    uvms_run_status_t m;
    if (uvms_run_status_t_decode_checked(d, n, &m) < 0) return "does not decode or fails its CRC";
    if (m.state == UVMS_RUN_STATUS_T_FINISHED || m.state == UVMS_RUN_STATUS_T_FAILED) {
      lc.have_end = true;
      lc.end = m;
    }
    return "";
  }
  return "is on an unknown channel";
}

// Every message of a run carries its session (sil/msg/session.h): another one in the log is a
// foreign message that should never have been recorded. "" when it checks out.
std::string CheckSession(const uint8_t *d, int n, LogCheck &lc) {
  if (!uvms_crc_check(d, n)) return "";  // a recorded, corrupted sensors message: not judged
  std::int64_t session = UVMS_SESSION_NONE;
  if (!uvms_msg_session(d, n, &session)) return "is too short to carry a session";
  if (lc.session == UVMS_SESSION_NONE) lc.session = session;
  if (session == UVMS_SESSION_NONE || session != lc.session)
    return "carries session " + SessionText(session) + ", the run's is " + SessionText(lc.session) +
           " (a message of another run)";
  return "";
}

// One event against the whole-log checks; false (lc.error set) on damage. An event on a channel
// that is not the run's (LogCheck::foreign) is counted, numbered and otherwise ignored.
bool CheckEvent(const lcm_eventlog_event_t &ev, LogCheck &lc) {
  const std::string ch(ev.channel, size_t(ev.channellen));
  std::string what;
  if (ChannelFingerprint(ch) == 0 && ev.eventnum == lc.next_eventnum) {
    ++lc.foreign[ch];
    ++lc.next_eventnum;
    return true;
  }
  if (lc.have_end) what = "follows the end record";
  else if (ev.eventnum != lc.next_eventnum)
    what = "has number " + std::to_string(ev.eventnum) + ", expected " + std::to_string(lc.next_eventnum) +
           " (events missing)";
  else what = CheckMessage(ch, static_cast<const uint8_t *>(ev.data), ev.datalen, lc);
  if (what.empty()) what = CheckSession(static_cast<const uint8_t *>(ev.data), ev.datalen, lc);
  if (what.empty() && ch == UVMS_CH_TRUTH) {
    if (ev.timestamp <= lc.last_truth_utime) what = "goes back in time (a tick repeated)";
    lc.last_truth_utime = ev.timestamp;
    ++lc.truth;
  }
  ++lc.next_eventnum;
  if (what.empty()) return true;
  lc.error = "event " + std::to_string(ev.eventnum) + " on " + ch + " " + what;
  return false;
}

// Notes an intact event's tick in LogCheck::tick_msgs when it is its window's own tick.
void NoteTickMessage(const std::string &ch, const uint8_t *d, int n, LogCheck &lc) {
  if (lc.truth == 0) return;  // before truth 0: the configuration and its answer
  const long window = lc.truth - 1;
  std::int64_t tick = -1;
  std::uint8_t bit = 0;
  if (ch == UVMS_CH_SENSORS) {
    uvms_sensors_t m;
    if (uvms_sensors_t_decode_checked(d, n, &m) < 0) return;  // corrupted: the controller drops it
    tick = m.tick;
    bit = kTickSensors;
  } else if (ch == UVMS_CH_ACTUATORS) {
    uvms_actuators_t m;
    if (uvms_actuators_t_decode_checked(d, n, &m) < 0) return;
    tick = m.tick;
    bit = kTickActuators;
  } else if (ch == UVMS_CH_TELEMETRY) {
    uvms_telemetry_t m;
    if (uvms_telemetry_t_decode_checked(d, n, &m) < 0) return;
    tick = m.tick;
    bit = kTickTelemetry;
  }
  if (bit == 0 || tick != window) return;  // another channel, or late / early: out of sequence
  if (lc.tick_msgs.size() <= size_t(window)) lc.tick_msgs.resize(size_t(window) + 1, 0);
  lc.tick_msgs[size_t(window)] |= bit;
}

// What a tick's window holds (LogCheck::tick_msgs), 0 past its end.
std::uint8_t TickMessages(const LogCheck &lc, long k) {
  return k >= 0 && size_t(k) < lc.tick_msgs.size() ? lc.tick_msgs[size_t(k)] : 0;
}

// The ticks of the run (0 .. end.tick - 1) whose actuators are not in their window: the ticks
// the plant took no actuators on, which it counts as missed (link faults, a late controller).
long UnansweredTicks(const LogCheck &lc) {
  long n = 0;
  for (long k = 0; k < lc.end.tick; ++k) n += (TickMessages(lc, k) & kTickActuators) == 0;
  return n;
}

// After a complete log: every tick whose sensors are logged has its actuators and telemetry
// logged too, except the ticks the run itself missed. More ticks without actuators than the end
// record's missed_ticks, or a tick with its actuators but without its telemetry, means the log
// lacks messages the run had: every tick with its sensors but not its actuators or telemetry is
// then named (the first few, and the count). "" when it checks out.
std::string CheckTicks(const LogCheck &lc) {
  const long unanswered = UnansweredTicks(lc);
  bool telemetry_lost = false;
  for (long k = 0; k < lc.end.tick; ++k) {
    const std::uint8_t b = TickMessages(lc, k);
    telemetry_lost = telemetry_lost || ((b & kTickActuators) && !(b & kTickTelemetry));
  }
  if (unanswered <= lc.end.missed_ticks && !telemetry_lost) return "";
  constexpr long kListed = 10;  // the first ticks named, then the count
  std::string list;
  long lacking = 0;
  for (long k = 0; k < long(lc.tick_msgs.size()); ++k) {
    const std::uint8_t b = TickMessages(lc, k);
    if (!(b & kTickSensors) || ((b & kTickActuators) && (b & kTickTelemetry))) continue;
    if (++lacking > kListed) continue;
    list += (lacking > 1 ? ", " : "") + std::to_string(k) + " (no " +
            (!(b & kTickActuators) ? ((b & kTickTelemetry) ? "actuators" : "actuators, no telemetry")
                                   : "telemetry") + ")";
  }
  if (lacking > kListed) list += ", ...";
  return "incomplete: " + std::to_string(lacking) + " tick" + (lacking == 1 ? "" : "s") +
         " with the sensors logged but not the actuators or telemetry: " + list + "; " +
         std::to_string(unanswered) + " ticks without actuators, the end record counts " +
         std::to_string(lc.end.missed_ticks) + " missed";
}

// After the last event: the file must have been read to its end (else it is truncated or has
// trailing bytes), end with the end record, and hold one truth per tick. "" when complete.
std::string CheckEnd(lcm_eventlog_t *log, const std::string &path, const LogCheck &lc) {
  struct stat st {};
  const long pos = std::ftell(log->f);
  if (stat(path.c_str(), &st) == 0 && pos >= 0 && pos != long(st.st_size))
    return "truncated or damaged: events end at byte " + std::to_string(pos) + " of " +
           std::to_string(long(st.st_size));
  if (!lc.have_end) return "incomplete: no end record (the final run_status_t): truncated or cut short";
  if (lc.truth == 0 && lc.end.tick > 0)
    return "incomplete: no truth records for " + std::to_string(lc.end.tick) +
           " ticks: a log recorded from the link (lcm-logger) holds truth_t only when the run "
           "publishes it: run with --set link.publish_truth=true (README \"Record and play back "
           "with LCM's tools\")";
  if (lc.truth != lc.end.tick + 1)
    return "incomplete: " + std::to_string(lc.truth) + " truth records for " + std::to_string(lc.end.tick) +
           " ticks (expected one per tick and one at the end)";
  return CheckTicks(lc);
}

// The end record's verdict in words: "finished" or "failed: <reason>".
std::string EndWords(const uvms_run_status_t &st) {
  if (st.state == UVMS_RUN_STATUS_T_FINISHED) return "finished";
  std::string reason(reinterpret_cast<const char *>(st.reason), strnlen(reinterpret_cast<const char *>(st.reason), sizeof st.reason));
  return std::string("failed (") + FailureName(st.code) + "): " + reason;
}

}  // namespace

int RunReplayCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err) {
  if (args.size() == 1 && (args[0] == "-h" || args[0] == "--help")) {
    out << kReplayHelp;
    return 0;
  }
  if (args.size() != 1) {
    err << "uvms replay: error: expected exactly one log file or run directory\n" << kReplayHelp;
    return 2;
  }
  std::error_code ec;
  const std::string path = fs::is_directory(args[0], ec) ? (fs::path(args[0]) / "run.lcmlog").string() : args[0];
  lcm_eventlog_t *log = lcm_eventlog_create(path.c_str(), "r");
  if (log == nullptr) {
    err << "uvms replay: error: cannot open " << path
        << (path != args[0] ? " (a run directory holds its log as run.lcmlog)" : "") << '\n';
    return 3;
  }
  auto node = std::make_unique<uvms_ctrl_node_t>();
  uvms_ctrl_node_init(node.get());
  auto out_msgs = std::make_unique<uvms_ctrl_node_out_t>();
  std::map<int64_t, uvms_actuators_t> produced;  // by tick
  std::set<int64_t> sensor_ticks;                 // ticks whose intact sensors the log holds
  long configs = 0, sensors = 0, compared = 0;
  int rc = 0;
  LogCheck lc;
  for (lcm_eventlog_event_t *ev; rc == 0 && (ev = lcm_eventlog_read_next_event(log)) != nullptr;
       lcm_eventlog_free_event(ev)) {
    if (!CheckEvent(*ev, lc)) {
      err << "uvms replay: error: corrupt log: " << lc.error << '\n';
      rc = 3;
      continue;
    }
    const std::string ch(ev->channel, size_t(ev->channellen));
    const auto *data = static_cast<const uint8_t *>(ev->data);
    NoteTickMessage(ch, data, ev->datalen, lc);
    if (ch == UVMS_CH_CONFIG) {
      ++configs;
      uvms_ctrl_node_on_config(node.get(), data, ev->datalen, out_msgs.get());
      produced.clear();
    } else if (ch == UVMS_CH_SENSORS) {
      ++sensors;
      if (uvms_sensors_t m; uvms_sensors_t_decode_checked(data, ev->datalen, &m) >= 0) sensor_ticks.insert(m.tick);
      uvms_ctrl_node_on_sensors(node.get(), data, ev->datalen, out_msgs.get());
      if (out_msgs->has_actuators) produced[out_msgs->actuators.tick] = out_msgs->actuators;
    } else if (ch == UVMS_CH_ACTUATORS) {
      uvms_actuators_t logged;
      (void)uvms_actuators_t_decode_checked(data, ev->datalen, &logged);  // checked above
      const auto it = produced.find(logged.tick);
      if (it == produced.end() && sensor_ticks.count(logged.tick) == 0) {
        // The answer to sensors the log lacks: a message the recorder missed (lcm-logger on a
        // busy link), not a difference of the controller.
        err << "uvms replay: error: " << path << ": incomplete: the actuators of tick "
            << logged.tick << " without its sensors (a message the recorder missed)\n";
        rc = 3;
        continue;
      }
      if (it == produced.end()) {
        out << "uvms replay: DIFFERENT at tick " << logged.tick
            << ": the log has actuators the fresh controller did not produce\n";
        rc = 1;
        continue;
      }
      int index = -1;
      const char *field = uvms_actuators_first_difference(&it->second, &logged, &index);
      if (field != nullptr) {
        out << "uvms replay: DIFFERENT at tick " << logged.tick << ", field " << field;
        if (index >= 0) out << "[" << index << "]";
        out << std::setprecision(17) << '\n';
        rc = 1;
        continue;
      }
      ++compared;  // kept: a link fault may have duplicated the logged message
    }
  }
  const std::string incomplete = rc == 0 ? CheckEnd(log, path, lc) : "";
  lcm_eventlog_destroy(log);
  if (rc != 0) return rc;
  if (!incomplete.empty()) {
    err << "uvms replay: error: " << path << ": " << incomplete << '\n';
    return 3;
  }
  if (configs == 0 || compared == 0) {
    err << "uvms replay: error: " << path << " has " << configs << " configuration and "
        << compared << " actuator messages: nothing to compare\n";
    return 3;
  }
  out << "uvms replay: identical: " << compared << " actuator messages bit for bit (" << sensors
      << " sensor messages replayed); log complete: " << lc.end.tick << " ticks, "
      << lc.next_eventnum << " events, every CRC and session checked";
  if (lc.bad_sensors_crc > 0) out << " (" << lc.bad_sensors_crc << " corrupted sensor messages: recorded link faults)";
  for (const auto &[ch, n] : lc.foreign) out << "; ignored " << n << " event" << (n == 1 ? "" : "s") << " on " << ch;
  if (const long unanswered = UnansweredTicks(lc); unanswered > 0)
    out << "; " << unanswered << " ticks without actuators, all missed by the run (end record: "
        << lc.end.missed_ticks << " missed)";
  out << "; the run " << EndWords(lc.end) << '\n';
  if (lc.end.code == UVMS_RUN_STATUS_T_INTERRUPTED) {
    err << "uvms replay: the run is incomplete: it was interrupted (the log is intact)\n";
    return 4;
  }
  return 0;
}

}  // namespace uvms::sil
