#pragma once
// Commands and replies over a Transport, recording and verification.
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
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

  // Sends `command` and waits up to `timeout_ms` for its reply (Ack, Status,
  // Condition, SensorProfile or Error with the same sequence number),
  // skipping streamed traffic.
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

// A command answered with an Ack; false with `error` if it was refused or not answered.
bool command(DeviceClient& client, const protocol::Message& m, std::string& error);

// Asks a running device to restart into the bootloader: the protocol's
// RebootToBootloader first (the firmware rests the plate before it jumps),
// the transport's own request (USB: the SEREMU feature report) only if no
// Ack arrives: that one jumps from the USB interrupt with the DAC as it is,
// but works when the firmware's loop hangs. `by_transport` says which.
bool reboot_device(Transport& transport, std::string& error, bool& by_transport, int timeout_ms = 2000);

// A recording: the sensor reports and the ticks the device rendered (64-bit
// device microseconds, unwrapped), and the condition and the tracker's sensor
// profile, if known.
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

struct DeviceForce {
  uint64_t t_us = 0;
  float force_mN = 0.0f;
  bool over_force = false;
};

struct Recording {
  std::vector<DeviceSample> samples;
  std::vector<DeviceTick> ticks;
  std::vector<DeviceForce> forces;
  bool has_condition = false;
  protocol::ConditionMessage condition;
  bool has_sensor_profile = false;  // false: a firmware before sensor profiles, i.e. the default
  SensorProfile sensor_profile;
};

// The tracker the device ran while it recorded `r`: the recommended one for its sensor profile.
TrackerConfig tracker_config_of(const Recording& r);

// The profile the device's tracker uses (QuerySensorProfile); false with `error` if the device did not say.
bool query_sensor_profile(DeviceClient& client, SensorProfile& profile, std::string& error);

// Where record() puts what arrives, message by message.
class RecordSink {
 public:
  virtual ~RecordSink() = default;
  virtual void sample(const DeviceSample& s) = 0;
  virtual void tick(const DeviceTick& t) = 0;
  virtual void force(const DeviceForce& f) = 0;
  // After each streamed message: make what arrived so far durable. false: stop, `error` says why (a full disk).
  virtual bool flush(std::string& error) { return static_cast<void>(error), true; }
};

// Keeps everything in memory (tests, verify).
class MemorySink final : public RecordSink {
 public:
  explicit MemorySink(Recording& r) : r_(r) {}
  void sample(const DeviceSample& s) override { r_.samples.push_back(s); }
  void tick(const DeviceTick& t) override { r_.ticks.push_back(t); }
  void force(const DeviceForce& f) override { r_.forces.push_back(f); }

 private:
  Recording& r_;
};

// What the live line shows while recording.
struct RecordProgress {
  double done_s = 0.0;  // device time since the first tick
  size_t samples = 0, ticks = 0, forces = 0;
  size_t lost_ticks = 0;  // gaps in the tick stream (the device overran, or datagrams were lost)
  DeviceTick last_tick;
  bool finger = false;  // the last sensor report's touch
  float x = 0.0f, y = 0.0f;
  bool have_force = false;
  DeviceForce last_force;
};

// Streams every tick into `sink` until `seconds` of device time have passed
// (seconds <= 0: until progress() returns false, e.g. on Ctrl-C). progress()
// is called as ticks arrive; returning false ends the recording.
bool record(DeviceClient& client, double seconds, RecordSink& sink, std::string& error,
            const std::function<bool(const RecordProgress&)>& progress = nullptr);
inline bool record(DeviceClient& client, double seconds, Recording& out, std::string& error,
                   const std::function<bool(const RecordProgress&)>& progress = nullptr) {
  MemorySink sink(out);
  return record(client, seconds, sink, error, progress);
}

// Files of a recording, written row by row as the rows arrive:
// NAME.csv: the sensor trace of docs/spec.md (t_us,x,y,touch: ff-replay
// reads it) plus the device column taken_us (the tick that took the report,
// -1 unknown); NAME.ticks.csv: the device's ticks (t_us,amplitude,dac,present);
// NAME.force.csv: the load cells (t_us,force_mN,over_force); NAME.condition:
// the condition (in words as a comment, and as a protocol frame in hex), when
// known; NAME.sensor-profile: the tracker's sensor profile, the same way. Each CSV starts with `# ` metadata lines (the `metadata` given, one
// per line), then its header. flush() writes whole rows only, so a recorder
// killed at any moment leaves valid files up to its last flush.
class RecordingWriter final : public RecordSink {
 public:
  RecordingWriter() = default;
  ~RecordingWriter() override;
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;
  // Also writes NAME.condition and NAME.sensor-profile now when `r` has them (removes stale ones otherwise).
  bool open(const std::string& trace_path, const std::vector<std::string>& metadata, const Recording& r,
            std::string& error);
  void sample(const DeviceSample& s) override;
  void tick(const DeviceTick& t) override;
  void force(const DeviceForce& f) override;
  bool flush(std::string& error) override;  // error: "cannot write FILE: REASON", the first failure
  bool close(std::string& error);  // flushes and closes

 private:
  enum File { kTrace, kTicks, kForce, kFiles };
  std::FILE* files_[kFiles] = {};
  std::string names_[kFiles];
  // Each file's stdio buffer, ours: glibc ignores setvbuf's size without one.
  static constexpr size_t kBufferBytes = size_t{1} << 20;
  std::unique_ptr<char[]> buffers_[kFiles];
  std::string failure_;  // the first failed write, kept: later ones would only repeat it
  bool note_failure(File f);
};

// Whether `trace_path` can be written (its folder exists; it is not a folder, a device or "-", since a recording
// is several files named after it): checked before the device is touched.
bool check_output_path(const std::string& trace_path, std::string& error);

bool write_recording(const std::string& trace_path, const Recording& r, std::string& error,
                     const std::vector<std::string>& metadata = {});
bool read_recording(const std::string& trace_path, Recording& r, std::string& error);
std::string ticks_path_for(const std::string& trace_path);
std::string force_path_for(const std::string& trace_path);
std::string condition_path_for(const std::string& trace_path);
std::string sensor_profile_path_for(const std::string& trace_path);
// "heightmap, target top, strength 0.66, ..." for humans.
std::string describe(const protocol::ConditionMessage& c);
// "white noise 1 px, wander 0 px over 0 ms, ..." for humans.
std::string describe(const SensorProfile& p);

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
  size_t recorded = 0;            // ticks in the recording
  // Ticks compared / ticks recorded: a verify that compared little proved little.
  double coverage() const { return recorded == 0 ? 0.0 : static_cast<double>(compared) / static_cast<double>(recorded); }
};
constexpr double kDefaultMinCoverage = 0.9;
// Whether a verification passes: something compared, at least `min_coverage`
// of the recorded ticks, and none beyond one DAC code.
bool verify_passed(const VerifyResult& v, double min_coverage);
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
