#pragma once
// A Neonode zForce sensor as the I2C bus and the DR line see it. It answers
// configuration requests, and turns a finger trace (SensorSample points with
// t_us, in screen pixels) into touch notifications: down at the first
// touching point, move after, up at the first non-touching point; the DR
// line rises at each point's t_us (or, if the host is still reading the
// previous message, when that one is done). Frames are encoded here, from
// the protocol description, independently of the driver's decoder. Faults on
// request: wrong header, truncated, announced longer than sent, over-long,
// unknown or malformed tags, impossible values, a second finger.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "frictionfield/bus/data_ready.hpp"
#include "frictionfield/core/sensor_sample.hpp"
#include "frictionfield/drivers/zforce_calibration.hpp"
#include "frictionfield/drivers/zforce_protocol.hpp"
#include "frictionfield/emulated/i2c_bus.hpp"

namespace ff::emulated {

class ZforceModel final : public I2cTarget, public DataReadyInput {
 public:
  enum class Fault : uint8_t {
    BadHeader,         // first byte 0x00 instead of 0xEE
    Truncated,         // the BER message cut short (the length byte agrees with what is sent)
    CutShort,          // the length byte announces 6 more bytes than are sent
    LengthOverMax,     // a 200-byte payload
    UnknownTag,        // a notification choice the protocol does not define
    MalformedLength,   // a length field with 5 length octets
    ImpossibleEvent,   // touch event 7
    OutOfRange,        // x beyond the resolution
  };

  struct SecondFinger {
    uint32_t from_us = 0;  // present in every notification in [from_us, to_us]
    uint32_t to_us = 0;
    float x = 400.0f;
    float y = 100.0f;
    bool listed_first = false;  // put before the tracked finger in the notification
  };

  struct Options {
    zforce::TouchFormat format = zforce::TouchFormat::assumed_default();
    bool boot_complete = true;      // a boot-complete notification at t = 0
    bool timestamps = true;         // notificationTimestamp (32768 Hz) on touches
    bool timestamp_inside = false;  // ... inside the touch sequence instead of beside it
    bool answer_requests = true;    // false: requests are accepted but never answered
  };

  explicit ZforceModel(const Options& options);
  ZforceModel() : ZforceModel(Options()) {}

  // Scenario. Calibration: how pixels map back to sensor units (the inverse
  // of the driver's ScreenCalibration; the resolution is what the host sets).
  void set_calibration(const ScreenCalibration& c) { calibration_ = c; }
  void load_trace(const std::vector<SensorSample>& trace, const SecondFinger* second = nullptr);
  void inject(uint32_t t_us, Fault f);                         // a faulty frame of its own
  bool corrupt_frame_at(uint32_t t_us, Fault f);               // the trace frame due at t_us
  void schedule_raw(uint32_t t_us, std::vector<uint8_t> frame);  // anything at all

  // Time: frames due at or before now become readable.
  void advance_to(uint32_t now_us);

  // I2cTarget, DataReadyInput.
  BusStatus on_write(const uint8_t* data, size_t n) override;
  BusStatus on_read(uint8_t* data, size_t n) override;
  bool asserted() const override;
  bool take_edge(uint32_t& t_us, uint32_t& edges) override;

  // What the host configured.
  bool enabled() const { return enabled_; }
  bool detection_mode() const { return detection_; }
  uint16_t resolution_x() const { return resolution_x_; }
  uint16_t resolution_y() const { return resolution_y_; }
  uint16_t finger_frequency() const { return finger_hz_; }
  uint16_t idle_frequency() const { return idle_hz_; }
  uint8_t reported_touches() const { return reported_touches_; }
  uint32_t requests() const { return requests_; }
  uint32_t requests_rejected() const { return rejected_; }
  const std::string& last_rejection() const { return last_rejection_; }
  uint32_t frames_delivered() const { return delivered_; }
  uint32_t touch_frames_dropped_disabled() const { return dropped_disabled_; }
  size_t frames_pending() const { return queue_.size(); }
  uint32_t overread_bytes() const { return overread_; }

  // Encoders (public for tests that want a frame by hand).
  std::vector<uint8_t> touch_frame(const uint8_t* ids, const uint8_t* events, const uint32_t* xs,
                                   const uint32_t* ys, int count, uint32_t t_us) const;
  void to_sensor(float x_px, float y_px, uint32_t& x, uint32_t& y) const;

 private:
  struct Frame {
    uint32_t due_us;
    std::vector<uint8_t> bytes;
    size_t declared;  // bytes the host may read before it ends (2 + length byte, or fewer)
    bool touch;       // dropped (not delivered) while reporting is disabled
  };

  void schedule(Frame f);
  void respond(const std::vector<uint8_t>& payload);
  void become_current();
  std::vector<uint8_t> notification(const std::vector<uint8_t>& body, bool with_timestamp, uint32_t t_us) const;

  Options options_;
  ScreenCalibration calibration_;
  std::deque<Frame> queue_;
  bool current_ = false;   // the front frame is readable (DR up)
  size_t read_pos_ = 0;
  uint32_t now_ = 0;
  uint32_t free_since_ = 0;  // when the host finished reading the last message
  uint32_t edge_us_ = 0;
  uint32_t edges_ = 0;
  uint32_t edges_taken_ = 0;
  bool enabled_ = false;
  bool detection_ = false;
  uint16_t resolution_x_ = 0;
  uint16_t resolution_y_ = 0;
  uint16_t finger_hz_ = 0;
  uint16_t idle_hz_ = 0;
  uint8_t reported_touches_ = 0;
  uint32_t requests_ = 0;
  uint32_t rejected_ = 0;
  std::string last_rejection_;
  uint32_t delivered_ = 0;
  uint32_t dropped_disabled_ = 0;
  uint32_t overread_ = 0;
};

}  // namespace ff::emulated
