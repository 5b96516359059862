#pragma once
// Ethernet library (Ethernet.h): the W5200 set-up calls the binding makes.
#include <cstdint>

#include "IPAddress.h"

class EthernetClass {
 public:
  static void init(uint8_t sspin);
  void begin(uint8_t* mac, IPAddress ip);
  void setRetransmissionTimeout(uint16_t milliseconds);
  void setRetransmissionCount(uint8_t num);
};
extern EthernetClass Ethernet;
