#include "frictionfield/protocol/codec.hpp"

#include <initializer_list>
#include <new>
#include <type_traits>

#include "frictionfield/core/scenes.hpp"
#include "wire.hpp"

namespace ff::protocol {

const char* to_string(DecodeStatus s) {
  switch (s) {
    case DecodeStatus::Ok: return "ok";
    case DecodeStatus::TooShort: return "too short";
    case DecodeStatus::BadMagic: return "bad magic";
    case DecodeStatus::BadVersion: return "unsupported version";
    case DecodeStatus::BadLength: return "length does not match";
    case DecodeStatus::BadCrc: return "CRC mismatch";
    case DecodeStatus::UnknownType: return "unknown message type";
    case DecodeStatus::Malformed: return "malformed payload";
  }
  return "?";
}

const char* to_string(ErrorCode c) {
  switch (c) {
    case ErrorCode::TooShort: return "frame too short";
    case ErrorCode::BadMagic: return "bad magic";
    case ErrorCode::BadVersion: return "unsupported protocol version";
    case ErrorCode::BadLength: return "length does not match";
    case ErrorCode::BadCrc: return "CRC mismatch";
    case ErrorCode::UnknownType: return "unknown message type";
    case ErrorCode::Malformed: return "malformed payload";
    case ErrorCode::Busy: return "busy";
  }
  return "unknown error code";
}

ErrorCode error_code_for(DecodeStatus s) {
  switch (s) {
    case DecodeStatus::TooShort: return ErrorCode::TooShort;
    case DecodeStatus::BadMagic: return ErrorCode::BadMagic;
    case DecodeStatus::BadVersion: return ErrorCode::BadVersion;
    case DecodeStatus::BadLength: return ErrorCode::BadLength;
    case DecodeStatus::BadCrc: return ErrorCode::BadCrc;
    case DecodeStatus::UnknownType: return ErrorCode::UnknownType;
    default: return ErrorCode::Malformed;
  }
}

uint16_t crc16_ccitt(const uint8_t* data, size_t size, uint16_t crc) {
  for (size_t i = 0; i < size; ++i) {
    crc ^= static_cast<uint16_t>(data[i] << 8);
    for (int b = 0; b < 8; ++b) crc = (crc & 0x8000u) ? static_cast<uint16_t>((crc << 1) ^ 0x1021u) : static_cast<uint16_t>(crc << 1);
  }
  return crc;
}

Condition ConditionMessage::to_condition() const {
  Condition c;
  switch (kind) {
    case ConditionKind::Heightmap: c.scene = scenes::heightmap(target); break;
    case ConditionKind::Frictionmap: c.scene = scenes::frictionmap(target); break;
    case ConditionKind::Neutral: c.scene = scenes::neutral(); break;
    case ConditionKind::General: c.scene = scene; c.scene.sampled = SampledHeightMap{}; break;
  }
  c.amplitude.strength = strength;
  c.amplitude.idle_amplitude = idle_amplitude;
  c.amplitude.s_curve = s_curve;
  c.amplitude.calibration = calibration;
  return c;
}

namespace {

// `x = T()` may build the T on the stack first and copy it; constructing in
// place does not (every message type is plain data).
template <class T>
void reset_in_place(T& x) {
  static_assert(std::is_trivially_destructible_v<T>, "plain data only");
  ::new (static_cast<void*>(&x)) T();
}

// --- scenes ------------------------------------------------------------------

void put_vec(WireWriter& w, Vec2 v) { w.f32(v.x); w.f32(v.y); }
Vec2 get_vec(WireReader& r) { const float x = r.f32(); return {x, r.f32()}; }

void put_element(WireWriter& w, const FieldElement& e) {
  w.u8(static_cast<uint8_t>(e.kind));
  w.f32(e.weight);
  switch (e.kind) {
    case ElementKind::PointSink:
      put_vec(w, e.point.centre);
      w.f32(e.point.radius);
      w.f32(e.point.feather);
      break;
    case ElementKind::Vortex:
    case ElementKind::Saddle:
      put_vec(w, e.point.centre);
      break;
    case ElementKind::PathSink: {
      const PathCurve& c = e.valley.curve;
      w.u8(static_cast<uint8_t>(c.kind));
      if (c.kind == CurveKind::Polyline) {
        w.u8(c.count);
        for (int i = 0; i < c.count; ++i) put_vec(w, c.points[i]);
      } else {
        w.f32(c.x0); w.f32(c.y0); w.f32(c.length); w.f32(c.rise); w.f32(c.amplitude); w.f32(c.wavelength);
      }
      w.f32(e.valley.a);
      w.f32(e.valley.band_half_width);
      w.f32(e.valley.band_feather);
      break;
    }
    case ElementKind::Tunnel:
      w.f32(e.tunnel.x_start); w.f32(e.tunnel.length); w.f32(e.tunnel.width_start);
      w.f32(e.tunnel.width_end); w.f32(e.tunnel.scale); w.f32(e.tunnel.y_centre);
      break;
    case ElementKind::Texture:
      w.f32(e.texture.wavelength_x); w.f32(e.texture.wavelength_y); w.f32(e.texture.height);
      break;
  }
}

bool get_element(WireReader& r, FieldElement& e) {
  const uint8_t kind = r.u8();
  if (kind > static_cast<uint8_t>(ElementKind::Texture)) return false;
  e.kind = static_cast<ElementKind>(kind);
  e.weight = r.f32();
  switch (e.kind) {
    case ElementKind::PointSink:
      e.point.centre = get_vec(r);
      e.point.radius = r.f32();
      e.point.feather = r.f32();
      break;
    case ElementKind::Vortex:
    case ElementKind::Saddle:
      e.point.centre = get_vec(r);
      break;
    case ElementKind::PathSink: {
      PathCurve& c = e.valley.curve;
      const uint8_t ck = r.u8();
      if (ck > static_cast<uint8_t>(CurveKind::Polyline)) return false;
      c.kind = static_cast<CurveKind>(ck);
      if (c.kind == CurveKind::Polyline) {
        c.count = r.u8();
        if (c.count > kMaxPolylinePoints) return false;
        for (int i = 0; i < c.count; ++i) c.points[i] = get_vec(r);
      } else {
        c.x0 = r.f32(); c.y0 = r.f32(); c.length = r.f32(); c.rise = r.f32(); c.amplitude = r.f32(); c.wavelength = r.f32();
      }
      e.valley.a = r.f32();
      e.valley.band_half_width = r.f32();
      e.valley.band_feather = r.f32();
      break;
    }
    case ElementKind::Tunnel:
      e.tunnel.x_start = r.f32(); e.tunnel.length = r.f32(); e.tunnel.width_start = r.f32();
      e.tunnel.width_end = r.f32(); e.tunnel.scale = r.f32(); e.tunnel.y_centre = r.f32();
      break;
    case ElementKind::Texture:
      e.texture.wavelength_x = r.f32(); e.texture.wavelength_y = r.f32(); e.texture.height = r.f32();
      break;
  }
  return r.ok();
}

void put_scene(WireWriter& w, const SceneDefinition& s) {
  w.u8(static_cast<uint8_t>(s.rendering));
  w.f32(s.constant);
  w.f32(s.bias);
  w.u8(static_cast<uint8_t>(s.evaluation));
  w.f32(s.table.spacing_px);
  w.u8(static_cast<uint8_t>(s.table.storage));
  w.u8(static_cast<uint8_t>(s.table.source));
  w.u8(s.element_count);
  for (int i = 0; i < s.element_count && i < kMaxSceneElements; ++i) put_element(w, s.elements[i]);
}

// The get_* functions read into a message decode() has just reset.
bool get_scene(WireReader& r, SceneDefinition& s) {
  const uint8_t rendering = r.u8();
  s.constant = r.f32();
  s.bias = r.f32();
  const uint8_t evaluation = r.u8();
  s.table.spacing_px = r.f32();
  const uint8_t storage = r.u8(), source = r.u8();
  const uint8_t count = r.u8();
  if (rendering > 2 || evaluation > 1 || storage > 1 || source > 1 || count > kMaxSceneElements) return false;
  s.rendering = static_cast<Rendering>(rendering);
  s.evaluation = static_cast<Evaluation>(evaluation);
  s.table.storage = static_cast<TableStorage>(storage);
  s.table.source = static_cast<TableSource>(source);
  for (int i = 0; i < count; ++i) {
    if (!get_element(r, s.elements[i])) return false;
  }
  s.element_count = count;
  return r.ok();
}

// --- conditions --------------------------------------------------------------

void put_condition(WireWriter& w, const ConditionMessage& c) {
  w.u8(static_cast<uint8_t>(c.kind));
  w.u8(static_cast<uint8_t>(c.target));
  w.f32(c.strength);
  w.f32(c.idle_amplitude);
  w.f32(c.s_curve);
  const DacCalibration& cal = c.calibration;
  w.u8(cal.count);
  for (int i = 0; i < cal.count && i < kMaxCalibrationPoints; ++i) {
    w.f32(cal.amplitude[i]);
    w.f32(cal.code[i]);
  }
  if (c.kind == ConditionKind::General) put_scene(w, c.scene);
}

// Values the core would have to repair (strength outside (0, 1], a
// non-monotonic calibration) make the message malformed: refused, not repaired.
bool get_condition(WireReader& r, ConditionMessage& c) {
  const uint8_t kind = r.u8(), target = r.u8();
  if (kind > 3 || target > 2) return false;
  c.kind = static_cast<ConditionKind>(kind);
  c.target = static_cast<Target>(target);
  c.strength = r.f32();
  c.idle_amplitude = r.f32();
  c.s_curve = r.f32();
  const uint8_t points = r.u8();
  if (points < 2 || points > kMaxCalibrationPoints) return false;
  c.calibration.count = points;
  for (int i = 0; i < points; ++i) {
    c.calibration.amplitude[i] = r.f32();
    c.calibration.code[i] = r.f32();
  }
  if (!r.ok()) return false;
  if (!(c.strength > 0.0f && c.strength <= 1.0f) || !(c.idle_amplitude >= 0.0f && c.idle_amplitude <= 1.0f) ||
      !(c.s_curve >= 0.0f && c.s_curve <= 1.0f) || !c.calibration.valid()) {
    return false;
  }
  if (c.kind == ConditionKind::General && !get_scene(r, c.scene)) return false;
  return r.ok();
}

// --- sensor profiles -----------------------------------------------------------

void put_profile(WireWriter& w, const SensorProfile& p) {
  w.f32(p.white_noise_px);
  w.f32(p.correlated_noise_px);
  w.f32(p.correlation_time_ms);
  w.f32(p.tremor_px);
  w.f32(p.report_rate_hz);
  w.f32(p.jitter_us);
  w.u32(p.latency_us);
  w.f32(p.tremor_hz);
}

// Any finite values: whether the tracker can use them is the device's to
// judge (is_valid), answered with Ack refused, as a scene's ranges are. The
// tremor's frequency came later: a profile without it has not measured it.
void get_profile(WireReader& r, SensorProfile& p) {
  p.white_noise_px = r.f32();
  p.correlated_noise_px = r.f32();
  p.correlation_time_ms = r.f32();
  p.tremor_px = r.f32();
  p.report_rate_hz = r.f32();
  p.jitter_us = r.f32();
  p.latency_us = r.u32();
  p.tremor_hz = r.at_end() ? 0.0f : r.f32();
}

// --- payloads ----------------------------------------------------------------

void put_payload(WireWriter& w, const Message& m) {
  switch (m.type) {
    case MessageType::SetCondition:
    case MessageType::Condition:
      put_condition(w, m.condition);
      break;
    case MessageType::SetSensorProfile:
    case MessageType::SensorProfile:
      put_profile(w, m.sensor_profile);
      break;
    case MessageType::QueryStatus:
    case MessageType::StopStream:
    case MessageType::RebootToBootloader:
    case MessageType::QueryCondition:
    case MessageType::QuerySensorProfile:
      break;
    case MessageType::StartStream:
      w.u8(m.stream.tick_decimation);
      break;
    case MessageType::SetCarrier:
      w.f32(m.carrier.frequency_hz);
      break;
    case MessageType::StartSweep:
      w.f32(m.sweep.start_hz);
      w.f32(m.sweep.end_hz);
      w.u32(m.sweep.duration_ms);
      break;
    case MessageType::Ack:
      w.u8(static_cast<uint8_t>(m.ack.command));
      w.u8(static_cast<uint8_t>(m.ack.status));
      w.u8(m.ack.detail);
      break;
    case MessageType::Status: {
      const StatusMessage& s = m.status;
      w.u16(s.firmware_version);
      w.u8(static_cast<uint8_t>(s.kind));
      w.u8(static_cast<uint8_t>(s.target));
      w.f32(s.strength);
      w.u32(s.ticks);
      w.u32(s.tick_cycles_mean);
      w.u32(s.tick_cycles_max);
      w.u32(s.protocol_errors);
      w.u32(s.watchdog_trips);
      w.u32(s.stream_overruns);
      w.f32(s.force_mN);
      w.u8(static_cast<uint8_t>((s.over_force ? 1 : 0) | (s.finger_present ? 2 : 0)));
      w.f32(s.carrier_hz);
      for (uint32_t v : {s.isr_cycles_mean, s.isr_cycles_max, s.isr_cycles_p99, s.prepare_us_last, s.loop_pass_max_us,
                         s.zforce_layout_beside, s.zforce_layout_inside}) {
        w.u32(v);
      }
      w.u8(static_cast<uint8_t>(Fault::kCount));
      for (int i = 0; i < static_cast<int>(Fault::kCount); ++i) w.u32(s.faults.count[i]);
      w.u8(static_cast<uint8_t>(DeviceCount::kCount));
      for (uint32_t v : s.device.count) w.u32(v);
      w.u8(static_cast<uint8_t>(s.sensor_state));
      const uint8_t n = s.sensor_count_n < kMaxSensorCounts ? s.sensor_count_n : kMaxSensorCounts;
      w.u8(n);
      for (int i = 0; i < n; ++i) w.u32(s.sensor_counts[i]);
      break;
    }
    case MessageType::Force:
      w.u32(m.force.t_us);
      w.f32(m.force.force_mN);
      w.u8(m.force.over_force ? 1 : 0);
      break;
    case MessageType::Samples:
      w.u8(m.samples.count);
      w.u8(m.samples.has_taken_times ? 1 : 0);
      for (int i = 0; i < m.samples.count && i < kMaxSamplesPerMessage; ++i) {
        const SensorSample& s = m.samples.samples[i];
        w.u32(s.t_us);
        w.f32(s.x);
        w.f32(s.y);
        w.u8(s.touch ? 1 : 0);
        if (m.samples.has_taken_times) w.u32(m.samples.taken_us[i]);
      }
      break;
    case MessageType::Ticks:
      w.u8(m.ticks.count);
      for (int i = 0; i < m.ticks.count && i < kMaxTicksPerMessage; ++i) {
        const TickRecord& t = m.ticks.ticks[i];
        w.u32(t.t_us);
        w.f32(t.amplitude);
        w.u16(static_cast<uint16_t>((t.dac & 0x0FFFu) | (t.present ? 0x8000u : 0u)));
      }
      break;
    case MessageType::Error:
      w.u8(static_cast<uint8_t>(m.error.code));
      w.u8(m.error.type);
      break;
  }
}

bool known_type(uint8_t t) {
  switch (static_cast<MessageType>(t)) {
    case MessageType::SetCondition: case MessageType::QueryStatus: case MessageType::StartStream:
    case MessageType::StopStream: case MessageType::SetCarrier: case MessageType::StartSweep:
    case MessageType::RebootToBootloader: case MessageType::QueryCondition: case MessageType::SetSensorProfile:
    case MessageType::QuerySensorProfile: case MessageType::Ack: case MessageType::Status: case MessageType::Force:
    case MessageType::Samples: case MessageType::Ticks: case MessageType::Condition: case MessageType::SensorProfile:
    case MessageType::Error:
      return true;
  }
  return false;
}

bool get_payload(WireReader& r, Message& m) {
  switch (m.type) {
    case MessageType::SetCondition:
    case MessageType::Condition:
      return get_condition(r, m.condition);
    case MessageType::SetSensorProfile:
    case MessageType::SensorProfile:
      get_profile(r, m.sensor_profile);
      return true;
    case MessageType::QueryStatus:
    case MessageType::StopStream:
    case MessageType::RebootToBootloader:
    case MessageType::QueryCondition:
    case MessageType::QuerySensorProfile:
      return true;
    case MessageType::StartStream:
      m.stream.tick_decimation = r.u8();
      return m.stream.tick_decimation >= 1;
    case MessageType::SetCarrier:
      m.carrier.frequency_hz = r.f32();
      return true;
    case MessageType::StartSweep:
      m.sweep.start_hz = r.f32();
      m.sweep.end_hz = r.f32();
      m.sweep.duration_ms = r.u32();
      return true;
    case MessageType::Ack: {
      const uint8_t command = r.u8(), status = r.u8();
      m.ack.command = static_cast<MessageType>(command);
      m.ack.status = static_cast<AckStatus>(status);
      m.ack.detail = r.u8();
      return known_type(command) && status <= 1;
    }
    case MessageType::Status: {
      StatusMessage& s = m.status;
      s.firmware_version = r.u16();
      const uint8_t kind = r.u8(), target = r.u8();
      if (kind > 3 || target > 2) return false;
      s.kind = static_cast<ConditionKind>(kind);
      s.target = static_cast<Target>(target);
      s.strength = r.f32();
      s.ticks = r.u32();
      s.tick_cycles_mean = r.u32();
      s.tick_cycles_max = r.u32();
      s.protocol_errors = r.u32();
      s.watchdog_trips = r.u32();
      s.stream_overruns = r.u32();
      s.force_mN = r.f32();
      const uint8_t flags = r.u8();
      if (flags > 3) return false;
      s.over_force = flags & 1;
      s.finger_present = flags & 2;
      s.carrier_hz = r.f32();
      for (uint32_t* v : {&s.isr_cycles_mean, &s.isr_cycles_max, &s.isr_cycles_p99, &s.prepare_us_last,
                          &s.loop_pass_max_us, &s.zforce_layout_beside, &s.zforce_layout_inside}) {
        *v = r.u32();
      }
      const uint8_t n = r.u8();  // newer firmware may count more faults: keep what we know
      for (int i = 0; i < n; ++i) {
        const uint32_t v = r.u32();
        if (i < static_cast<int>(Fault::kCount)) s.faults.count[i] = v;
      }
      if (r.at_end()) return true;  // firmware 1.0 ends here: state unknown, no counts (as reset)
      const uint8_t devices = r.u8();  // a newer firmware may count more: keep what we know
      for (int i = 0; i < devices; ++i) {
        const uint32_t v = r.u32();
        if (i < static_cast<int>(DeviceCount::kCount)) s.device.count[i] = v;
      }
      const uint8_t state = r.u8();
      if (state > static_cast<uint8_t>(SensorState::Unknown)) return false;
      s.sensor_state = static_cast<SensorState>(state);
      const uint8_t sensor = r.u8();
      for (int i = 0; i < sensor; ++i) {
        const uint32_t v = r.u32();
        if (i < kMaxSensorCounts) s.sensor_counts[i] = v;
      }
      s.sensor_count_n = sensor < kMaxSensorCounts ? sensor : kMaxSensorCounts;
      return true;
    }
    case MessageType::Force: {
      m.force.t_us = r.u32();
      m.force.force_mN = r.f32();
      const uint8_t over = r.u8();
      m.force.over_force = over == 1;
      return over <= 1;
    }
    case MessageType::Samples: {
      m.samples.count = r.u8();
      const uint8_t flags = r.u8();
      if (m.samples.count > kMaxSamplesPerMessage || flags > 1) return false;
      m.samples.has_taken_times = flags == 1;
      for (int i = 0; i < m.samples.count; ++i) {
        SensorSample& s = m.samples.samples[i];
        s.t_us = r.u32();
        s.x = r.f32();
        s.y = r.f32();
        const uint8_t touch = r.u8();
        if (touch > 1) return false;
        s.touch = touch == 1;
        if (m.samples.has_taken_times) m.samples.taken_us[i] = r.u32();
      }
      return true;
    }
    case MessageType::Ticks:
      m.ticks.count = r.u8();
      if (m.ticks.count > kMaxTicksPerMessage) return false;
      for (int i = 0; i < m.ticks.count; ++i) {
        TickRecord& t = m.ticks.ticks[i];
        t.t_us = r.u32();
        t.amplitude = r.f32();
        const uint16_t d = r.u16();
        t.dac = d & 0x0FFFu;
        t.present = (d & 0x8000u) != 0;
        if ((d & 0x7000u) != 0) return false;
      }
      return true;
    case MessageType::Error: {
      const uint8_t code = r.u8();
      m.error.code = static_cast<ErrorCode>(code);
      m.error.type = r.u8();
      return code >= static_cast<uint8_t>(ErrorCode::TooShort) && code <= static_cast<uint8_t>(ErrorCode::Busy);
    }
  }
  return false;
}

}  // namespace

size_t encode(const Message& m, uint8_t* out, size_t capacity) {
  if (out == nullptr || capacity < kHeaderBytes + kCrcBytes) return 0;
  WireWriter payload(out + kHeaderBytes, capacity - kHeaderBytes - kCrcBytes);
  put_payload(payload, m);
  if (!payload.ok() || payload.size() > kMaxPayload) return 0;
  WireWriter header(out, kHeaderBytes);
  header.u8('F');
  header.u8('F');
  header.u8(kVersion);
  header.u8(static_cast<uint8_t>(m.type));
  header.u8(m.sequence);
  header.u16(static_cast<uint16_t>(payload.size()));
  const size_t body = kHeaderBytes + payload.size();
  const uint16_t crc = crc16_ccitt(out + 2, body - 2);
  out[body] = static_cast<uint8_t>(crc);
  out[body + 1] = static_cast<uint8_t>(crc >> 8);
  return body + kCrcBytes;
}

DecodeStatus decode(const uint8_t* in, size_t size, Message& out) {
  if (in == nullptr || size < kHeaderBytes + kCrcBytes) return DecodeStatus::TooShort;
  if (in[0] != 'F' || in[1] != 'F') return DecodeStatus::BadMagic;
  if (in[2] != kVersion) return DecodeStatus::BadVersion;
  const size_t length = static_cast<size_t>(in[5]) | (static_cast<size_t>(in[6]) << 8);
  if (length > kMaxPayload || size != kHeaderBytes + length + kCrcBytes) return DecodeStatus::BadLength;
  const uint16_t crc = static_cast<uint16_t>(in[kHeaderBytes + length] | (in[kHeaderBytes + length + 1] << 8));
  if (crc16_ccitt(in + 2, kHeaderBytes + length - 2) != crc) return DecodeStatus::BadCrc;
  if (!known_type(in[3])) return DecodeStatus::UnknownType;
  // Straight into `out`: a Message-sized temporary would be the deepest frame
  // of the firmware's main loop (5 KB of the Teensy's 21 KB stack).
  reset_in_place(out);
  out.type = static_cast<MessageType>(in[3]);
  out.sequence = in[4];
  WireReader r(in + kHeaderBytes, length);
  if (!get_payload(r, out) || !r.at_end()) {
    reset_in_place(out);  // no half-read message for a caller that ignores the status
    return DecodeStatus::Malformed;
  }
  return DecodeStatus::Ok;
}

}  // namespace ff::protocol
