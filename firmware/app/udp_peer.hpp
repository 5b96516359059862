#pragma once
// Who the device answers over UDP: the last address that sent a datagram.
// A send that timed out (no ARP answer) makes the device quiet towards that
// address until it speaks again, so that an unplugged host costs one bounded
// wait, not one every 30 ms (the force messages).
#include <cstdint>

#include "firmware/app/board.hpp"

namespace ff::firmware {

class UdpPeer {
 public:
  void heard_from(const UdpEndpoint& from) {
    peer_ = from;
    reachable_ = from.port != 0;
  }
  bool reachable() const { return reachable_; }
  const UdpEndpoint& endpoint() const { return peer_; }
  void send_failed() {
    reachable_ = false;
    ++send_failures_;
  }
  uint32_t send_failures() const { return send_failures_; }

 private:
  UdpEndpoint peer_;
  bool reachable_ = false;
  uint32_t send_failures_ = 0;
};

}  // namespace ff::firmware
