#include "frictionfield/drivers/zforce_sensor.hpp"

#include "frictionfield/bus/clock.hpp"

namespace ff {
namespace {

using zforce::FrameError;
using zforce::TouchEvent;

constexpr int kMaxFramesPerPoll = 4;
constexpr uint32_t kMaxDrainBytes = 2 + 255;  // the longest frame a length byte can announce

}  // namespace

const char* to_string(ZforceCount c) {
  switch (c) {
    case ZforceCount::FramesRead: return "frames read";
    case ZforceCount::Samples: return "samples";
    case ZforceCount::WrongHeader: return "wrong header";
    case ZforceCount::LengthOverMax: return "length over max";
    case ZforceCount::Truncated: return "truncated";
    case ZforceCount::MalformedTag: return "malformed tag";
    case ZforceCount::UnknownTag: return "unknown tag";
    case ZforceCount::ImpossibleValue: return "impossible value";
    case ZforceCount::BusError: return "bus error";
    case ZforceCount::ResyncBytes: return "resync bytes";
    case ZforceCount::OtherFingerIgnored: return "other finger ignored";
    case ZforceCount::GhostOrInvalid: return "ghost or invalid";
    case ZforceCount::ResumedWithoutDown: return "resumed without down";
    case ZforceCount::UnexpectedResponse: return "unexpected response";
    case ZforceCount::ConfigRetry: return "config retry";
    case ZforceCount::SensorRebooted: return "sensor rebooted";
    case ZforceCount::TrackLost: return "track lost";
    case ZforceCount::TimestampBeside: return "timestamp beside the touches";
    case ZforceCount::TimestampInside: return "timestamp inside the touches";
    case ZforceCount::kCount: break;
  }
  return "?";
}

ZforceSensor::ZforceSensor(I2cInitiator& bus, DataReadyInput& data_ready, const ZforceConfig& config)
    : bus_(bus), dr_(data_ready), config_(config) {
  if (config_.resolution_x == 0) config_.resolution_x = 1;
  if (config_.resolution_y == 0) config_.resolution_y = 1;
  if (!config_.calibration.valid()) config_.calibration = ScreenCalibration::fit(config_.resolution_x, config_.resolution_y);
  if (config_.max_attempts == 0) config_.max_attempts = 1;
  decoder_.set_limits(config_.resolution_x, config_.resolution_y);
}

void ZforceSensor::add(ZforceCount c, uint32_t n) {
  uint32_t& v = counts_[static_cast<int>(c)];
  v = (UINT32_MAX - v < n) ? UINT32_MAX : v + n;
}

uint32_t ZforceSensor::errors() const {
  static constexpr ZforceCount kErrors[] = {ZforceCount::WrongHeader,  ZforceCount::LengthOverMax,
                                            ZforceCount::Truncated,    ZforceCount::MalformedTag,
                                            ZforceCount::UnknownTag,   ZforceCount::ImpossibleValue,
                                            ZforceCount::BusError};
  uint64_t sum = 0;
  for (ZforceCount c : kErrors) sum += count(c);
  return sum > UINT32_MAX ? UINT32_MAX : static_cast<uint32_t>(sum);
}

void ZforceSensor::count_error(FrameError e) {
  switch (e) {
    case FrameError::WrongHeader: add(ZforceCount::WrongHeader); break;
    case FrameError::LengthOverMax: add(ZforceCount::LengthOverMax); break;
    case FrameError::Truncated: add(ZforceCount::Truncated); break;
    case FrameError::MalformedTag: add(ZforceCount::MalformedTag); break;
    case FrameError::UnknownTag: add(ZforceCount::UnknownTag); break;
    case FrameError::ImpossibleValue: add(ZforceCount::ImpossibleValue); break;
    case FrameError::None: break;
  }
}

void ZforceSensor::set_ignored(uint8_t id, bool on) {
  const uint32_t mask = 1u << (id & 31u);
  if (on) {
    ignored_[id >> 5] |= mask;
  } else {
    ignored_[id >> 5] &= ~mask;
  }
}

void ZforceSensor::begin(uint32_t now_us) {
  state_ = ZforceState::Booting;
  step_ = Step::TouchFormat;
  awaiting_ = false;
  attempts_ = 0;
  deadline_us_ = now_us + config_.boot_wait_us;
  edge_pending_ = false;
  tracking_ = false;
  for (uint32_t& w : ignored_) w = 0;
}

bool ZforceSensor::next_edge(uint32_t& t_us) {
  if (edge_pending_) {
    edge_pending_ = false;
    t_us = pending_edge_us_;
    return true;
  }
  uint32_t edges = 0;
  return dr_.take_edge(t_us, edges);
}

void ZforceSensor::drain_until_idle() {
  // The header was wrong (or a read failed), so the length cannot be trusted:
  // read single bytes until the sensor drops DR (its message is gone),
  // bounded by the longest frame there can be.
  // A new rising edge means the sensor has started its next message: stop
  // there and keep the edge for it.
  for (uint32_t i = 0; i < kMaxDrainBytes && dr_.asserted(); ++i) {
    uint32_t edge_us = 0;
    uint32_t edges = 0;
    if (dr_.take_edge(edge_us, edges)) {
      edge_pending_ = true;
      pending_edge_us_ = edge_us;
      return;
    }
    uint8_t b = 0;
    if (bus_.read(config_.address, &b, 1, config_.i2c_timeout_us) != BusStatus::Ok) {
      add(ZforceCount::BusError);
      return;
    }
    add(ZforceCount::ResyncBytes);
  }
}

void ZforceSensor::discard(uint32_t bytes) {
  while (bytes > 0) {
    const uint32_t chunk = bytes < zforce::kMaxFramePayload ? bytes : static_cast<uint32_t>(zforce::kMaxFramePayload);
    if (bus_.read(config_.address, buffer_ + 2, chunk, config_.i2c_timeout_us) != BusStatus::Ok) {
      add(ZforceCount::BusError);
      return;
    }
    add(ZforceCount::ResyncBytes, chunk);
    bytes -= chunk;
  }
}

bool ZforceSensor::read_frame(zforce::Message& msg) {
  if (bus_.read(config_.address, buffer_, 2, config_.i2c_timeout_us) != BusStatus::Ok) {
    add(ZforceCount::BusError);
    drain_until_idle();
    return false;
  }
  if (buffer_[0] != zforce::kFrameStart) {
    count_error(FrameError::WrongHeader);
    drain_until_idle();
    return false;
  }
  const uint32_t length = buffer_[1];
  if (length > zforce::kMaxFramePayload) {
    count_error(FrameError::LengthOverMax);
    discard(length);  // the length itself is plausible: skip exactly the announced frame
    return false;
  }
  if (length > 0 && bus_.read(config_.address, buffer_ + 2, length, config_.i2c_timeout_us) != BusStatus::Ok) {
    add(ZforceCount::BusError);
    drain_until_idle();
    return false;
  }
  const FrameError e = decoder_.decode(buffer_, 2 + length, msg);
  if (e != FrameError::None) {
    count_error(e);
    return false;
  }
  add(ZforceCount::FramesRead);
  return true;
}

void ZforceSensor::send_step(uint32_t now_us) {
  size_t n = 0;
  switch (step_) {
    case Step::TouchFormat: n = zforce::build_touch_format_request(buffer_, sizeof(buffer_)); break;
    case Step::Resolution:
      n = zforce::build_resolution(buffer_, sizeof(buffer_), config_.resolution_x, config_.resolution_y);
      break;
    case Step::Frequency:
      n = zforce::build_frequency(buffer_, sizeof(buffer_), config_.finger_frequency_hz, config_.idle_frequency_hz);
      break;
    case Step::ReportedTouches:
      n = zforce::build_reported_touches(buffer_, sizeof(buffer_), config_.reported_touches);
      break;
    case Step::OperationMode: n = zforce::build_operation_mode_detection(buffer_, sizeof(buffer_)); break;
    case Step::Enable: n = zforce::build_enable(buffer_, sizeof(buffer_), true); break;
    case Step::kDone: return;
  }
  ++attempts_;
  if (bus_.write(config_.address, buffer_, n, config_.i2c_timeout_us) != BusStatus::Ok) add(ZforceCount::BusError);
  awaiting_ = true;  // a failed write times out and is retried like a lost answer
  deadline_us_ = now_us + config_.response_timeout_us;
}

void ZforceSensor::on_response(const zforce::Message& msg, uint32_t now_us) {
  static constexpr uint16_t kAnswers[] = {zforce::kTouchFormat, zforce::kResolution, zforce::kFrequency,
                                          zforce::kDeviceConfiguration, zforce::kOperationMode, zforce::kEnable};
  const int step = static_cast<int>(step_);
  if (state_ != ZforceState::Configuring || !awaiting_ || step >= static_cast<int>(Step::kDone) ||
      msg.response_to != kAnswers[step]) {
    add(ZforceCount::UnexpectedResponse);
    return;
  }
  if (step_ == Step::TouchFormat && msg.has_format) decoder_.set_format(msg.format);
  awaiting_ = false;
  attempts_ = 0;
  step_ = static_cast<Step>(step + 1);
  if (step_ == Step::kDone) state_ = ZforceState::Running;
  deadline_us_ = now_us + config_.response_timeout_us;
}

bool ZforceSensor::on_touches(const zforce::Message& msg, uint32_t t_us, SensorSample& out) {
  if (!tracking_) {
    int pick = -1;
    for (int i = 0; i < msg.touch_count && pick < 0; ++i) {
      if (msg.touches[i].event == TouchEvent::Down) pick = i;
    }
    for (int i = 0; i < msg.touch_count && pick < 0; ++i) {
      if (msg.touches[i].event == TouchEvent::Move && !ignored(msg.touches[i].id)) {
        pick = i;
        add(ZforceCount::ResumedWithoutDown);
      }
    }
    if (pick >= 0) {
      tracking_ = true;
      tracked_id_ = msg.touches[pick].id;
      set_ignored(tracked_id_, false);
    }
  }
  int index = -1;
  for (int i = 0; i < msg.touch_count; ++i) {
    const zforce::Touch& t = msg.touches[i];
    if (tracking_ && t.id == tracked_id_) {
      index = i;
    } else if (t.event == TouchEvent::Up) {
      set_ignored(t.id, false);
    } else if (t.event == TouchEvent::Down || t.event == TouchEvent::Move) {
      set_ignored(t.id, true);
      add(ZforceCount::OtherFingerIgnored);
    }
  }
  if (index < 0) return false;
  const zforce::Touch& t = msg.touches[index];
  tracked_seen_us_ = t_us;
  if (t.event == TouchEvent::Invalid || t.event == TouchEvent::Ghost) {
    add(ZforceCount::GhostOrInvalid);
    return false;
  }
  out.t_us = t_us;
  config_.calibration.to_screen(t.x, t.y, out.x, out.y);
  out.touch = t.event != TouchEvent::Up;
  if (!out.touch) tracking_ = false;
  return true;
}

bool ZforceSensor::poll(uint32_t now_us, SensorSample& out) {
  if (state_ == ZforceState::Booting && deadline_reached(now_us, deadline_us_)) {
    state_ = ZforceState::Configuring;
    deadline_us_ = now_us + config_.response_timeout_us;
  }
  // Signed: an edge that rose after the loop read the clock stamps its frame
  // a little after now_us, which is no silence at all.
  const int32_t silent_us = signed_elapsed(now_us, tracked_seen_us_);
  if (tracking_ && silent_us > 0 && static_cast<uint32_t>(silent_us) > config_.track_timeout_us) {
    tracking_ = false;
    for (uint32_t& w : ignored_) w = 0;
    add(ZforceCount::TrackLost);
  }

  for (int i = 0; i < kMaxFramesPerPoll && dr_.asserted(); ++i) {
    uint32_t edge_us = 0;
    const uint32_t frame_us = next_edge(edge_us) ? edge_us : now_us;
    zforce::Message msg;
    if (!read_frame(msg)) continue;
    switch (msg.kind) {
      case zforce::MessageKind::BootComplete:
        if (state_ == ZforceState::Running || state_ == ZforceState::Failed) add(ZforceCount::SensorRebooted);
        if (state_ != ZforceState::Configuring || step_ != Step::TouchFormat || awaiting_) {
          state_ = ZforceState::Configuring;
          step_ = Step::TouchFormat;
          awaiting_ = false;
          attempts_ = 0;
          deadline_us_ = now_us + config_.response_timeout_us;
          tracking_ = false;
        }
        break;
      case zforce::MessageKind::Response: on_response(msg, now_us); break;
      case zforce::MessageKind::Touches:
        if (msg.has_timestamp) add(msg.timestamp_inside ? ZforceCount::TimestampInside : ZforceCount::TimestampBeside);
        if (on_touches(msg, frame_us, out)) {
          add(ZforceCount::Samples);
          return true;
        }
        break;
      case zforce::MessageKind::OtherNotification: break;
    }
  }

  if (state_ == ZforceState::Configuring) {
    // The deadline is the answer's, or, while DR keeps the next request back
    // (a message the bus cannot read), the request's: either way an attempt.
    if (deadline_reached(now_us, deadline_us_)) {
      if (!awaiting_) ++attempts_;
      awaiting_ = false;
      if (attempts_ >= config_.max_attempts) {
        state_ = ZforceState::Failed;
      } else {
        add(ZforceCount::ConfigRetry);
        deadline_us_ = now_us + config_.response_timeout_us;
      }
    }
    if (state_ == ZforceState::Configuring && !awaiting_ && !dr_.asserted()) send_step(now_us);
  }
  return false;
}

}  // namespace ff
