#include "firmware/app/firmware_app.hpp"

namespace ff::firmware {

using protocol::Message;
using protocol::MessageType;

FirmwareApp::FirmwareApp(const Peripherals& io, Board& board, HapticPipeline& pipeline)
    : board_(board),
      pipeline_(pipeline),
      dds_(io.spi, io.dds_chip_select),
      sweep_(dds_),
      amplitude_(io.dac, DacCalibration::linear()),  // codes come mapped from the pipeline
      zforce_(io.i2c, io.data_ready),
      load_cells_(io.adc) {
  condition_.kind = protocol::ConditionKind::Neutral;
}

void FirmwareApp::begin(uint32_t now_us) {
  amplitude_.write_code(pipeline_.amplitude_map().idle_code());  // the plate rests until told otherwise
  dds_.start(kDefaultCarrierHz);
  zforce_.begin(now_us);
  load_cells_.start(now_us);
  heartbeat_us_.store(now_us, std::memory_order_release);
  last_mouse_us_ = last_stream_flush_us_ = now_us;
}

void FirmwareApp::tick(uint32_t now_us) {
  const uint32_t start = board_.cycles();
  const uint32_t silent = now_us - heartbeat_us_.load(std::memory_order_acquire);
  if (silent > kWatchdogUs) {
    // The main loop stalled: no fresh reports, no host. Rest the plate.
    if (!watchdog_tripped_) ++counters_.watchdog_trips;
    watchdog_tripped_ = true;
    amplitude_.write_code(pipeline_.amplitude_map().idle_code());
    return;
  }
  watchdog_tripped_ = false;
  const TickOutput out = pipeline_.tick(now_us);
  amplitude_.write_code(out.dac);
  mouse_x_.store(out.position.x, std::memory_order_relaxed);
  mouse_y_.store(out.position.y, std::memory_order_relaxed);
  present_.store(out.present, std::memory_order_release);
  if (streaming_.load(std::memory_order_acquire) &&
      ++tick_count_ % decimation_.load(std::memory_order_relaxed) == 0) {
    if (!ring_.push({now_us, out.amplitude, out.dac, out.present})) ++counters_.stream_overruns;
  }
  const uint32_t cycles = board_.cycles() - start;
  cycles_sum_ += cycles;
  ++cycles_count_;
  if (cycles > cycles_max_) cycles_max_ = cycles;
}

uint32_t FirmwareApp::tick_cycles_mean() const {
  return cycles_count_ == 0 ? 0u : static_cast<uint32_t>(cycles_sum_ / cycles_count_);
}

void FirmwareApp::loop(uint32_t now_us) {
  heartbeat_us_.store(now_us, std::memory_order_release);

  // Sensor: the DR interrupt only timestamped; the I2C read happens here.
  SensorSample s;
  while (zforce_.poll(now_us, s)) {
    pipeline_.post_sample(s);
    if (streaming_.load(std::memory_order_relaxed)) {
      pending_samples_.samples[pending_samples_.count++] = s;
      if (pending_samples_.count == protocol::kMaxSamplesPerMessage) flush_stream(now_us, true);
    }
  }

  // Host messages: UDP datagrams and HID reports.
  size_t size = 0;
  while (board_.udp_receive(frame_, sizeof frame_, size)) handle_frame(frame_, size, Channel::Udp, now_us);
  uint8_t report[protocol::kHidReportBytes];
  while (board_.hid_receive(report)) {
    if (hid_in_.push(report)) handle_frame(hid_in_.frame(), hid_in_.size(), Channel::Hid, now_us);
  }

  // Cursor for the visual loop: absolute mouse every 3 ms.
  if (now_us - last_mouse_us_ >= kMouseIntervalUs) {
    last_mouse_us_ += kMouseIntervalUs;
    if (now_us - last_mouse_us_ >= kMouseIntervalUs) last_mouse_us_ = now_us;  // after a stall: no burst
    if (present_.load(std::memory_order_acquire)) {
      board_.mouse_move_to(static_cast<int>(mouse_x_.load(std::memory_order_relaxed) + 0.5f),
                           static_cast<int>(mouse_y_.load(std::memory_order_relaxed) + 0.5f));
    }
  }

  // Force every 30 ms (5-reading average inside the monitor).
  LoadReading reading;
  if (load_cells_.step(now_us, zforce_.finger_present(), reading)) {
    force_ = reading;
    send_force(now_us);
  }

  SweepStep step;
  if (sweep_.running()) sweep_.step(now_us, step);

  if (streaming_.load(std::memory_order_relaxed) && now_us - last_stream_flush_us_ >= 10000) flush_stream(now_us, false);
}

void FirmwareApp::flush_stream(uint32_t now_us, bool /*force*/) {
  last_stream_flush_us_ = now_us;
  if (pending_samples_.count > 0) {
    out_ = Message{};
    out_.type = MessageType::Samples;
    out_.samples = pending_samples_;
    reply(out_, Channel::Hid);
    pending_samples_.count = 0;
  }
  for (;;) {
    out_ = Message{};
    out_.type = MessageType::Ticks;
    protocol::TickRecord r;
    while (out_.ticks.count < protocol::kMaxTicksPerMessage && ring_.pop(r)) out_.ticks.ticks[out_.ticks.count++] = r;
    if (out_.ticks.count == 0) break;
    reply(out_, Channel::Hid);
  }
}

void FirmwareApp::send_force(uint32_t now_us) {
  out_ = Message{};
  out_.type = MessageType::Force;
  out_.force = {now_us, force_.force_mN, force_.over_force};
  reply(out_, Channel::Udp);
  if (streaming_.load(std::memory_order_relaxed)) reply(out_, Channel::Hid);
}

void FirmwareApp::set_carrier(uint32_t hz) {
  // Write the register that is not playing, then switch: no glitch in the carrier.
  const uint8_t next = static_cast<uint8_t>(dds_.selected_frequency() ^ 1u);
  dds_.set_frequency_hz(next, hz);
  dds_.select(next, dds_.selected_phase());
  carrier_hz_ = hz;
}

void FirmwareApp::reply(const Message& m, Channel channel) {
  Message copy = m;
  copy.sequence = sequence_;
  uint8_t frame[protocol::kMaxFrame];
  const size_t n = protocol::encode(copy, frame, sizeof frame);
  if (n == 0) return;
  if (channel == Channel::Udp) {
    board_.udp_send(frame, n);
    return;
  }
  uint8_t reports[protocol::kMaxHidReports][protocol::kHidReportBytes];
  const size_t count = protocol::split_into_reports(frame, n, reports, protocol::kMaxHidReports);
  for (size_t i = 0; i < count; ++i) board_.hid_send(reports[i]);
}

void FirmwareApp::handle_frame(const uint8_t* frame, size_t size, Channel channel, uint32_t now_us) {
  static Message in;  // large: not on the main loop's stack
  const protocol::DecodeStatus status = protocol::decode(frame, size, in);
  sequence_ = size > 4 ? frame[4] : 0;
  Message& r = out_;
  r = Message{};
  if (status != protocol::DecodeStatus::Ok) {
    ++counters_.protocol_errors;
    r.type = MessageType::Error;
    r.error.code = protocol::error_code_for(status);
    r.error.type = size > 3 ? frame[3] : 0;
    reply(r, channel);
    return;
  }
  r.type = MessageType::Ack;
  r.ack.command = in.type;
  switch (in.type) {
    case MessageType::SetCondition: {
      // Prepared here, in the main loop; the tick switches atomically.
      const PrepareStatus st = pipeline_.set_condition(in.condition.to_condition());
      r.ack.detail = static_cast<uint8_t>(st);
      if (st == PrepareStatus::Ok) {
        condition_ = in.condition;
        ++counters_.conditions_set;
      } else {
        r.ack.status = protocol::AckStatus::Refused;
        ++counters_.conditions_refused;
      }
      break;
    }
    case MessageType::QueryStatus: {
      r.type = MessageType::Status;
      protocol::StatusMessage& st = r.status;
      st.firmware_version = kFirmwareVersion;
      st.kind = condition_.kind;
      st.target = condition_.target;
      st.strength = condition_.strength;
      st.ticks = pipeline_.ticks();
      st.tick_cycles_mean = tick_cycles_mean();
      st.tick_cycles_max = cycles_max_;
      st.protocol_errors = counters_.protocol_errors;
      st.force_mN = force_.force_mN;
      st.over_force = force_.over_force;
      st.finger_present = present_.load(std::memory_order_acquire);
      st.carrier_hz = static_cast<float>(carrier_hz_);
      st.faults = pipeline_.faults();
      break;
    }
    case MessageType::StartStream:
      decimation_.store(in.stream.tick_decimation, std::memory_order_relaxed);
      streaming_.store(true, std::memory_order_release);
      break;
    case MessageType::StopStream:
      streaming_.store(false, std::memory_order_release);
      flush_stream(now_us, true);
      break;
    case MessageType::SetCarrier:
      if (in.carrier.frequency_hz >= 1000.0f && in.carrier.frequency_hz <= 1.0e6f) {
        set_carrier(static_cast<uint32_t>(in.carrier.frequency_hz + 0.5f));
      } else {
        r.ack.status = protocol::AckStatus::Refused;
      }
      break;
    case MessageType::StartSweep: {
      SweepConfig c;
      c.start_hz = static_cast<uint32_t>(in.sweep.start_hz);
      c.stop_hz = static_cast<uint32_t>(in.sweep.end_hz);
      c.duration_us = in.sweep.duration_ms * 1000u;
      if (!(in.sweep.start_hz >= 1000.0f && in.sweep.end_hz >= 1000.0f && in.sweep.start_hz <= 1.0e6f &&
            in.sweep.end_hz <= 1.0e6f) || !sweep_.begin(c, now_us)) {
        r.ack.status = protocol::AckStatus::Refused;
      }
      break;
    }
    case MessageType::RebootToBootloader:
      amplitude_.write_code(pipeline_.amplitude_map().idle_code());
      reply(r, channel);
      board_.reboot_to_bootloader();
      return;
    default:  // device-to-host types sent to the device
      ++counters_.protocol_errors;
      r.type = MessageType::Error;
      r.error.code = protocol::ErrorCode::UnknownType;
      r.error.type = static_cast<uint8_t>(in.type);
      break;
  }
  reply(r, channel);
}

}  // namespace ff::firmware
