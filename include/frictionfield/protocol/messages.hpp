#pragma once
// The host <-> device messages (docs/protocol.md). One codec serves UDP and
// the USB HID host channel alike. Plain data: no heap, no pointers.
#include <cstdint>

#include "frictionfield/core/amplitude_map.hpp"
#include "frictionfield/core/condition.hpp"
#include "frictionfield/core/fault_counters.hpp"
#include "frictionfield/core/path_curve.hpp"
#include "frictionfield/core/scene.hpp"
#include "frictionfield/core/sensor_profile.hpp"
#include "frictionfield/core/sensor_sample.hpp"
#include "frictionfield/protocol/device_counts.hpp"

namespace ff::protocol {

// 2: streamed reports may say which tick took them; status carries
// the watchdog and stream-overrun counters; the DAC calibration travels whole;
// QueryCondition / Condition; non-finite numbers are malformed.
constexpr uint8_t kVersion = 2;

enum class MessageType : uint8_t {
  // host -> device
  SetCondition = 0x01,   // the thesis' three fields, or a general scene
  QueryStatus = 0x02,
  StartStream = 0x03,    // raw sensor reports + rendered ticks, for ffctl record
  StopStream = 0x04,
  SetCarrier = 0x05,     // AD9834 frequency
  StartSweep = 0x06,     // frequency sweep (resonance search)
  RebootToBootloader = 0x07,
  QueryCondition = 0x08, // what the device renders now (ffctl record keeps it for verify)
  SetSensorProfile = 0x09,    // the tracker's sensor (ffctl sensor-profile): until reset or power-off
  QuerySensorProfile = 0x0A,  // which profile the tracker uses
  // device -> host
  Ack = 0x81,            // a command was carried out (or refused: status)
  Status = 0x82,
  Force = 0x83,          // every 30 ms: 5-sample average
  Samples = 0x84,        // raw sensor reports
  Ticks = 0x85,          // rendered ticks (every `decimation`-th)
  Condition = 0x86,      // reply to QueryCondition: the SetCondition payload
  SensorProfile = 0x87,  // reply to QuerySensorProfile: the SetSensorProfile payload
  Error = 0xE0,          // a malformed or unknown message was received
};

enum class ConditionKind : uint8_t { Heightmap = 0, Frictionmap = 1, Neutral = 2, General = 3 };

// What the experiment's host sends each trial (thesis alg. 1), or a general scene.
struct ConditionMessage {
  ConditionKind kind = ConditionKind::Heightmap;
  Target target = Target::Middle;
  float strength = 1.0f;
  float idle_amplitude = 0.0f;
  float s_curve = 0.0f;
  DacCalibration calibration = DacCalibration::linear();  // 2..16 points
  SceneDefinition scene;  // General only (no sampled height map over the wire)

  Condition to_condition() const;
};

enum class AckStatus : uint8_t { Ok = 0, Refused = 1 };
struct AckMessage {
  MessageType command = MessageType::SetCondition;
  AckStatus status = AckStatus::Ok;
  uint8_t detail = 0;  // e.g. PrepareStatus
};

struct StatusMessage {
  uint16_t firmware_version = 0;  // major << 8 | minor
  ConditionKind kind = ConditionKind::Neutral;
  Target target = Target::Middle;
  float strength = 1.0f;
  uint32_t ticks = 0;
  uint32_t tick_cycles_mean = 0;
  uint32_t tick_cycles_max = 0;
  uint32_t protocol_errors = 0;
  uint32_t watchdog_trips = 0;   // ticks forced idle because the main loop stalled
  uint32_t stream_overruns = 0;  // tick records dropped from the stream
  float force_mN = 0.0f;
  bool over_force = false;
  bool finger_present = false;
  float carrier_hz = 0.0f;
  // What only silicon can tell (docs/firmware.md): the whole tick interrupt
  // in DWT cycles (180 per us; the tick's budget is 90,000), the last scene
  // preparation, the slowest main-loop pass since boot, and which zForce
  // timestamp layout the sensor sends.
  uint32_t isr_cycles_mean = 0;
  uint32_t isr_cycles_max = 0;
  uint32_t isr_cycles_p99 = 0;  // upper edge of the histogram bin holding the 99th percentile
  uint32_t prepare_us_last = 0;
  uint32_t loop_pass_max_us = 0;
  uint32_t zforce_layout_beside = 0;
  uint32_t zforce_layout_inside = 0;
  FaultCounters faults;
  // What the firmware counts beside the faults, the touch sensor's state and
  // the zForce driver's own counts (ZforceCount order). A firmware before 1.1
  // sends none of them: Unknown, and no counts.
  DeviceCounts device;
  SensorState sensor_state = SensorState::Unknown;
  uint8_t sensor_count_n = 0;
  uint32_t sensor_counts[kMaxSensorCounts] = {};
};

struct ForceMessage {
  uint32_t t_us = 0;
  float force_mN = 0.0f;
  bool over_force = false;
};

constexpr int kMaxSamplesPerMessage = 24;
struct SamplesMessage {
  uint8_t count = 0;
  SensorSample samples[kMaxSamplesPerMessage];
  // With each report, the time of the tick that took it from the mailbox
  // (a firmware that streams reports as its ticks take them knows it): lets
  // `ffctl verify` hand it to the same tick natively, whatever the I2C read
  // latency was. Without it, verify goes by the reports' timestamps.
  bool has_taken_times = false;
  uint32_t taken_us[kMaxSamplesPerMessage] = {};
};

struct TickRecord {
  uint32_t t_us = 0;
  float amplitude = 0.0f;
  uint16_t dac = 0;
  bool present = false;
};
constexpr int kMaxTicksPerMessage = 32;
struct TicksMessage {
  uint8_t count = 0;
  TickRecord ticks[kMaxTicksPerMessage];
};

struct StreamMessage {
  uint8_t tick_decimation = 1;  // every n-th tick (1: all 2000 per second)
};

struct CarrierMessage {
  float frequency_hz = 34900.0f;
};

struct SweepMessage {
  float start_hz = 25000.0f;
  float end_hz = 70000.0f;
  uint32_t duration_ms = 30000;
};

enum class ErrorCode : uint8_t {
  TooShort = 1, BadMagic, BadVersion, BadLength, BadCrc, UnknownType, Malformed, Busy
};
struct ErrorMessage {
  ErrorCode code = ErrorCode::Malformed;
  uint8_t type = 0;  // the offending message type, if known
};

struct Message {
  MessageType type = MessageType::QueryStatus;
  uint8_t sequence = 0;  // echoed in replies
  ConditionMessage condition;  // SetCondition and Condition
  ff::SensorProfile sensor_profile;  // SetSensorProfile and SensorProfile (any finite values: the device judges)
  AckMessage ack;
  StatusMessage status;
  ForceMessage force;
  SamplesMessage samples;
  TicksMessage ticks;
  StreamMessage stream;
  CarrierMessage carrier;
  SweepMessage sweep;
  ErrorMessage error;
};

}  // namespace ff::protocol
