// SPDX-License-Identifier: Apache-2.0
// link_bus.hpp: what the plant's end of the link (lockstep_link.hpp) needs of a transport.
//
// Two transports implement it:
//  - LcmBus (lcm_bus.hpp): an LCM instance. `uvms run --transport udpm` and the `uvms-plant`
//    process, with the controller in another process (uvms-controller, or the PIL bridge).
//  - InProcessBus (inprocess_bus.hpp): the controller node in the same process, the messages
//    passed through a queue in memory with the delivery rules of LCM's memq:// provider.
//    `uvms run --transport memq`, and so every campaign run by default.
// Both carry the same encoded, CRC-sealed bytes in the same order, so a run's log is the same
// byte for byte over either (tests/sil/test_sil_e2e.py, tests/sil/test_plant_node.cpp).
#pragma once

#include <cstdint>

namespace uvms::sil {

class LinkBus {
 public:
  /// The plant's end of the link: receives what the controller publishes (actuators and
  /// telemetry). Called from inside Wait; it must not throw (lcm_guard.hpp's HandlerErrors).
  using Receiver = void (*)(void *user, const char *channel, const std::uint8_t *data,
                            int n) noexcept;

  virtual ~LinkBus() = default;
  /// Deliver the actuators and telemetry channels to receiver(user, ...) from now on; a null
  /// receiver ends the delivery (the plant's end is gone). One plant end at a time: setting a
  /// receiver while another is set throws std::logic_error; so does a transport that refuses
  /// (std::runtime_error), with nothing changed.
  virtual void SetReceiver(Receiver receiver, void *user) = 0;
  /// Publish one message (n ≥ 0 bytes). Returns 0, or nonzero when the transport failed to send
  /// it.
  virtual int Publish(const char *channel, const std::uint8_t *data, int n) = 0;
  /// Handle at most one message, waiting up to timeout_ms [ms] for it (busy-polling spin_us
  /// [µs] first where the transport waits on a descriptor: sil/link/lcm_wait.h). Returns 1 when
  /// one was handled, 0 when none came, -1 on an error of the transport.
  virtual int Wait(int timeout_ms, int spin_us) = 0;
  /// Whether a message can still arrive: always, for a transport another process publishes
  /// on; for the in-process queue, only while it holds one (nothing else can fill it).
  virtual bool MayReceive() const = 0;
};

}  // namespace uvms::sil
