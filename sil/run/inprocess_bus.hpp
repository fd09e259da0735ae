// SPDX-License-Identifier: Apache-2.0
// inprocess_bus.hpp: the link with the controller node in the same process (link_bus.hpp), for
// `uvms run --transport memq` and the campaigns.
//
// The messages are the same encoded, CRC-sealed bytes as over LCM, passed through a FIFO queue
// in memory with the delivery rules of LCM's memq:// provider (lcm_memq.c), so a run's log is
// the same byte for byte as over LCM:
//  - a message published on a channel nobody takes is dropped at once (the controller node
//    takes config, sensors and status; the plant's receiver actuators and telemetry; truth and
//    scene have no taker in the process);
//  - Wait takes the oldest message off the queue and hands it to its taker; what the taker
//    publishes meanwhile (the controller's actuators and telemetry) is queued behind.
// What it leaves out of LCM's memq: the notification pipe (three system calls per message:
// write, select, read), three heap allocations per message and the locks a second thread
// would need. Waiting never blocks: with the queue empty nothing can arrive (MayReceive), and the
// plant's end stops waiting at once instead of sleeping out its timeout.
// Single-threaded, like the rest of a run. Steady state allocates nothing: the queue's slots
// and their buffers are reused.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "link/controller_node.h"
#include "run/link_bus.hpp"

namespace uvms::sil {

class InProcessBus final : public LinkBus {
 public:
  /// The controller node that takes config, sensors and status (not owned; it outlives the bus).
  explicit InProcessBus(uvms_ctrl_node_t &node) : node_(node) {}
  InProcessBus(const InProcessBus &) = delete;
  InProcessBus &operator=(const InProcessBus &) = delete;

  void SetReceiver(Receiver receiver, void *user) override;
  /// Queue the message for its taker, or drop it if the channel has none: 0; n < 0: -1.
  int Publish(const char *channel, const std::uint8_t *data, int n) override;
  /// Hand the oldest queued message to its taker: 1; the queue empty: 0 at once (never waits);
  /// called by a taker while it handles a message: -1 (one message at a time).
  int Wait(int timeout_ms, int spin_us) override;
  bool MayReceive() const override { return count_ > 0; }
  /// Handle every queued message, and what they publish in turn, until the queue is empty.
  void Drain();
  /// Messages queued now.
  std::size_t queued() const { return count_; }

 private:
  enum class Taker { kNone, kController, kPlant };
  struct Slot {
    const char *channel{nullptr};  // one of the UVMS_CH_* literals
    Taker taker{Taker::kNone};
    std::vector<std::uint8_t> data;  // its capacity is kept from message to message
  };
  /// The channel's literal and its taker (kNone: dropped).
  Taker TakerOf(const char *channel, const char **literal) const;
  /// The controller node's publish function (uvms_ctrl_node_publish_fn): queues, never throws
  /// into the node's C code (returns -1 if the queue could not grow).
  static int PublishFromNode(void *self, const char *channel, const std::uint8_t *data,
                             int n) noexcept;
  void Grow();

  uvms_ctrl_node_t &node_;
  Receiver receiver_{nullptr};
  void *user_{nullptr};
  std::vector<Slot> ring_;      // a ring: count_ messages from head_ on
  std::size_t head_{0}, count_{0};
  std::vector<std::uint8_t> current_;  // the message being handled (its slot is free again)
  bool dispatching_{false};            // inside a taker
};

}  // namespace uvms::sil
