#pragma once
// The network beyond the emulated W5200 for ff-sim: a real UDP socket on
// 127.0.0.1. Datagrams to the device arrive from whoever sends them; the
// device's replies go back to that sender, as the W5200 would send them.
#include <cstdint>
#include <string>
#include <vector>

#include "teensy_model.hpp"

namespace ff::sim {

class SocketNetwork final : public teensy_model::UdpNetwork {
 public:
  ~SocketNetwork() override;
  bool open(uint16_t port, std::string& error);  // binds 127.0.0.1:port, non-blocking
  uint16_t port() const { return port_; }
  bool receive(std::vector<uint8_t>& payload, uint32_t& ip, uint16_t& port) override;
  bool deliver(uint32_t ip, uint16_t port, const std::vector<uint8_t>& payload) override;

 private:
  int fd_ = -1;
  uint16_t port_ = 0;
};

// Binds 127.0.0.1:port for datagrams; -1 and a message on failure.
int open_udp(uint16_t port, uint16_t& bound_port, std::string& error);

}  // namespace ff::sim
