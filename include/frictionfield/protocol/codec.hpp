#pragma once
// Frames (docs/protocol.md): little-endian, explicit field by field.
//
//   0  'F' 'F'          magic
//   2  version          kVersion
//   3  type             MessageType
//   4  sequence
//   5  length (u16)     payload bytes
//   7  payload
//   7+length  CRC-16/CCITT-FALSE (u16) over bytes 2 .. 7+length-1
#include <cstddef>
#include <cstdint>

#include "frictionfield/protocol/messages.hpp"

namespace ff::protocol {

constexpr size_t kHeaderBytes = 7;
constexpr size_t kCrcBytes = 2;
constexpr size_t kMaxPayload = 1400;  // fits one Ethernet UDP datagram
constexpr size_t kMaxFrame = kHeaderBytes + kMaxPayload + kCrcBytes;

enum class DecodeStatus : uint8_t { Ok, TooShort, BadMagic, BadVersion, BadLength, BadCrc, UnknownType, Malformed };
const char* to_string(DecodeStatus s);
const char* to_string(ErrorCode c);
ErrorCode error_code_for(DecodeStatus s);

// Writes one frame; returns its size, or 0 if `capacity` is too small or a
// number is not finite (a frame that encodes always decodes).
size_t encode(const Message& m, uint8_t* out, size_t capacity);
// Reads one frame of exactly `size` bytes into `out`, in place (no second
// Message on the stack). A bad header (TooShort .. UnknownType) leaves `out`
// untouched; a Malformed payload leaves it a default Message.
DecodeStatus decode(const uint8_t* in, size_t size, Message& out);

uint16_t crc16_ccitt(const uint8_t* data, size_t size, uint16_t crc = 0xFFFF);

}  // namespace ff::protocol
