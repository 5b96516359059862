#pragma once
// The Neonode zForce touch sensor protocol over I2C, as Neonode's "zForce
// Message Specification" (PDU definition v1.9, protocol 1.x) documents it and
// their Arduino library (neonode-inc/zforce-arduino) implements it.
//
// I2C target address 0x50. The sensor raises its data-ready (DR) line while
// it has a message for the host; the host reads two bytes, the frame header
// 0xEE and the payload length, then that many payload bytes, and DR falls
// when the message has been read. The host writes requests the same way
// (0xEE, length, payload) while DR is low, and every request is answered by
// a response message. The payload is one BER-encoded ProtocolMessage:
//   request      [PRIVATE 14] 0xEE   host -> sensor
//   response     [PRIVATE 15] 0xEF   sensor -> host
//   notification [PRIVATE 16] 0xF0   sensor -> host, unsolicited
// each beginning with the device address 0x40 0x02 <type> <index> (type 0
// platform, 2 zForce Air). A touch notification carries one TouchNotification
// [APPLICATION 2] octet string per finger (0x42), inside a SEQUENCE OF
// [0] (0xA0) when several may be reported, then optionally a Timestamp
// [APPLICATION 24] (0x58, 32768 Hz). The bytes of each TouchNotification are
// given by the TouchDescriptor bit string that the touchFormat request
// returns: id, event (0 down, 1 move, 2 up, 3 invalid, 4 ghost), x and y in
// 1-3 big-endian bytes, sizes, confidence.
#include <cstddef>
#include <cstdint>

namespace ff::zforce {

constexpr uint8_t kI2cAddress = 0x50;
constexpr uint8_t kFrameStart = 0xEE;
// Longest payload this driver accepts: a touch notification with the ten
// touches the sensor can report, 9-byte format, timestamp and latency, fits
// in 127 bytes. Longer messages (device information strings) are never
// requested; they are counted and skipped.
constexpr size_t kMaxFramePayload = 128;
constexpr size_t kMaxFrameBytes = 2 + kMaxFramePayload;

// Identifiers (one octet, or two in the high-tag form written as 0x5Fnn/0x7Fnn).
constexpr uint16_t kRequest = 0xEE;
constexpr uint16_t kResponse = 0xEF;
constexpr uint16_t kNotification = 0xF0;
constexpr uint16_t kDeviceAddress = 0x40;       // [APPLICATION 0] OCTET STRING (2)
constexpr uint16_t kTouchDescriptor = 0x41;     // [APPLICATION 1] BIT STRING
constexpr uint16_t kTouchNotification = 0x42;   // [APPLICATION 2] OCTET STRING
constexpr uint16_t kBootComplete = 0x63;        // [APPLICATION 3] SEQUENCE
constexpr uint16_t kEnable = 0x65;              // [APPLICATION 5]
constexpr uint16_t kTouchFormat = 0x66;         // [APPLICATION 6]
constexpr uint16_t kOperationMode = 0x67;       // [APPLICATION 7]
constexpr uint16_t kFrequency = 0x68;           // [APPLICATION 8]
constexpr uint16_t kResolution = 0x69;          // [APPLICATION 9]
constexpr uint16_t kDeviceConfiguration = 0x73; // [APPLICATION 19]
constexpr uint16_t kResultCode = 0x54;          // [APPLICATION 20] INTEGER
constexpr uint16_t kTimestamp = 0x58;           // [APPLICATION 24] INTEGER
constexpr uint16_t kStatusNotification = 0x7B;  // [APPLICATION 27]
constexpr uint16_t kLatency = 0x5F23;           // [APPLICATION 35] INTEGER
constexpr uint16_t kTouchNotifications = 0xA0;  // [0] SEQUENCE OF TouchNotification

constexpr uint8_t kDeviceTypePlatform = 0x00;
constexpr uint8_t kDeviceTypeAir = 0x02;
constexpr uint8_t kMaxDeviceType = 0x04;  // lighting

enum class TouchEvent : uint8_t { Down = 0, Move = 1, Up = 2, Invalid = 3, Ghost = 4 };
constexpr uint8_t kMaxTouchEvent = 4;

// Bit numbers of the TouchDescriptor; each present field is one byte, in this order.
enum class TouchField : uint8_t {
  Id = 0, Event = 1,
  X1 = 2, X2 = 3, X3 = 4, Y1 = 5, Y2 = 6, Y3 = 7, Z1 = 8, Z2 = 9, Z3 = 10,
  SizeX1 = 11, SizeX2 = 12, SizeX3 = 13, SizeY1 = 14, SizeY2 = 15, SizeY3 = 16,
  SizeZ1 = 17, SizeZ2 = 18, SizeZ3 = 19, Orientation = 20, Confidence = 21, Pressure = 22,
};
constexpr uint8_t kTouchFieldCount = 23;

struct TouchFormat {
  uint32_t fields = 0;  // bit n: TouchField n present

  static constexpr uint32_t bit(TouchField f) { return 1u << static_cast<uint8_t>(f); }
  bool has(TouchField f) const { return (fields & bit(f)) != 0; }
  uint8_t bytes() const;
  // Usable by this driver: id, event and at least the first byte of x and y.
  bool usable() const;
  // What the driver assumes until the sensor's touchFormat answer arrives:
  // id, event, x (2 bytes), y (2 bytes), size x (2 bytes), confidence: the
  // 9-byte layout the Arduino library decoded before it asked for the format.
  static TouchFormat assumed_default();
};

// Request frames, I2C header included. Each returns the frame length, or 0
// if `capacity` is too small.
size_t build_touch_format_request(uint8_t* out, size_t capacity);
size_t build_enable(uint8_t* out, size_t capacity, bool enable);  // enable: continuous reporting
size_t build_operation_mode_detection(uint8_t* out, size_t capacity);  // detection on, raw signals off
size_t build_resolution(uint8_t* out, size_t capacity, uint16_t x, uint16_t y);
size_t build_frequency(uint8_t* out, size_t capacity, uint16_t finger_hz, uint16_t idle_hz);
size_t build_reported_touches(uint8_t* out, size_t capacity, uint8_t touches);

}  // namespace ff::zforce
