// SPDX-License-Identifier: Apache-2.0
// recorder.cpp: the run's LCM event log (recorder.hpp).
#include "run/recorder.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include <unistd.h>

namespace uvms::sil {

Recorder::Recorder(const std::string &path) : path_(path) {
  if (path.empty()) return;
  errno = 0;
  log_ = lcm_eventlog_create(path.c_str(), "w");
  if (log_ == nullptr) Fail("creating");
}

Recorder::~Recorder() {
  if (log_ != nullptr) lcm_eventlog_destroy(log_);
}

void Recorder::Write(const char *channel, const std::uint8_t *data, int len, std::int64_t utime) {
  if (log_ == nullptr) return;
  lcm_eventlog_event_t ev{};
  ev.eventnum = next_++;
  ev.timestamp = utime;
  ev.channellen = int32_t(std::strlen(channel));
  ev.datalen = len;
  ev.channel = const_cast<char *>(channel);
  ev.data = const_cast<std::uint8_t *>(data);
  errno = 0;
  if (lcm_eventlog_write_event(log_, &ev) != 0) Fail("writing an event to");
}

void Recorder::Flush() {
  if (log_ == nullptr) return;
  errno = 0;
  // lcm_eventlog_t exposes its FILE (eventlog.h); lcm_eventlog_destroy would drop this error.
  if (std::fflush(log_->f) != 0 || std::ferror(log_->f)) Fail("flushing");
}

void Recorder::Close() {
  if (log_ == nullptr) return;
  Flush();
  errno = 0;
  const bool synced = ::fsync(fileno(log_->f)) == 0 || errno == EINVAL;
  const int sync_errno = errno;
  lcm_eventlog_destroy(log_);  // fclose: its buffer is already empty, so no write can fail here
  log_ = nullptr;
  errno = sync_errno;
  if (!synced) Fail("syncing");
}

void Recorder::Fail(const char *what) const {
  std::string msg = std::string(what) + " the run log " + path_ + " failed";
  if (errno != 0) msg += std::string(": ") + std::strerror(errno);
  throw std::runtime_error(msg);
}

}  // namespace uvms::sil
