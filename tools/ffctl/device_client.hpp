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

  // Sends `command` and waits for its reply (Ack, Status or Error), skipping
  // streamed traffic. false with a readable `error`.
  bool request(protocol::Message command, protocol::Message& reply, std::string& error, int timeout_ms = 2000);
  // The next well-formed message of any kind.
  ReceiveResult next(protocol::Message& m, int timeout_ms);
  uint32_t malformed_replies() const { return malformed_; }

 private:
  Transport& transport_;
  uint8_t sequence_ = 0;
  uint32_t malformed_ = 0;
};

// A recording: the sensor reports (64-bit device microseconds, unwrapped) and
// the ticks the device rendered.
struct DeviceTick {
  uint64_t t_us = 0;
  float amplitude = 0.0f;
  uint16_t dac = 0;
  bool present = false;
};

struct Recording {
  std::vector<host::TraceRow> samples;
  std::vector<DeviceTick> ticks;
};

// Streams for `seconds` of device time (every tick) into `out`.
bool record(DeviceClient& client, double seconds, Recording& out, std::string& error,
            const std::function<void(double done_s, size_t samples, size_t ticks)>& progress = nullptr);

// trace.csv (t_us,x,y,touch: ff-replay reads it) and trace.ticks.csv (t_us,amplitude,dac,present).
bool write_recording(const std::string& trace_path, const Recording& r, std::string& error);
bool read_recording(const std::string& trace_path, Recording& r, std::string& error);
std::string ticks_path_for(const std::string& trace_path);

struct Mismatch {
  uint64_t t_us;
  float device_amplitude, native_amplitude;
  uint16_t device_dac, native_dac;
};

struct VerifyResult {
  size_t compared = 0;
  size_t beyond_one_code = 0;
  float max_amplitude_difference = 0.0f;
  int max_dac_difference = 0;
  std::vector<Mismatch> first;  // the first few beyond one code
};

// Replays the recorded reports through a native pipeline at the device's own
// tick times (each report delivered before the first tick at or after it).
VerifyResult verify(const Recording& r, const Condition& condition,
                    const TrackerConfig& tracker = TrackerConfig::recommended());

}  // namespace ff::ffctl
