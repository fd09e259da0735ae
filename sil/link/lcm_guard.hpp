// SPDX-License-Identifier: Apache-2.0
// lcm_guard.hpp: the C++ side of the LCM C API boundary, as Drake's DrakeLcm does it.
//
//  - LcmSubscription: one lcm_subscribe, released by lcm_unsubscribe when the guard goes, on every
//    path (normal end, early return, exception).
//  - HandlerErrors: no C++ exception may unwind through LCM's C frames (lcm_handle calls the
//    handlers). A handler runs its body under Guard(), which keeps what it throws; the code that
//    called lcm_handle / lcm_handle_timeout / uvms_lcm_wait calls Rethrow() after it returns,
//    and the error continues from there as an ordinary exception.
//
// A handler given to LcmSubscription is declared noexcept and does all its work inside
// HandlerErrors::Guard: if anything escaped it anyway, std::terminate would stop the process at
// the handler instead of unwinding LCM.
#pragma once

#include <lcm/lcm.h>

#include <atomic>
#include <exception>
#include <stdexcept>
#include <string>
#include <utility>

namespace uvms::sil {

class LcmSubscription {
 public:
  /// Subscribes handler(user) to channel on lcm. Throws std::runtime_error if LCM refuses.
  LcmSubscription(lcm_t *lcm, const char *channel, lcm_msg_handler_t handler, void *user)
      : lcm_(lcm), sub_(lcm_subscribe(lcm, channel, handler, user)) {
    if (sub_ == nullptr) throw std::runtime_error(std::string("LCM subscription to ") + channel + " failed");
    ++live_;
  }
  ~LcmSubscription() {
    lcm_unsubscribe(lcm_, sub_);
    --live_;
  }
  LcmSubscription(const LcmSubscription &) = delete;
  LcmSubscription &operator=(const LcmSubscription &) = delete;

  /// Subscriptions held by guards in this process right now (a test seam: 0 after a node is
  /// gone, whatever ended it).
  static long live() { return live_.load(); }

 private:
  lcm_t *lcm_;
  lcm_subscription_t *sub_;
  static inline std::atomic<long> live_{0};
};

class HandlerErrors {
 public:
  /// Run one handler's body; keep the first exception it throws. While an error is kept, later
  /// bodies are skipped (the caller is about to stop on it).
  template <typename Body>
  void Guard(Body &&body) noexcept {
    if (error_) return;
    try {
      std::forward<Body>(body)();
    } catch (...) {
      error_ = std::current_exception();
    }
  }
  /// After the handle call has returned: throw the kept error, if any (and forget it).
  void Rethrow() {
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
  }

 private:
  std::exception_ptr error_;
};

}  // namespace uvms::sil
