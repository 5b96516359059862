#pragma once
// Decodes one zForce I2C frame (0xEE, length, BER payload) into a message.
// No heap; every loop is bounded by the frame length; a frame is either
// decoded whole or rejected whole with the first reason found.
#include <cstddef>
#include <cstdint>

#include "frictionfield/drivers/zforce_protocol.hpp"

namespace ff::zforce {

enum class FrameError : uint8_t {
  None,
  WrongHeader,      // first byte is not 0xEE
  LengthOverMax,    // declared payload longer than kMaxFramePayload
  Truncated,        // the bytes end before the frame or an item inside it does
  MalformedTag,     // bad identifier or length octets, trailing bytes, wrong structure
  UnknownTag,       // an identifier the protocol does not define where it appears
  ImpossibleValue,  // well-formed but impossible: event > 4, coordinate beyond the
                    // resolution, touch size not matching the format, duplicate id
};
const char* to_string(FrameError e);

constexpr uint8_t kMaxTouches = 10;  // the most the sensor reports

struct Touch {
  uint8_t id = 0;
  TouchEvent event = TouchEvent::Invalid;
  uint32_t x = 0;  // sensor units, 0..resolution
  uint32_t y = 0;
};

enum class MessageKind : uint8_t { Touches, BootComplete, Response, OtherNotification };

struct Message {
  MessageKind kind = MessageKind::OtherNotification;
  bool has_address = false;
  uint8_t device_type = 0;
  uint8_t device_index = 0;
  uint8_t touch_count = 0;
  Touch touches[kMaxTouches];
  bool has_timestamp = false;
  uint32_t timestamp = 0;     // sensor clock, 32768 Hz
  // Where the timestamp stood: beside the touch sequence (A0 ... 58 ...) or
  // inside it (A0 { 42 ... 58 ... }). Neonode's own library reads touches by
  // fixed offsets and takes both; no capture of the thesis' module says which.
  bool timestamp_inside = false;
  uint16_t response_to = 0;   // Response: the command answered (kEnable, kTouchFormat, ...)
  bool has_format = false;    // Response to kTouchFormat carried a usable descriptor
  TouchFormat format;
};

class FrameDecoder {
 public:
  FrameDecoder() = default;

  // Ignored (false) unless usable().
  bool set_format(const TouchFormat& f) {
    if (!f.usable()) return false;
    format_ = f;
    return true;
  }
  const TouchFormat& format() const { return format_; }
  // Coordinates above these are impossible (the resolution the sensor was set to).
  void set_limits(uint32_t max_x, uint32_t max_y) {
    max_x_ = max_x;
    max_y_ = max_y;
  }

  // A whole frame: exactly 2 + frame[1] bytes.
  FrameError decode(const uint8_t* frame, size_t n, Message& out) const;
  // The payload after the two header bytes.
  FrameError decode_payload(const uint8_t* payload, size_t n, Message& out) const;

 private:
  FrameError decode_response(const uint8_t* p, size_t n, Message& out) const;
  FrameError decode_notification(const uint8_t* p, size_t n, Message& out) const;
  FrameError decode_touch(const uint8_t* p, size_t n, Touch& out) const;

  TouchFormat format_ = TouchFormat::assumed_default();
  uint32_t max_x_ = 0xFFFFFF;
  uint32_t max_y_ = 0xFFFFFF;
};

// Parses a TouchDescriptor BIT STRING's content (unused-bits octet first).
FrameError parse_touch_descriptor(const uint8_t* content, size_t n, TouchFormat& out);

}  // namespace ff::zforce
