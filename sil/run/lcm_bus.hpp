// SPDX-License-Identifier: Apache-2.0
// lcm_bus.hpp: the link over an LCM instance (link_bus.hpp): lcm_publish, lcm_subscribe and the
// bounded wait of sil/link/lcm_wait.h. The subscriptions are guards (lcm_guard.hpp): released
// when the receiver is cleared or the bus goes, on every path.
#pragma once

#include <lcm/lcm.h>

#include <memory>

#include "link/lcm_guard.hpp"
#include "run/link_bus.hpp"

namespace uvms::sil {

class LcmBus final : public LinkBus {
 public:
  /// Works on lcm (not owned: it outlives the bus).
  explicit LcmBus(lcm_t *lcm) : lcm_(lcm), publish_lcm_(lcm) {}
  /// Listens on lcm and publishes on publish_lcm (neither owned): a link whose two directions
  /// have a URL each, so that this process does not receive its own datagrams. LCM opens no
  /// receive socket on an instance nobody subscribes to.
  LcmBus(lcm_t *lcm, lcm_t *publish_lcm) : lcm_(lcm), publish_lcm_(publish_lcm) {}
  LcmBus(const LcmBus &) = delete;
  LcmBus &operator=(const LcmBus &) = delete;

  void SetReceiver(Receiver receiver, void *user) override;
  int Publish(const char *channel, const std::uint8_t *data, int n) override;
  int Wait(int timeout_ms, int spin_us) override;
  bool MayReceive() const override { return true; }

 private:
  static void OnMessageRaw(const lcm_recv_buf_t *rb, const char *channel, void *self) noexcept;

  lcm_t *lcm_, *publish_lcm_;
  Receiver receiver_{nullptr};
  void *user_{nullptr};
  std::unique_ptr<LcmSubscription> actuators_, telemetry_;
};

}  // namespace uvms::sil
