// SPDX-License-Identifier: Apache-2.0
// lcm_bus.cpp: the link over an LCM instance (lcm_bus.hpp).
#include "run/lcm_bus.hpp"

#include <stdexcept>
#include <utility>

#include "link/lcm_wait.h"
#include "msg/codec.h"

namespace uvms::sil {

void LcmBus::SetReceiver(Receiver receiver, void *user) {
  if (receiver == nullptr) {
    actuators_.reset();
    telemetry_.reset();
    receiver_ = nullptr;
    user_ = nullptr;
    return;
  }
  if (receiver_ != nullptr) throw std::logic_error("LcmBus: a plant end is already receiving");
  // Both subscriptions first: if the second is refused, the first goes with its guard.
  auto actuators = std::make_unique<LcmSubscription>(lcm_, UVMS_CH_ACTUATORS, &OnMessageRaw, this);
  auto telemetry = std::make_unique<LcmSubscription>(lcm_, UVMS_CH_TELEMETRY, &OnMessageRaw, this);
  actuators_ = std::move(actuators);
  telemetry_ = std::move(telemetry);
  receiver_ = receiver;
  user_ = user;
}

void LcmBus::OnMessageRaw(const lcm_recv_buf_t *rb, const char *channel, void *self) noexcept {
  auto *bus = static_cast<LcmBus *>(self);
  if (bus->receiver_ != nullptr)
    bus->receiver_(bus->user_, channel, static_cast<const std::uint8_t *>(rb->data),
                   int(rb->data_size));
}

int LcmBus::Publish(const char *channel, const std::uint8_t *data, int n) {
  if (n < 0) return -1;
  return lcm_publish(publish_lcm_, channel, data, unsigned(n));
}

int LcmBus::Wait(int timeout_ms, int spin_us) { return uvms_lcm_wait(lcm_, timeout_ms, spin_us); }

}  // namespace uvms::sil
