#include "device_client.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

#include "frictionfield/host/input_file.hpp"
#include "frictionfield/host/output_file.hpp"
#include "frictionfield/host/scene_file.hpp"
#include "frictionfield/host/sensor_profile_options.hpp"

namespace ff::ffctl {

using protocol::Message;
using protocol::MessageType;

// --- requests ----------------------------------------------------------------

ReceiveResult DeviceClient::next(Message& m, int timeout_ms) {
  std::vector<uint8_t> frame;
  // One deadline for the whole call: frames that do not decode (another
  // protocol version left streaming, corrupt frames) must not extend it.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return ReceiveResult::Timeout;
    const ReceiveResult r = transport_.receive(frame, static_cast<int>(left.count()));
    if (r != ReceiveResult::Frame) return r;
    const protocol::DecodeStatus status = protocol::decode(frame.data(), frame.size(), m);
    if (status == protocol::DecodeStatus::Ok) return r;
    if (status == protocol::DecodeStatus::BadVersion) foreign_version_ = frame[2];
    ++malformed_;  // counted, skipped: the next frame may be fine
  }
}

bool DeviceClient::request(Message command, Message& reply, std::string& error, int timeout_ms) {
  command.sequence = ++sequence_;
  uint8_t frame[protocol::kMaxFrame];
  const size_t n = protocol::encode(command, frame, sizeof frame);
  if (n == 0) return error = "the command does not fit in one frame", false;
  if (!transport_.send(frame, n)) return error = "the device did not take the command (disconnected?)", false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    const ReceiveResult r = left.count() > 0 ? next(reply, static_cast<int>(left.count())) : ReceiveResult::Timeout;
    if (r == ReceiveResult::Disconnected) return error = "the device disconnected", false;
    if (r == ReceiveResult::Timeout) {
      error = "no reply from the device within " + std::to_string(timeout_ms) + " ms";
      if (foreign_version_ != 0) {
        error += ": it speaks protocol version " + std::to_string(foreign_version_) + ", this ffctl version " +
                 std::to_string(protocol::kVersion) + " (flash the matching firmware)";
      }
      return false;
    }
    if (reply.sequence != command.sequence) continue;  // streamed traffic, or an older command's reply
    if (reply.type == MessageType::Error) {
      return error = std::string("the device refused the message: ") + protocol::to_string(reply.error.code), false;
    }
    switch (reply.type) {
      case MessageType::Ack: case MessageType::Status: case MessageType::Condition: case MessageType::SensorProfile:
        return true;
      default:
        break;  // streamed traffic that happens to carry the sequence
    }
  }
}

bool command(DeviceClient& client, const Message& m, std::string& error) {
  Message reply;
  if (!client.request(m, reply, error)) return false;
  if (reply.type == MessageType::Ack && reply.ack.status != protocol::AckStatus::Ok) {
    return error = "the device refused the command", false;
  }
  return true;
}

bool query_sensor_profile(DeviceClient& client, SensorProfile& profile, std::string& error) {
  Message q, reply;
  q.type = MessageType::QuerySensorProfile;
  if (!client.request(q, reply, error)) return false;
  if (reply.type != MessageType::SensorProfile) return error = "the device answered QuerySensorProfile with another message", false;
  profile = reply.sensor_profile;
  return true;
}

bool reboot_device(Transport& transport, std::string& error, bool& by_transport, int timeout_ms) {
  DeviceClient client(transport);
  Message m, reply;
  m.type = MessageType::RebootToBootloader;
  by_transport = false;
  if (client.request(m, reply, error, timeout_ms)) return true;
  if (!transport.request_bootloader()) return false;
  by_transport = true;
  return true;
}

// --- recording ---------------------------------------------------------------

namespace {

// The device's 32-bit microseconds as a 64-bit time, for values that arrive
// nearly in order (reports are stamped a little before the ticks around them).
class Unwrapper {
 public:
  uint64_t operator()(uint32_t t) {
    if (!have_) {
      have_ = true;
      newest_ = t;
      return t;
    }
    const int64_t v = static_cast<int64_t>(newest_) + static_cast<int32_t>(t - static_cast<uint32_t>(newest_));
    if (v < 0) return 0;
    if (static_cast<uint64_t>(v) > newest_) newest_ = static_cast<uint64_t>(v);
    return static_cast<uint64_t>(v);
  }

 private:
  bool have_ = false;
  uint64_t newest_ = 0;
};

}  // namespace

namespace {

// The device sends a report once a tick has taken it, within its stream's
// flush interval (~10 ms, docs/protocol.md, "Streaming"); this much device time
// past the last kept tick leaves none of that tick's reports behind.
constexpr uint64_t kReportCatchUpUs = 50000;
constexpr int kCatchUpTimeoutMs = 500;  // wall time: a device that stops streaming ends it sooner

}  // namespace

bool record(DeviceClient& client, double seconds, RecordSink& sink, std::string& error,
            const std::function<bool(const RecordProgress&)>& progress) {
  Message start, reply;
  start.type = MessageType::StartStream;  // every tick: the default decimation
  if (!client.request(start, reply, error)) return false;
  Unwrapper unwrap;
  uint64_t first = 0;
  RecordProgress p;
  // Reports of a Samples message; the newest tick that took one of them (0: unknown).
  auto keep_samples = [&](const Message& m) {
    uint64_t newest_taken = 0;
    for (int i = 0; i < m.samples.count; ++i) {
      const SensorSample& s = m.samples.samples[i];
      DeviceSample d{{unwrap(s.t_us), s.x, s.y, s.touch}, m.samples.has_taken_times, 0};
      if (d.taken_known) newest_taken = std::max(newest_taken, d.taken_us = unwrap(m.samples.taken_us[i]));
      sink.sample(d);
      p.finger = s.touch;
      p.x = s.x;
      p.y = s.y;
      ++p.samples;
    }
    return newest_taken;
  };
  bool ok = true;
  for (;;) {
    Message m;
    const ReceiveResult r = client.next(m, 1000);
    if (r == ReceiveResult::Disconnected) {
      std::string ignored;  // close() reports a failed write
      sink.flush(ignored);
      error = "the device disconnected while recording";
      return false;  // no StopStream: there is nobody to tell
    }
    if (r == ReceiveResult::Timeout) {
      error = "the device stopped streaming";
      ok = false;
      break;
    }
    if (m.type == MessageType::Samples) {
      keep_samples(m);
      continue;
    }
    if (m.type == MessageType::Force) {
      const DeviceForce f{unwrap(m.force.t_us), m.force.force_mN, m.force.over_force};
      sink.force(f);
      p.have_force = true;
      p.last_force = f;
      ++p.forces;
      continue;
    }
    if (m.type != MessageType::Ticks || m.ticks.count == 0) continue;
    for (int i = 0; i < m.ticks.count; ++i) {
      const protocol::TickRecord& t = m.ticks.ticks[i];
      const DeviceTick d{unwrap(t.t_us), t.amplitude, t.dac, t.present};
      if (p.ticks == 0) {
        first = d.t_us;
      } else if (d.t_us - p.last_tick.t_us > 3 * kTickPeriodUs / 2) {
        p.lost_ticks += static_cast<size_t>((d.t_us - p.last_tick.t_us + kTickPeriodUs / 2) / kTickPeriodUs) - 1;
      }
      sink.tick(d);
      p.last_tick = d;
      ++p.ticks;
    }
    if (!sink.flush(error)) {
      ok = false;
      break;
    }
    p.done_s = static_cast<double>(p.last_tick.t_us - first) * 1e-6;
    if (progress && !progress(p)) break;
    if (seconds > 0.0 && p.done_s >= seconds) break;
  }
  if (ok && p.ticks > 0) {
    // The reports trail the ticks by up to the flush interval: read on
    // (keeping reports, not ticks) until they have caught up with the last
    // kept tick, so that verify replays every report that tick had seen.
    for (;;) {
      Message m;
      if (client.next(m, kCatchUpTimeoutMs) != ReceiveResult::Frame) break;
      if (m.type == MessageType::Samples && keep_samples(m) >= p.last_tick.t_us) break;
      if (m.type == MessageType::Ticks && m.ticks.count > 0 &&
          unwrap(m.ticks.ticks[m.ticks.count - 1].t_us) >= p.last_tick.t_us + kReportCatchUpUs)
        break;
    }
  }
  Message stop;
  stop.type = MessageType::StopStream;
  std::string ignored;
  client.request(stop, reply, ignored);
  return sink.flush(error) && ok;
}

std::string describe(const protocol::ConditionMessage& c) {
  static const char* kinds[] = {"heightmap", "frictionmap", "neutral", "general scene"};
  static const char* targets[] = {"top", "middle", "bottom"};
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s, target %s, strength %.3g, idle amplitude %.3g, S-curve %.3g%s",
                kinds[static_cast<int>(c.kind)], targets[static_cast<int>(c.target)], static_cast<double>(c.strength),
                static_cast<double>(c.idle_amplitude), static_cast<double>(c.s_curve),
                c.calibration.code[0] > c.calibration.code[c.calibration.count - 1] ? ", decreasing DAC calibration" : "");
  return buf;
}

std::string describe(const SensorProfile& p) {
  char hz[32] = "";  // the frequency only where it was measured
  if (p.tremor_hz > 0.0f) std::snprintf(hz, sizeof hz, " at %.3g Hz", static_cast<double>(p.tremor_hz));
  char buf[280];
  std::snprintf(buf, sizeof buf,
                "white noise %.3g px, wander %.3g px over %.3g ms, tremor %.3g px%s, %.4g reports/s +- %.3g us, "
                "latency %u us",
                static_cast<double>(p.white_noise_px), static_cast<double>(p.correlated_noise_px),
                static_cast<double>(p.correlation_time_ms), static_cast<double>(p.tremor_px), hz,
                static_cast<double>(p.report_rate_hz), static_cast<double>(p.jitter_us),
                static_cast<unsigned>(p.latency_us));
  return buf;
}

TrackerConfig tracker_config_of(const Recording& r) {
  return r.has_sensor_profile ? TrackerConfig::recommended(r.sensor_profile) : TrackerConfig::recommended();
}

namespace {

// run1.csv -> run1; a name without the suffix is its own stem (a ".csv" inside a folder's name is not the suffix).
std::string stem_of(const std::string& trace_path) {
  const std::string suffix = ".csv";
  const bool has_suffix = trace_path.size() > suffix.size() &&
                          trace_path.compare(trace_path.size() - suffix.size(), suffix.size(), suffix) == 0;
  return has_suffix ? trace_path.substr(0, trace_path.size() - suffix.size()) : trace_path;
}

// `m` as a hex frame line after `# ` comment lines: exact, and the codec checks it on the way back.
// Written whole or not at all (a killed recorder leaves the old file or none).
bool write_frame_file(const std::string& path, const Message& m, const std::vector<std::string>& comments,
                      std::string& error) {
  uint8_t frame[protocol::kMaxFrame];
  const size_t n = protocol::encode(m, frame, sizeof frame);
  std::ostringstream out;
  for (const std::string& line : comments) out << "# " << line << "\n";
  out << "frame ";
  char hex[3];
  for (size_t i = 0; i < n; ++i) {
    std::snprintf(hex, sizeof hex, "%02x", frame[i]);
    out << hex;
  }
  out << "\n";
  if (n == 0) return error = "cannot encode the frame for " + path, false;  // a guard: what came over the protocol fits
  return host::write_file_atomically(path, out.str(), error);
}

// The frame line of a file write_frame_file() wrote, which must hold a message of `type`.
bool read_frame_file(const std::string& path, MessageType type, const char* what, Message& m, std::string& error) {
  std::ifstream in;
  std::string why;
  if (!host::open_input_file(path, in, why)) return error = path + ": " + why, false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("frame ", 0) != 0) continue;
    std::vector<uint8_t> frame;
    for (size_t i = 6; i + 1 < line.size() && line[i] != '\r'; i += 2) {
      unsigned byte = 0;
      if (std::sscanf(line.c_str() + i, "%2x", &byte) != 1) return error = path + ": bad hex in the frame line", false;
      frame.push_back(static_cast<uint8_t>(byte));
    }
    const protocol::DecodeStatus st = protocol::decode(frame.data(), frame.size(), m);
    if (st != protocol::DecodeStatus::Ok || m.type != type) {
      return error = path + ": not a " + what + " frame (" + protocol::to_string(st) + ")", false;
    }
    return true;
  }
  return error = path + ": no frame line", false;
}

// The condition as the SetCondition frame that sets it.
bool write_condition(const std::string& path, const protocol::ConditionMessage& c, std::string& error) {
  Message m;
  m.type = MessageType::SetCondition;
  m.condition = c;
  std::vector<std::string> comments = {"The condition the device rendered while ffctl recorded (ffctl verify reads it).",
                                       describe(c)};
  if (c.kind == protocol::ConditionKind::General) {
    std::istringstream scene(host::format_scene_text(c.scene));
    for (std::string line; std::getline(scene, line);) comments.push_back("  " + line);
  }
  return write_frame_file(path, m, comments, error);
}

bool read_condition(const std::string& path, protocol::ConditionMessage& c, std::string& error) {
  Message m;
  if (!read_frame_file(path, MessageType::SetCondition, "condition", m, error)) return false;
  c = m.condition;
  return true;
}

// The profile as the SetSensorProfile frame that sets it.
bool write_sensor_profile(const std::string& path, const SensorProfile& p, std::string& error) {
  Message m;
  m.type = MessageType::SetSensorProfile;
  m.sensor_profile = p;
  return write_frame_file(path, m,
                          {"The sensor profile the device's tracker used while ffctl recorded (ffctl verify replays "
                           "with it).",
                           describe(p), "ffctl sensor-profile " + host::sensor_profile_flags(p)},
                          error);
}

bool read_sensor_profile(const std::string& path, SensorProfile& p, std::string& error) {
  Message m;
  if (!read_frame_file(path, MessageType::SetSensorProfile, "sensor profile", m, error)) return false;
  if (!is_valid(m.sensor_profile)) return error = path + ": the profile is outside SensorProfileLimits", false;
  p = m.sensor_profile;
  return true;
}

}  // namespace

std::string ticks_path_for(const std::string& trace_path) { return stem_of(trace_path) + ".ticks.csv"; }
std::string force_path_for(const std::string& trace_path) { return stem_of(trace_path) + ".force.csv"; }
std::string condition_path_for(const std::string& trace_path) { return stem_of(trace_path) + ".condition"; }
std::string sensor_profile_path_for(const std::string& trace_path) { return stem_of(trace_path) + ".sensor-profile"; }

bool check_output_path(const std::string& trace_path, std::string& error) {
  if (trace_path.empty()) return error = "-o: no file name", false;
  const std::string several_files =
      ": a recording is several files named after it (NAME.csv, NAME.ticks.csv, NAME.force.csv); give a file name "
      "such as run1.csv";
  if (trace_path == "-") return error = "-o -" + several_files, false;
  struct stat st{};
  if (::stat(trace_path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) {
    return error = "-o " + trace_path + ": is a folder; give a file name such as " + trace_path + "/run1.csv", false;
  }
  if (::stat(trace_path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    return error = "-o " + trace_path + ": not a regular file" + several_files, false;  // /dev/null.ticks.csv in /dev
  }
  const size_t slash = trace_path.rfind('/');
  const std::string folder = slash == std::string::npos ? "." : trace_path.substr(0, slash == 0 ? 1 : slash);
  if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    return error = "-o " + trace_path + ": the folder " + folder + " does not exist", false;
  }
  if (::access(folder.c_str(), W_OK) != 0) return error = "-o " + trace_path + ": the folder " + folder + " is not writable", false;
  return true;
}

RecordingWriter::~RecordingWriter() {
  for (std::FILE* f : files_) {
    if (f) std::fclose(f);
  }
}

bool RecordingWriter::note_failure(File f) {
  if (failure_.empty()) failure_ = host::cannot_write(names_[f], errno);
  return false;
}

namespace {
constexpr const char* kTicksHeader = "t_us,amplitude,dac,present";
}  // namespace

bool RecordingWriter::open(const std::string& path, const std::vector<std::string>& metadata, const Recording& r,
                           std::string& error) {
  names_[kTrace] = path;
  names_[kTicks] = ticks_path_for(path);
  names_[kForce] = force_path_for(path);
  const std::string headers[kFiles] = {"t_us,x,y,touch,taken_us\n", std::string(kTicksHeader) + "\n",
                                       "t_us,force_mN,over_force\n"};
  for (int i = 0; i < kFiles; ++i) {
    files_[i] = std::fopen(names_[i].c_str(), "w");
    if (!files_[i]) return note_failure(static_cast<File>(i)), error = failure_, false;
    // Large buffers, flushed explicitly after whole rows: a kill never leaves half a row.
    buffers_[i] = std::make_unique<char[]>(kBufferBytes);
    std::setvbuf(files_[i], buffers_[i].get(), _IOFBF, kBufferBytes);
    for (const std::string& line : metadata) std::fprintf(files_[i], "# %s\n", line.c_str());
    std::fputs(headers[i].c_str(), files_[i]);
  }
  if (!flush(error)) return false;
  // A stale one would mislead verify.
  if (!r.has_condition) std::remove(condition_path_for(path).c_str());
  if (!r.has_sensor_profile) std::remove(sensor_profile_path_for(path).c_str());
  return (!r.has_condition || write_condition(condition_path_for(path), r.condition, error)) &&
         (!r.has_sensor_profile || write_sensor_profile(sensor_profile_path_for(path), r.sensor_profile, error));
}

void RecordingWriter::sample(const DeviceSample& s) {
  std::fprintf(files_[kTrace], "%llu,%.9g,%.9g,%d,%lld\n", static_cast<unsigned long long>(s.row.t_us),
               static_cast<double>(s.row.x), static_cast<double>(s.row.y), s.row.touch ? 1 : 0,
               s.taken_known ? static_cast<long long>(s.taken_us) : -1LL);
}

void RecordingWriter::tick(const DeviceTick& t) {
  std::fprintf(files_[kTicks], "%llu,%.9g,%u,%d\n", static_cast<unsigned long long>(t.t_us),
               static_cast<double>(t.amplitude), static_cast<unsigned>(t.dac), t.present ? 1 : 0);
}

void RecordingWriter::force(const DeviceForce& f) {
  std::fprintf(files_[kForce], "%llu,%.9g,%d\n", static_cast<unsigned long long>(f.t_us),
               static_cast<double>(f.force_mN), f.over_force ? 1 : 0);
}

bool RecordingWriter::flush(std::string& error) {
  for (int i = 0; i < kFiles; ++i) {
    // ferror: a write when a row filled the buffer failed (between flushes, more than 1 MiB of rows).
    if (files_[i] && (std::fflush(files_[i]) != 0 || std::ferror(files_[i]))) note_failure(static_cast<File>(i));
  }
  return failure_.empty() || (error = failure_, false);
}

bool RecordingWriter::close(std::string& error) {
  flush(error);  // fclose() would flush too, but not report an earlier failed write (ferror)
  for (int i = 0; i < kFiles; ++i) {
    if (files_[i] && std::fclose(files_[i]) != 0) note_failure(static_cast<File>(i));
    files_[i] = nullptr;
  }
  return failure_.empty() || (error = failure_, false);
}

bool write_recording(const std::string& path, const Recording& r, std::string& error,
                     const std::vector<std::string>& metadata) {
  RecordingWriter w;
  if (!w.open(path, metadata, r, error)) return false;
  for (const DeviceSample& s : r.samples) w.sample(s);
  for (const DeviceTick& t : r.ticks) w.tick(t);
  for (const DeviceForce& f : r.forces) w.force(f);
  return w.close(error);
}

namespace {

// The sensor trace of a recording, with the device's taken_us where ffctl
// wrote it (-1: unknown; a plain sensor trace has no such column).
bool read_samples(const std::string& path, std::vector<DeviceSample>& samples, std::string& error) {
  std::ifstream in;
  std::string why;
  if (!host::open_input_file(path, in, why)) return error = path + ": " + why, false;
  host::SensorTraceReader reader(in);
  host::TraceError terr;
  if (!reader.read_header(terr)) return error = terr.to_string(path), false;
  for (host::TraceRow row; reader.next(row, terr);) {
    DeviceSample s{row, row.taken_us >= 0, row.taken_us >= 0 ? static_cast<uint64_t>(row.taken_us) : 0};
    samples.push_back(s);
  }
  return terr.message.empty() || (error = terr.to_string(path), false);
}

// NAME.ticks.csv: a header, then t_us,amplitude,dac,present per row; '#' and
// blank lines anywhere are skipped, as in every trace file.
bool read_ticks(const std::string& path, std::vector<DeviceTick>& ticks, std::string& error) {
  std::ifstream in;
  std::string why;
  if (!host::open_input_file(path, in, why)) {
    return error = path + ": " + why + " (ffctl record writes it next to the trace)", false;
  }
  bool header_seen = false;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    line.erase(line.find_last_not_of(" \t\r") + 1);  // Windows line ends
    if (!header_seen) {  // a file without it would lose its first tick as the header
      header_seen = true;
      if (line.substr(first) != kTicksHeader) {
        return error = path + ":" + std::to_string(line_no) + ": expected the header " + kTicksHeader, false;
      }
      continue;
    }
    unsigned long long time = 0;
    unsigned dac = 0;
    int present = 0;
    float amp = 0.0f;
    char tail = 0;
    if (!std::isdigit(static_cast<unsigned char>(line[first])) ||  // %llu would take "-5" as a huge time
        std::sscanf(line.c_str(), "%llu,%f,%u,%d%c", &time, &amp, &dac, &present, &tail) != 4 || dac > 4095 ||
        present < 0 || present > 1 || !std::isfinite(amp)) {
      return error = path + ":" + std::to_string(line_no) + ": expected t_us,amplitude,dac,present", false;
    }
    if (!ticks.empty() && time <= ticks.back().t_us) {
      return error = path + ":" + std::to_string(line_no) + ": tick times must increase", false;
    }
    ticks.push_back({time, amp, static_cast<uint16_t>(dac), present != 0});
  }
  return true;
}

}  // namespace

bool read_recording(const std::string& path, Recording& r, std::string& error) {
  if (!read_samples(path, r.samples, error) || !read_ticks(ticks_path_for(path), r.ticks, error)) return false;
  const std::string cpath = condition_path_for(path);
  r.has_condition = std::ifstream(cpath).good();
  if (r.has_condition && !read_condition(cpath, r.condition, error)) return false;
  const std::string ppath = sensor_profile_path_for(path);
  r.has_sensor_profile = std::ifstream(ppath).good();
  return !r.has_sensor_profile || read_sensor_profile(ppath, r.sensor_profile, error);
}

// --- verification ------------------------------------------------------------

namespace {

VerifyResult replay(const Recording& r, const Condition& condition, const TrackerConfig& tracker, bool compare_all) {
  VerifyResult v;
  auto pipeline = std::make_unique<HapticPipeline>(tracker);
  if (pipeline->set_condition(condition) != PrepareStatus::Ok) return v;
  v.prepared = true;
  v.exact_alignment = !r.samples.empty();
  for (const DeviceSample& s : r.samples) v.exact_alignment = v.exact_alignment && s.taken_known;

  size_t next = 0;
  bool synchronised = false;
  bool in_run = false;
  uint64_t previous_t = 0;
  for (size_t i = 0; i < r.ticks.size(); ++i) {
    const DeviceTick& t = r.ticks[i];
    if (i > 0 && t.t_us - previous_t > 3 * kTickPeriodUs / 2) {
      // Ticks missing from the stream: the states may part; compare again
      // once neither side has a finger.
      v.missing_ticks += static_cast<size_t>((t.t_us - previous_t + kTickPeriodUs / 2) / kTickPeriodUs) - 1;
      synchronised = false;
    }
    previous_t = t.t_us;
    // Every report this tick (or a tick missing from the stream) took.
    for (; next < r.samples.size(); ++next) {
      const DeviceSample& s = r.samples[next];
      if ((s.taken_known ? s.taken_us : s.row.t_us) > t.t_us) break;
      pipeline->post_sample({static_cast<uint32_t>(s.row.t_us), s.row.x, s.row.y, s.row.touch});
    }
    const TickOutput out = pipeline->tick(static_cast<uint32_t>(t.t_us));
    if (!synchronised && (compare_all || (!t.present && !out.present))) {
      synchronised = true;
      v.synchronised = !compare_all;
    }
    if (!synchronised) {
      ++v.warm_up;
      in_run = false;
      continue;
    }
    ++v.compared;
    const float da = std::fabs(out.amplitude - t.amplitude);
    const int dd = std::abs(static_cast<int>(out.dac) - static_cast<int>(t.dac));
    v.max_amplitude_difference = std::fmax(v.max_amplitude_difference, da);
    v.max_dac_difference = std::max(v.max_dac_difference, dd);
    const bool presence = out.present != t.present;
    if (dd <= 1 && !presence) {
      in_run = false;
      continue;
    }
    ++v.beyond_one_code;
    if (presence) ++v.presence_mismatches;
    const Mismatch m{t.t_us, t.amplitude, out.amplitude, t.dac, out.dac, t.present, out.present};
    if (!in_run) {
      in_run = true;
      ++v.run_count;
      if (v.runs.size() < kMaxRuns) v.runs.push_back({0, t.t_us, t.t_us, -1, m, m});
    }
    if (v.run_count <= kMaxRuns) {
      MismatchRun& run = v.runs.back();
      ++run.ticks;
      run.last_t_us = t.t_us;
      if (dd > run.max_dac_difference) {
        run.max_dac_difference = dd;
        run.worst = m;
      }
    }
  }
  return v;
}

}  // namespace

VerifyResult verify(const Recording& r, const Condition& condition, const TrackerConfig& tracker) {
  VerifyResult v = replay(r, condition, tracker, false);
  if (v.prepared && !v.synchronised) v = replay(r, condition, tracker, true);
  v.recorded = r.ticks.size();
  return v;
}

bool verify_passed(const VerifyResult& v, double min_coverage) {
  return v.prepared && v.compared > 0 && v.beyond_one_code == 0 && v.coverage() >= min_coverage;
}

}  // namespace ff::ffctl
