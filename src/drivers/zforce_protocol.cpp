#include "frictionfield/drivers/zforce_protocol.hpp"

#include "frictionfield/drivers/ber.hpp"

namespace ff::zforce {
namespace {

// Frames a request addressed to `device_type` 0: 0xEE, length, then the
// request [PRIVATE 14] { deviceAddress, <body> }.
template <typename Body>
size_t build_request(uint8_t* out, size_t capacity, uint8_t device_type, Body body) {
  if (out == nullptr || capacity < 2) return 0;
  ber::Writer w(out + 2, capacity - 2);
  w.begin(kRequest);
  const uint8_t address[2] = {device_type, 0};
  w.octets(kDeviceAddress, address, 2);
  body(w);
  w.end();
  if (!w.ok() || w.size() > kMaxFramePayload) return 0;
  out[0] = kFrameStart;
  out[1] = static_cast<uint8_t>(w.size());
  return w.size() + 2;
}

}  // namespace

uint8_t TouchFormat::bytes() const {
  uint8_t n = 0;
  for (uint8_t i = 0; i < kTouchFieldCount; ++i) n = static_cast<uint8_t>(n + ((fields >> i) & 1u));
  return n;
}

bool TouchFormat::usable() const {
  return has(TouchField::Id) && has(TouchField::Event) && has(TouchField::X1) && has(TouchField::Y1) &&
         (fields >> kTouchFieldCount) == 0;
}

TouchFormat TouchFormat::assumed_default() {
  TouchFormat f;
  f.fields = bit(TouchField::Id) | bit(TouchField::Event) | bit(TouchField::X1) | bit(TouchField::X2) |
             bit(TouchField::Y1) | bit(TouchField::Y2) | bit(TouchField::SizeX1) | bit(TouchField::SizeX2) |
             bit(TouchField::Confidence);
  return f;
}

size_t build_touch_format_request(uint8_t* out, size_t capacity) {
  return build_request(out, capacity, kDeviceTypeAir, [](ber::Writer& w) {
    w.begin(kTouchFormat);  // an empty sequence asks for the current value
    w.end();
  });
}

size_t build_enable(uint8_t* out, size_t capacity, bool enable) {
  return build_request(out, capacity, kDeviceTypeAir, [enable](ber::Writer& w) {
    w.begin(kEnable);
    if (enable) {
      w.unsigned_integer(0x81, 0);  // enable [1] INTEGER 0: report continuously
    } else {
      w.null(0x80);  // disable [0] NULL
    }
    w.end();
  });
}

size_t build_operation_mode_detection(uint8_t* out, size_t capacity) {
  return build_request(out, capacity, kDeviceTypeAir, [](ber::Writer& w) {
    w.begin(kOperationMode);
    w.boolean(0x80, true);   // detection
    w.boolean(0x81, false);  // signals
    w.boolean(0x82, false);  // ledLevels
    w.boolean(0x83, false);  // detectionHid
    w.boolean(0x84, false);  // gestures
    w.end();
  });
}

size_t build_resolution(uint8_t* out, size_t capacity, uint16_t x, uint16_t y) {
  return build_request(out, capacity, kDeviceTypeAir, [x, y](ber::Writer& w) {
    w.begin(kResolution);
    w.unsigned_integer(0x80, x);
    w.unsigned_integer(0x81, y);
    w.end();
  });
}

size_t build_frequency(uint8_t* out, size_t capacity, uint16_t finger_hz, uint16_t idle_hz) {
  // Scan frequencies belong to the platform device (as in Neonode's library).
  return build_request(out, capacity, kDeviceTypePlatform, [finger_hz, idle_hz](ber::Writer& w) {
    w.begin(kFrequency);
    w.unsigned_integer(0x80, finger_hz);
    w.unsigned_integer(0x82, idle_hz);
    w.end();
  });
}

size_t build_reported_touches(uint8_t* out, size_t capacity, uint8_t touches) {
  return build_request(out, capacity, kDeviceTypeAir, [touches](ber::Writer& w) {
    w.begin(kDeviceConfiguration);
    w.unsigned_integer(0x86, touches);  // numberOfReportedTouches [6]
    w.end();
  });
}

}  // namespace ff::zforce
