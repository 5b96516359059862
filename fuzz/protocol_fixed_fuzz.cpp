// libFuzzer target: the protocol decoder past its door. The input's header
// and payload are kept, but magic, version, length and CRC are made right
// before decoding, so mutations reach the payload parsers instead of dying at
// the CRC check (the plain target, protocol_fuzz.cpp, tests the door itself).
// Same checks as the plain target.
#include <algorithm>
#include <cstdint>
#include <cstring>

#include "frictionfield/protocol/codec.hpp"

namespace ff::fuzz {
int protocol_one_input(const uint8_t* data, size_t size);
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace ff::protocol;
  if (size < kHeaderBytes) return 0;
  static uint8_t frame[kMaxFrame];
  const size_t payload = std::min(size - kHeaderBytes, kMaxPayload);
  std::memcpy(frame, data, kHeaderBytes + payload);
  // The header as codec.hpp lays it out: magic, version, type, sequence, u16 length.
  frame[0] = 'F';
  frame[1] = 'F';
  frame[2] = kVersion;
  frame[5] = static_cast<uint8_t>(payload);
  frame[6] = static_cast<uint8_t>(payload >> 8);
  const size_t body = kHeaderBytes + payload;
  const uint16_t crc = crc16_ccitt(frame + 2, body - 2);
  frame[body] = static_cast<uint8_t>(crc);
  frame[body + 1] = static_cast<uint8_t>(crc >> 8);
  return ff::fuzz::protocol_one_input(frame, body + kCrcBytes);
}
