#pragma once
// The Neonode zForce sensor on I2C + DR: configures it (touch format,
// resolution, scan frequency, reported touches, detection mode, enable),
// reads its frames when DR is up, tracks one finger and hands out
// ff::SensorSample in screen pixels, stamped with the DR edge time.
//
// One finger: the first to go down is tracked until it goes up; every other
// finger is ignored (counted), so a second finger in the light plane cannot
// move the tracked position. A finger whose down event was lost (a dropped
// frame) is picked up from its move events, unless it is one already being
// ignored.
//
// Everything is driven by poll() from the main loop; nothing blocks, nothing
// allocates, every frame and every drain is bounded.
#include <cstdint>

#include "frictionfield/bus/data_ready.hpp"
#include "frictionfield/bus/i2c.hpp"
#include "frictionfield/core/sensor_sample.hpp"
#include "frictionfield/drivers/zforce_calibration.hpp"
#include "frictionfield/drivers/zforce_frame.hpp"

namespace ff {

struct ZforceConfig {
  uint8_t address = zforce::kI2cAddress;
  uint16_t resolution_x = 3200;  // sensor units across the active area (0.25 px each by default)
  uint16_t resolution_y = 1920;
  uint16_t finger_frequency_hz = 200;  // scan rate with a finger present (the thesis' ~200 Hz)
  uint16_t idle_frequency_hz = 50;     // scan rate with none
  uint8_t reported_touches = 2;        // see the second finger, so that it can be ignored by id
  uint32_t i2c_timeout_us = 2000;
  uint32_t boot_wait_us = 300000;      // for the boot-complete notification, then configure anyway
  uint32_t response_timeout_us = 100000;
  uint8_t max_attempts = 3;            // per configuration request
  uint32_t track_timeout_us = 200000;  // tracked finger silent this long: forgotten (its up was lost)
  ScreenCalibration calibration = ScreenCalibration::fit(3200, 1920);
};

enum class ZforceCount : uint8_t {
  FramesRead,          // frames decoded without error
  Samples,             // samples handed out
  WrongHeader,
  LengthOverMax,
  Truncated,
  MalformedTag,
  UnknownTag,
  ImpossibleValue,
  BusError,            // an I2C read or write failed
  ResyncBytes,         // bytes read and dropped to get back to a frame start
  OtherFingerIgnored,  // touch reports of a finger other than the tracked one
  GhostOrInvalid,      // the tracked finger reported invalid or ghost: no sample
  ResumedWithoutDown,  // tracking started from a move (its down was lost)
  UnexpectedResponse,  // a response to something not asked
  ConfigRetry,         // a configuration request sent again after a timeout
  SensorRebooted,      // boot-complete while running: configured again
  TrackLost,           // the tracked finger stopped reporting without an up event
  TimestampBeside,     // touch notifications with the timestamp beside the touch sequence
  TimestampInside,     // ... or inside it (both layouts are accepted; the first board run tells which)
  kCount
};
const char* to_string(ZforceCount c);

enum class ZforceState : uint8_t { Booting, Configuring, Running, Failed };

class ZforceSensor {
 public:
  ZforceSensor(I2cInitiator& bus, DataReadyInput& data_ready, const ZforceConfig& config = ZforceConfig());

  // Starts the boot wait and configuration from `now_us`.
  void begin(uint32_t now_us);
  // Main loop. Reads frames while DR is up (at most a few per call) and
  // returns true with `out` filled when one of them gave a sample; call it
  // again until it returns false.
  bool poll(uint32_t now_us, SensorSample& out);

  ZforceState state() const { return state_; }
  bool finger_present() const { return tracking_; }
  uint32_t count(ZforceCount c) const { return counts_[static_cast<int>(c)]; }
  uint32_t errors() const;  // frame errors and bus errors together
  const zforce::TouchFormat& format() const { return decoder_.format(); }
  const ZforceConfig& config() const { return config_; }

 private:
  enum class Step : uint8_t { TouchFormat, Resolution, Frequency, ReportedTouches, OperationMode, Enable, kDone };

  void add(ZforceCount c, uint32_t n = 1);
  void count_error(zforce::FrameError e);
  bool next_edge(uint32_t& t_us);
  bool read_frame(zforce::Message& msg);  // false: nothing usable (counted)
  void drain_until_idle();
  void discard(uint32_t bytes);
  void send_step(uint32_t now_us);
  void on_response(const zforce::Message& msg, uint32_t now_us);
  bool on_touches(const zforce::Message& msg, uint32_t t_us, SensorSample& out);
  bool ignored(uint8_t id) const { return (ignored_[id >> 5] >> (id & 31u)) & 1u; }
  void set_ignored(uint8_t id, bool on);

  I2cInitiator& bus_;
  DataReadyInput& dr_;
  ZforceConfig config_;
  zforce::FrameDecoder decoder_;
  ZforceState state_ = ZforceState::Booting;
  Step step_ = Step::TouchFormat;
  bool awaiting_ = false;
  uint8_t attempts_ = 0;
  uint32_t deadline_us_ = 0;
  bool edge_pending_ = false;  // an edge seen while draining: the next message's
  uint32_t pending_edge_us_ = 0;
  bool tracking_ = false;
  uint32_t tracked_seen_us_ = 0;
  uint8_t tracked_id_ = 0;
  uint32_t ignored_[8] = {};  // one bit per touch id
  uint32_t counts_[static_cast<int>(ZforceCount::kCount)] = {};
  uint8_t buffer_[zforce::kMaxFrameBytes] = {};
};

}  // namespace ff
