#pragma once
// Commands and replies over a Transport, recording and verification.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/host/trace_csv.hpp"
#include "frictionfield/protocol/codec.hpp"
#include "transport.hpp"

namespace ff::ffctl {

class DeviceClient {
 public:
  explicit DeviceClient(Transport& transport) : transport_(transport) {}

  // Sends `command` and waits up to `timeout_ms` for its reply (Ack, Status
  // or Error with the same sequence number), skipping streamed traffic.
  // false with a readable `error` (an Error reply, a timeout, a disconnect).
  bool request(protocol::Message command, protocol::Message& reply, std::string& error, int timeout_ms = 2000);
  // The next well-formed message of any kind; malformed frames are counted and skipped.
  ReceiveResult next(protocol::Message& m, int timeout_ms);
  uint32_t malformed_replies() const { return malformed_; }
  // The version byte of the last frame that spoke another protocol version (0: none).
  uint8_t foreign_version() const { return foreign_version_; }

 private:
  Transport& transport_;
  uint8_t sequence_ = 0;
  uint32_t malformed_ = 0;
  uint8_t foreign_version_ = 0;
};

const char* to_string(protocol::ErrorCode code);

// A recording: the sensor reports and the ticks the device rendered (64-bit
// device microseconds, unwrapped), and the condition, if known.
struct DeviceSample {
  host::TraceRow row;
  bool taken_known = false;
  uint64_t taken_us = 0;  // the tick that took it from the mailbox, if the firmware said
};

struct DeviceTick {
  uint64_t t_us = 0;
  float amplitude = 0.0f;
  uint16_t dac = 0;
  bool present = false;
};

struct Recording {
  std::vector<DeviceSample> samples;
  std::vector<DeviceTick> ticks;
  bool has_condition = false;
  protocol::ConditionMessage condition;
};

// Streams every tick into `out` until `seconds` of device time have passed
// (seconds <= 0: until progress() returns false, e.g. on Ctrl-C). progress()
// is called as ticks arrive; returning false ends the recording.
bool record(DeviceClient& client, double seconds, Recording& out, std::string& error,
            const std::function<bool(double done_s, size_t samples, size_t ticks)>& progress = nullptr);

// NAME.csv: the sensor trace of docs/spec.md#sensor-trace (t_us,x,y,touch: ff-replay reads it),
// plus the device column taken_us (the tick that took the report, -1 unknown)
// when the firmware said; NAME.ticks.csv: the device's ticks
// (t_us,amplitude,dac,present); NAME.condition: the condition (in words as a
// comment, and as a protocol frame in hex), when known.
bool write_recording(const std::string& trace_path, const Recording& r, std::string& error);
bool read_recording(const std::string& trace_path, Recording& r, std::string& error);
std::string ticks_path_for(const std::string& trace_path);
std::string condition_path_for(const std::string& trace_path);
// "heightmap, target top, strength 0.66, ..." for humans.
std::string describe(const protocol::ConditionMessage& c);

struct Mismatch {
  uint64_t t_us = 0;
  float device_amplitude = 0.0f, native_amplitude = 0.0f;
  uint16_t device_dac = 0, native_dac = 0;
  bool device_present = false, native_present = false;
};

// Consecutive ticks that differ by more than one DAC code (or in presence).
struct MismatchRun {
  size_t ticks = 0;
  uint64_t first_t_us = 0, last_t_us = 0;
  int max_dac_difference = -1;
  Mismatch worst;
  Mismatch first;  // where it starts: its device and native values
};

struct VerifyResult {
  bool prepared = false;          // the condition prepared natively
  bool synchronised = false;      // a tick without a finger on both sides was found
  size_t warm_up = 0;             // ticks not compared while waiting for one (start, after gaps)
  size_t compared = 0;
  size_t beyond_one_code = 0;     // including presence mismatches
  size_t presence_mismatches = 0;
  float max_amplitude_difference = 0.0f;
  int max_dac_difference = 0;
  size_t missing_ticks = 0;       // gaps in the stream (the device overran or stalled)
  bool exact_alignment = false;   // every report said which tick took it
  std::vector<MismatchRun> runs;  // the first kMaxRuns
  size_t run_count = 0;
};
constexpr size_t kMaxRuns = 20;

// Replays the recorded reports through a native pipeline at the device's own
// tick times and compares tick by tick. Each report goes to the tick that
// took it on the device when the recording says (whatever the I2C read
// latency was), else to the first tick at or after its timestamp. Comparison
// starts, and restarts after a gap in the stream, at the first tick where
// neither side has a finger: before it the device's filters held history the
// recording lacks. If that never happens, everything is compared.
VerifyResult verify(const Recording& r, const Condition& condition,
                    const TrackerConfig& tracker = TrackerConfig::recommended());

}  // namespace ff::ffctl
