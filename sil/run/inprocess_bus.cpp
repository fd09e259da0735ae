// SPDX-License-Identifier: Apache-2.0
// inprocess_bus.cpp: the link with the controller node in the same process (inprocess_bus.hpp).
#include "run/inprocess_bus.hpp"

#include <cstring>
#include <stdexcept>
#include <utility>

#include "msg/codec.h"

namespace uvms::sil {

void InProcessBus::SetReceiver(Receiver receiver, void *user) {
  if (receiver != nullptr && receiver_ != nullptr)
    throw std::logic_error("InProcessBus: a plant end is already receiving");
  receiver_ = receiver;
  user_ = user;
}

InProcessBus::Taker InProcessBus::TakerOf(const char *channel, const char **literal) const {
  static const char *const kController[] = {UVMS_CH_CONFIG, UVMS_CH_SENSORS, UVMS_CH_STATUS};
  static const char *const kPlant[] = {UVMS_CH_ACTUATORS, UVMS_CH_TELEMETRY};
  for (const char *c : kController)
    if (std::strcmp(channel, c) == 0) return *literal = c, Taker::kController;
  for (const char *c : kPlant)
    if (std::strcmp(channel, c) == 0)
      return *literal = c, receiver_ != nullptr ? Taker::kPlant : Taker::kNone;
  return Taker::kNone;
}

void InProcessBus::Grow() {
  // Unroll the ring into a larger one: the queued messages keep their order from index 0.
  std::vector<Slot> bigger(ring_.empty() ? 4 : 2 * ring_.size());
  for (std::size_t i = 0; i < count_; ++i) bigger[i] = std::move(ring_[(head_ + i) % ring_.size()]);
  ring_.swap(bigger);
  head_ = 0;
}

int InProcessBus::Publish(const char *channel, const std::uint8_t *data, int n) {
  const char *literal = nullptr;
  const Taker taker = TakerOf(channel, &literal);
  if (n < 0) return -1;
  if (taker == Taker::kNone) return 0;  // nobody takes it: dropped, as memq does
  if (count_ == ring_.size()) Grow();
  Slot &s = ring_[(head_ + count_) % ring_.size()];
  s.channel = literal;
  s.taker = taker;
  s.data.assign(data, data + n);
  ++count_;
  return 0;
}

int InProcessBus::PublishFromNode(void *self, const char *channel, const std::uint8_t *data,
                                  int n) noexcept {
  try {
    return static_cast<InProcessBus *>(self)->Publish(channel, data, n);
  } catch (...) {  // no exception crosses the node's C frames (the queue could not grow)
    return -1;     // the node warns that the answer was not published
  }
}

int InProcessBus::Wait(int /*timeout_ms*/, int /*spin_us*/) {
  if (dispatching_) return -1;  // called from inside a taker: one message at a time
  if (count_ == 0) return 0;
  Slot &s = ring_[head_];
  const char *channel = s.channel;
  const Taker taker = s.taker;
  current_.swap(s.data);  // the slot is free now: what the taker publishes may reuse it
  head_ = (head_ + 1) % ring_.size();
  --count_;
  const int n = int(current_.size());
  dispatching_ = true;
  if (taker == Taker::kController) {
    (void)uvms_ctrl_node_handle(&node_, channel, current_.data(), n, &PublishFromNode, this);
  } else if (receiver_ != nullptr) {  // the plant's end may have gone since it was queued
    receiver_(user_, channel, current_.data(), n);
  }
  dispatching_ = false;
  return 1;
}

void InProcessBus::Drain() {
  while (Wait(0, 0) > 0) {
  }
}

}  // namespace uvms::sil
