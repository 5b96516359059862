#pragma once
// Ethernet library (EthernetUdp.h): one UDP socket.
#include <cstddef>
#include <cstdint>

#include "IPAddress.h"

class EthernetUDP {
 public:
  uint8_t begin(uint16_t port);
  int parsePacket();
  int available();
  int read();
  int read(uint8_t* buffer, size_t len);
  IPAddress remoteIP();
  uint16_t remotePort();
  int beginPacket(IPAddress ip, uint16_t port);
  size_t write(const uint8_t* buffer, size_t size);
  int endPacket();
};
