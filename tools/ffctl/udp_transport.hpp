#pragma once
// The protocol over UDP (docs/protocol.md: one frame per datagram; the device
// replies to the sender's address and port): the WIZ820io on the lab's
// Ethernet, or ff-sim on this computer. POSIX sockets.
#include <string>

#include "transport.hpp"

namespace ff::ffctl {

constexpr uint16_t kDefaultUdpPort = 8888;

// "HOST" or "HOST:PORT" (port 1..65535; default kDefaultUdpPort), IPv4 only:
// an IPv6 address is refused. false with a readable `error`.
bool parse_udp_address(const std::string& text, std::string& host, uint16_t& port, std::string& error);

class UdpTransport final : public Transport {
 public:
  // Resolves `host` (IPv4) and connects a datagram socket to it; throws
  // std::runtime_error with a readable message (unknown host, no socket).
  UdpTransport(const std::string& host, uint16_t port);
  ~UdpTransport() override;
  UdpTransport(const UdpTransport&) = delete;
  UdpTransport& operator=(const UdpTransport&) = delete;
  bool send(const uint8_t* frame, size_t size) override;
  ReceiveResult receive(std::vector<uint8_t>& frame, int timeout_ms) override;

 private:
  int socket_ = -1;
};

}  // namespace ff::ffctl
