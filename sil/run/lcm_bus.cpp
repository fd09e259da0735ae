// SPDX-License-Identifier: Apache-2.0
// lcm_bus.cpp: the link over an LCM instance (lcm_bus.hpp).
#include "run/lcm_bus.hpp"

#include "link/lcm_wait.h"
#include "msg/codec.h"

namespace uvms::sil {

void LcmBus::SetReceiver(Receiver receiver, void *user) {
  actuators_.reset();
  telemetry_.reset();
  receiver_ = receiver;
  user_ = user;
  if (receiver == nullptr) return;
  actuators_ = std::make_unique<LcmSubscription>(lcm_, UVMS_CH_ACTUATORS, &OnMessageRaw, this);
  telemetry_ = std::make_unique<LcmSubscription>(lcm_, UVMS_CH_TELEMETRY, &OnMessageRaw, this);
}

void LcmBus::OnMessageRaw(const lcm_recv_buf_t *rb, const char *channel, void *self) noexcept {
  auto *bus = static_cast<LcmBus *>(self);
  if (bus->receiver_ != nullptr)
    bus->receiver_(bus->user_, channel, static_cast<const std::uint8_t *>(rb->data),
                   int(rb->data_size));
}

int LcmBus::Publish(const char *channel, const std::uint8_t *data, int n) {
  return lcm_publish(lcm_, channel, data, unsigned(n));
}

int LcmBus::Wait(int timeout_ms, int spin_us) { return uvms_lcm_wait(lcm_, timeout_ms, spin_us); }

}  // namespace uvms::sil
