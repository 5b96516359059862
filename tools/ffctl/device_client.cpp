#include "device_client.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

namespace ff::ffctl {

using protocol::Message;
using protocol::MessageType;

ReceiveResult DeviceClient::next(Message& m, int timeout_ms) {
  std::vector<uint8_t> frame;
  for (;;) {
    const ReceiveResult r = transport_.receive(frame, timeout_ms);
    if (r != ReceiveResult::Frame) return r;
    if (protocol::decode(frame.data(), frame.size(), m) == protocol::DecodeStatus::Ok) return r;
    ++malformed_;  // counted, skipped: the next frame may be fine
  }
}

bool DeviceClient::request(Message command, Message& reply, std::string& error, int timeout_ms) {
  command.sequence = ++sequence_;
  uint8_t frame[protocol::kMaxFrame];
  const size_t n = protocol::encode(command, frame, sizeof frame);
  if (n == 0) return error = "the command does not fit in one frame", false;
  if (!transport_.send(frame, n)) return error = "the device did not take the command (disconnected?)", false;
  for (int waited = 0; waited < 50; ++waited) {
    const ReceiveResult r = next(reply, timeout_ms);
    if (r == ReceiveResult::Disconnected) return error = "the device disconnected", false;
    if (r == ReceiveResult::Timeout) return error = "no reply from the device within " + std::to_string(timeout_ms) + " ms", false;
    if (reply.type == MessageType::Error) {
      return error = "the device refused the message (error code " + std::to_string(static_cast<int>(reply.error.code)) + ")", false;
    }
    if ((reply.type == MessageType::Ack || reply.type == MessageType::Status) && reply.sequence == command.sequence) return true;
  }
  return error = "no reply among the device's streamed messages", false;
}

bool record(DeviceClient& client, double seconds, Recording& out, std::string& error,
            const std::function<void(double, size_t, size_t)>& progress) {
  Message start, reply;
  start.type = MessageType::StartStream;
  start.stream.tick_decimation = 1;
  if (!client.request(start, reply, error)) return false;
  uint64_t high = 0;
  uint32_t last32 = 0;
  bool have = false;
  auto unwrap = [&](uint32_t t) {  // 32-bit device micros to a monotonic 64-bit time
    if (have && t < last32 && last32 - t > 0x80000000u) high += 0x100000000ull;
    last32 = t;
    have = true;
    return high + t;
  };
  uint64_t first = 0;
  bool started = false;
  for (;;) {
    Message m;
    const ReceiveResult r = client.next(m, 1000);
    if (r == ReceiveResult::Disconnected) return error = "the device disconnected while recording", false;
    if (r == ReceiveResult::Timeout) return error = "the device stopped streaming", false;
    uint64_t newest = 0;
    if (m.type == MessageType::Samples) {
      for (int i = 0; i < m.samples.count; ++i) {
        const SensorSample& s = m.samples.samples[i];
        newest = unwrap(s.t_us);
        out.samples.push_back({newest, s.x, s.y, s.touch});
      }
    } else if (m.type == MessageType::Ticks) {
      for (int i = 0; i < m.ticks.count; ++i) {
        const protocol::TickRecord& t = m.ticks.ticks[i];
        newest = unwrap(t.t_us);
        out.ticks.push_back({newest, t.amplitude, t.dac, t.present});
      }
    } else {
      continue;
    }
    if (!started) {
      first = newest;
      started = true;
    }
    const double done = static_cast<double>(newest - first) * 1e-6;
    if (progress) progress(done, out.samples.size(), out.ticks.size());
    if (done >= seconds) break;
  }
  Message stop;
  stop.type = MessageType::StopStream;
  std::string ignored;
  client.request(stop, reply, ignored);
  return true;
}

std::string ticks_path_for(const std::string& trace_path) {
  const size_t dot = trace_path.rfind(".csv");
  return (dot == std::string::npos ? trace_path : trace_path.substr(0, dot)) + ".ticks.csv";
}

bool write_recording(const std::string& path, const Recording& r, std::string& error) {
  std::ofstream trace(path), ticks(ticks_path_for(path));
  if (!trace || !ticks) return error = "cannot write " + path, false;
  trace << "t_us,x,y,touch\n";
  char buf[128];
  for (const host::TraceRow& s : r.samples) {
    std::snprintf(buf, sizeof buf, "%llu,%.3f,%.3f,%d\n", static_cast<unsigned long long>(s.t_us),
                  static_cast<double>(s.x), static_cast<double>(s.y), s.touch ? 1 : 0);
    trace << buf;
  }
  ticks << "t_us,amplitude,dac,present\n";
  for (const DeviceTick& t : r.ticks) {
    std::snprintf(buf, sizeof buf, "%llu,%.7g,%u,%d\n", static_cast<unsigned long long>(t.t_us),
                  static_cast<double>(t.amplitude), static_cast<unsigned>(t.dac), t.present ? 1 : 0);
    ticks << buf;
  }
  return true;
}

bool read_recording(const std::string& path, Recording& r, std::string& error) {
  host::TraceError terr;
  if (!host::read_sensor_trace_file(path, r.samples, terr)) return error = terr.to_string(path), false;
  const std::string tpath = ticks_path_for(path);
  std::ifstream in(tpath);
  if (!in) return error = tpath + ": cannot open (ffctl record writes it next to the trace)", false;
  std::string line;
  std::getline(in, line);
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    DeviceTick t;
    unsigned long long time = 0;
    unsigned dac = 0;
    int present = 0;
    float amp = 0.0f;
    if (std::sscanf(line.c_str(), "%llu,%f,%u,%d", &time, &amp, &dac, &present) != 4 || dac > 4095) {
      return error = tpath + ":" + std::to_string(line_no) + ": expected t_us,amplitude,dac,present", false;
    }
    t.t_us = time;
    t.amplitude = amp;
    t.dac = static_cast<uint16_t>(dac);
    t.present = present != 0;
    r.ticks.push_back(t);
  }
  return true;
}

VerifyResult verify(const Recording& r, const Condition& condition, const TrackerConfig& tracker) {
  VerifyResult v;
  auto pipeline = std::make_unique<HapticPipeline>(tracker);
  if (pipeline->set_condition(condition) != PrepareStatus::Ok) return v;
  size_t next = 0;
  for (const DeviceTick& t : r.ticks) {
    while (next < r.samples.size() && r.samples[next].t_us <= t.t_us) {
      const host::TraceRow& s = r.samples[next++];
      pipeline->post_sample({static_cast<uint32_t>(s.t_us), s.x, s.y, s.touch});
    }
    const TickOutput out = pipeline->tick(static_cast<uint32_t>(t.t_us));
    ++v.compared;
    const float da = std::fabs(out.amplitude - t.amplitude);
    const int dd = std::abs(static_cast<int>(out.dac) - static_cast<int>(t.dac));
    v.max_amplitude_difference = std::fmax(v.max_amplitude_difference, da);
    v.max_dac_difference = std::max(v.max_dac_difference, dd);
    if (dd > 1) {
      ++v.beyond_one_code;
      if (v.first.size() < 10) v.first.push_back({t.t_us, t.amplitude, out.amplitude, t.dac, out.dac});
    }
  }
  return v;
}

}  // namespace ff::ffctl
