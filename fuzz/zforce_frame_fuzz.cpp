// libFuzzer target for the zForce frame parser, two ways:
//  1. the whole input as one I2C frame through FrameDecoder (and, if it is a
//     touchFormat answer, a second decoder with that format);
//  2. the input as a stream of sensor messages served over a fake I2C bus
//     and DR line to the full ZforceSensor driver: [L][L bytes][L][L bytes]...
//     each chunk one message (DR up until the host has read it all).
// Checked: no crash or sanitizer report, decoded values in range, every
// sample finite, on screen and in time order, the main loop always ends.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "frictionfield/drivers/zforce_frame.hpp"
#include "frictionfield/drivers/zforce_sensor.hpp"

namespace {

using namespace ff;

void check(bool ok) {
  if (!ok) std::abort();
}

void check_message(const zforce::Message& m, uint32_t max_x, uint32_t max_y) {
  check(m.touch_count <= zforce::kMaxTouches);
  for (uint8_t i = 0; i < m.touch_count; ++i) {
    const zforce::Touch& t = m.touches[i];
    check(static_cast<uint8_t>(t.event) <= zforce::kMaxTouchEvent);
    if (t.event == zforce::TouchEvent::Down || t.event == zforce::TouchEvent::Move ||
        t.event == zforce::TouchEvent::Up) {
      check(t.x <= max_x && t.y <= max_y);
    }
  }
}

// The sensor side: messages cut from the input, read as the zForce would
// serve them over I2C.
class FakeSensor final : public I2cInitiator, public DataReadyInput {
 public:
  FakeSensor(const uint8_t* data, size_t size) : data_(data), size_(size) { next_message(); }

  bool asserted() const override { return pos_ < end_; }
  bool take_edge(uint32_t& t_us, uint32_t& edges) override {
    if (edges_ == taken_) return false;
    edges = edges_ - taken_;
    taken_ = edges_;
    t_us = edge_us_;
    return true;
  }
  uint32_t now_us = 0;

 private:
  void next_message() {
    while (pos_ >= end_ && end_ < size_) {
      const size_t length = data_[end_];
      pos_ = end_ + 1;
      end_ = pos_ + length > size_ ? size_ : pos_ + length;
      if (pos_ < end_) {
        ++edges_;
        edge_us_ = now_us;
      }
    }
  }
  BusStatus do_write_read(uint8_t, const uint8_t*, size_t, uint8_t* rx, size_t rx_len, uint32_t) override {
    for (size_t i = 0; i < rx_len; ++i) {
      rx[i] = pos_ < end_ ? data_[pos_++] : 0xFF;  // past the message: idle bytes
      if (pos_ >= end_) {
        for (size_t j = i + 1; j < rx_len; ++j) rx[j] = 0xFF;
        next_message();
        break;
      }
    }
    return BusStatus::Ok;
  }

  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  size_t end_ = 0;
  uint32_t edges_ = 0;
  uint32_t taken_ = 0;
  uint32_t edge_us_ = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // 1. One frame.
  zforce::FrameDecoder decoder;
  decoder.set_limits(3200, 1920);
  zforce::Message m;
  if (decoder.decode(data, size, m) == zforce::FrameError::None) {
    check_message(m, 3200, 1920);
    if (m.has_format) {
      check(m.format.usable());
      zforce::FrameDecoder learned;
      check(learned.set_format(m.format));
      learned.set_limits(3200, 1920);
      if (learned.decode(data, size, m) == zforce::FrameError::None) check_message(m, 3200, 1920);
    }
  }

  // 2. A stream of messages through the driver.
  FakeSensor sensor(data, size);
  ZforceSensor driver(sensor, sensor);
  driver.begin(0);
  uint32_t last_t = 0;
  bool have_last = false;
  for (uint32_t loop = 0; loop < size + 8; ++loop) {
    sensor.now_us = loop * 500u;
    SensorSample s;
    int samples = 0;
    while (driver.poll(sensor.now_us, s)) {
      check(++samples <= 64);
      check(std::isfinite(s.x) && std::isfinite(s.y));
      check(s.x >= 0.0f && s.x <= 800.0f && s.y >= 0.0f && s.y <= 480.0f);
      check(!have_last || s.t_us >= last_t);
      last_t = s.t_us;
      have_last = true;
    }
    if (!sensor.asserted()) break;
  }
  check(driver.count(ZforceCount::Samples) <= driver.count(ZforceCount::FramesRead));
  return 0;
}
