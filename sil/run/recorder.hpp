// SPDX-License-Identifier: Apache-2.0
// recorder.hpp: the run's LCM event log (lcm_eventlog), written by the plant node.
//
// Every message the plant publishes or accepts is written with the simulated time as its event
// timestamp and consecutive event numbers, so a run's log is a pure function of its scenario
// (no wall-clock anywhere in it). Failures throw std::runtime_error naming the log; the plant
// node never lets one cross an LCM handler (sil/link/lcm_guard.hpp) and ends the run on it.
#pragma once

#include <lcm/eventlog.h>

#include <cstdint>
#include <string>

namespace uvms::sil {

class Recorder {
 public:
  /// Creates (truncates) the log at path; an empty path records nothing.
  explicit Recorder(const std::string &path);
  ~Recorder();
  Recorder(const Recorder &) = delete;
  Recorder &operator=(const Recorder &) = delete;

  /// Whether events are written (a log is open): a message only the log would take need not be
  /// encoded otherwise.
  bool recording() const { return log_ != nullptr; }
  /// Append one event.
  void Write(const char *channel, const std::uint8_t *data, int len, std::int64_t utime);
  /// Flush what is buffered to the file (the last events): a failure here is a failed log too.
  void Flush();
  /// Flush, fsync and close the log (checked: throws on failure); later writes record nothing.
  /// The destructor closes an unclosed log without checking (an error path is already failing).
  void Close();

 private:
  [[noreturn]] void Fail(const char *what) const;

  std::string path_;
  lcm_eventlog_t *log_{nullptr};
  std::int64_t next_{0};
};

}  // namespace uvms::sil
