#include "firmware/app/firmware_app.hpp"

#include "firmware/app/mouse_pixel.hpp"
#include "frictionfield/core/fastrun.hpp"
#include "frictionfield/core/geometry.hpp"
#include "frictionfield/drivers/ad9834_registers.hpp"

namespace ff::firmware {

using protocol::Message;
using protocol::MessageType;

FirmwareApp::FirmwareApp(const Peripherals& io, Board& board, HapticPipeline& pipeline)
    : board_(board),
      pipeline_(pipeline),
      dds_(io.spi, io.dds_chip_select),
      sweep_(dds_),
      dac_(io.dac),
      amplitude_(io.dac, DacCalibration::linear()),  // codes come mapped from the pipeline
      zforce_(io.i2c, io.data_ready),
      load_cells_(io.adc) {
  condition_.kind = protocol::ConditionKind::Neutral;
}

void FirmwareApp::begin(uint32_t now_us, const DacCalibration& wiring) {
  // The plate rests until a finger comes, in the board's own DAC direction;
  // until a scene is set, the finger feels Condition's default, the neutral scene.
  Condition resting;
  resting.amplitude.calibration = wiring;
  pipeline_.set_condition(resting);
  condition_.calibration = wiring;
  rest_plate();
  dds_.start(kDefaultCarrierHz);
  zforce_.begin(now_us);
  load_cells_.start(now_us);
  heartbeat_us_.store(now_us, std::memory_order_release);
  ticks_seen_us_ = last_loop_us_ = now_us;  // the mouse and stream clocks start when first used
}

// ---- the 2 kHz interrupt ----------------------------------------------------

FF_FASTRUN void FirmwareApp::tick(uint32_t now_us) {
  const uint32_t start = board_.cycles();
  // Always run the pipeline, so that its clock stays continuous through a
  // stall (no leap to confirm when the loop comes back); only the output
  // is overridden.
  const uint32_t taken_before = pipeline_.samples_taken();
  const TickOutput out = pipeline_.tick(now_us);
  if (streaming_.load(std::memory_order_relaxed)) {  // which tick took each report: ffctl verify replays it there
    for (uint32_t k = taken_before; k != pipeline_.samples_taken(); ++k) {
      taken_us_by_slot_[k % SampleMailbox::kCapacity].store(now_us, std::memory_order_relaxed);
    }
  }
  const uint32_t limit = preparing_.load(std::memory_order_acquire) ? kPreparationWatchdogUs : kWatchdogUs;
  // Signed: a heartbeat stamped a moment after `now_us` is fresh, not 71 minutes old.
  const int32_t silent = static_cast<int32_t>(now_us - heartbeat_us_.load(std::memory_order_acquire));
  const bool stalled = silent > static_cast<int32_t>(limit);
  if (stalled && !watchdog_tripped_) watchdog_trips_.fetch_add(1, std::memory_order_relaxed);
  watchdog_tripped_ = stalled;
  const bool rest = stalled || force_idle_.load(std::memory_order_acquire);
  const uint16_t code = rest ? pipeline_.amplitude_map().idle_code() : out.dac;
  amplitude_.write_code(code);

  mouse_x_.store(out.position.x, std::memory_order_relaxed);
  mouse_y_.store(out.position.y, std::memory_order_relaxed);
  present_.store(out.present, std::memory_order_release);
  if (streaming_.load(std::memory_order_acquire) && ++stream_tick_ >= decimation_.load(std::memory_order_relaxed)) {
    stream_tick_ = 0;
    const float amplitude = rest ? pipeline_.amplitude_map().idle_amplitude() : out.amplitude;
    if (!ring_.push({now_us, amplitude, code, out.present})) ring_overruns_.fetch_add(1, std::memory_order_relaxed);
  }

  tick_cycles_.add(board_.cycles() - start);
}

FirmwareCounters FirmwareApp::counters() const {
  FirmwareCounters c = counters_;
  c.watchdog_trips = watchdog_trips_.load(std::memory_order_relaxed);
  c.stream_overruns += ring_overruns_.load(std::memory_order_relaxed);
  c.udp_send_failures = udp_peer_.send_failures();
  return c;
}

// Status carries the driver's state and counts as they are.
static_assert(static_cast<int>(ZforceState::Booting) == static_cast<int>(protocol::SensorState::Booting) &&
              static_cast<int>(ZforceState::Configuring) == static_cast<int>(protocol::SensorState::Configuring) &&
              static_cast<int>(ZforceState::Running) == static_cast<int>(protocol::SensorState::Running) &&
              static_cast<int>(ZforceState::Failed) == static_cast<int>(protocol::SensorState::Failed));
static_assert(static_cast<int>(ZforceCount::kCount) <= protocol::kMaxSensorCounts);

protocol::DeviceCounts FirmwareApp::device_counts(const FirmwareCounters& c) const {
  using protocol::DeviceCount;
  protocol::DeviceCounts d;
  d[DeviceCount::ConditionsSet] = c.conditions_set;
  d[DeviceCount::ConditionsRefused] = c.conditions_refused;
  d[DeviceCount::SensorProfilesSet] = c.sensor_profiles_set;
  d[DeviceCount::SensorProfilesRefused] = c.sensor_profiles_refused;
  d[DeviceCount::TickStalls] = c.tick_stalls;
  d[DeviceCount::HidFramesDropped] = c.hid_frames_dropped;
  d[DeviceCount::SensorRestarts] = c.sensor_restarts;
  d[DeviceCount::MouseMovesSkipped] = c.mouse_moves_skipped;
  d[DeviceCount::UdpSendFailures] = c.udp_send_failures;
  d[DeviceCount::ForceReadErrors] = load_cells_.read_errors();
  d[DeviceCount::ForceRezeros] = load_cells_.rezeros();
  d[DeviceCount::ForceRezerosRefused] = load_cells_.rezeros_refused();
  d[DeviceCount::ForcePeriodsMissed] = load_cells_.missed_periods();
  d[DeviceCount::UdpUnavailable] = board_.udp_available() ? 0 : 1;
  return d;
}

float FirmwareApp::carrier_hz() const {
  const uint32_t word = dds_.frequency_word_of(dds_.selected_frequency());
  return static_cast<float>(ad9834::output_millihz(word, dds_.mclk_hz())) * 0.001f;
}

// ---- the main loop ----------------------------------------------------------

void FirmwareApp::loop(uint32_t now_us) {
  heartbeat_us_.store(now_us, std::memory_order_release);
  const uint32_t pass_us = now_us - last_loop_us_;  // the previous pass, interrupts included
  last_loop_us_ = now_us;
  if (pass_us > loop_pass_max_us_) loop_pass_max_us_ = pass_us;
  preparing_.store(false, std::memory_order_release);

  const bool ticking = tick_alive(now_us);
  if (reboot_pending_ && static_cast<int32_t>(now_us - reboot_at_us_) >= 0) {
    reboot_pending_ = false;
    board_.reboot_to_bootloader();
    force_idle_.store(false, std::memory_order_release);  // a board without a bootloader returns
  }
  read_sensor(now_us);
  read_host(now_us);
  move_mouse(now_us);

  // Force every 30 ms (5-reading average inside the monitor).
  if (load_cells_.step(now_us, zforce_.finger_present(), force_)) send_force();

  SweepStep step;
  if (sweep_.running()) sweep_.step(now_us, step);

  if (streaming_.load(std::memory_order_relaxed)) stream(now_us, false);
  hid_out_.drain(board_);  // what the SEREMU queue had no room for last pass
  if (ticking) board_.watchdog_kick();
}

bool FirmwareApp::tick_alive(uint32_t now_us) {
  const uint32_t ticks = pipeline_.ticks();
  if (ticks != seen_ticks_) {
    seen_ticks_ = ticks;
    ticks_seen_us_ = now_us;
    tick_stalled_ = false;
    return true;
  }
  if (now_us - ticks_seen_us_ <= kTickStallUs) return true;
  if (!tick_stalled_) {
    // Nothing else will write the DAC: the last code would play on.
    tick_stalled_ = true;
    ++counters_.tick_stalls;
    rest_plate();
  }
  return false;
}

void FirmwareApp::read_sensor(uint32_t now_us) {
  // The DR interrupt only timestamped; the I2C read happens here.
  SensorSample s;
  while (zforce_.poll(now_us, s)) {
    const uint32_t index = pipeline_.samples_posted();
    if (!pipeline_.post_sample(s) || !streaming_.load(std::memory_order_relaxed)) continue;
    if (pending_samples_.count < protocol::kMaxSamplesPerMessage) {
      pending_index_[pending_samples_.count] = index;
      pending_samples_.samples[pending_samples_.count++] = s;
    } else {
      ++counters_.stream_overruns;
    }
  }
  if (zforce_.state() != ZforceState::Failed) {
    sensor_failed_ = false;
  } else if (!sensor_failed_) {
    sensor_failed_ = true;
    sensor_failed_us_ = now_us;
  } else if (now_us - sensor_failed_us_ >= kSensorRetryUs) {
    // Unplugged or powered late: no samples, so the pipeline is idle; try again.
    ++counters_.sensor_restarts;
    zforce_.begin(now_us);
  }
}

void FirmwareApp::read_host(uint32_t now_us) {
  size_t size = 0;
  UdpEndpoint from;
  for (int i = 0; i < kMaxDatagramsPerLoop && board_.udp_receive(frame_, sizeof frame_, size, from); ++i) {
    udp_peer_.heard_from(from);
    handle_frame(frame_, size, Channel::Udp, now_us);
  }
  uint8_t report[protocol::kHidReportBytes];
  for (int i = 0; i < kMaxReportsPerLoop && board_.hid_receive(report); ++i) {
    if (hid_in_.push(report)) handle_frame(hid_in_.frame(), hid_in_.size(), Channel::Hid, now_us);
  }
}

void FirmwareApp::move_mouse(uint32_t now_us) {
  // Cursor for the visual loop: absolute mouse every 3 ms while a finger is down.
  if (now_us - last_mouse_us_ < kMouseIntervalUs) return;
  last_mouse_us_ += kMouseIntervalUs;
  if (now_us - last_mouse_us_ >= kMouseIntervalUs) last_mouse_us_ = now_us;  // after a stall: no burst
  if (!present_.load(std::memory_order_acquire)) return;
  if (!board_.mouse_move_to(mouse_pixel(mouse_x_.load(std::memory_order_relaxed), kScreenMaxX),
                            mouse_pixel(mouse_y_.load(std::memory_order_relaxed), kScreenMaxY))) {
    ++counters_.mouse_moves_skipped;
  }
}

// Raw sensor reports and rendered ticks for `ffctl record`, over USB only.
// A record waits until its message is full or kStreamFlushUs passed; a
// message waits (in the ring) while the host channel has no room.
// The tick that took each pending report, as soon as one has (within a tick of posting it).
void FirmwareApp::note_taken_times() {
  const uint32_t taken = pipeline_.samples_taken();
  while (pending_taken_ < pending_samples_.count) {
    const uint32_t index = pending_index_[pending_taken_];
    if (static_cast<int32_t>(taken - index) <= 0) break;  // not taken yet
    // Older than the mailbox: its slot may hold a later report's time. Unknown then (a loop stalled 8 reports long).
    pending_samples_.taken_us[pending_taken_] =
        taken - index <= SampleMailbox::kCapacity
            ? taken_us_by_slot_[index % SampleMailbox::kCapacity].load(std::memory_order_relaxed)
            : 0;
    ++pending_taken_;
  }
}

void FirmwareApp::stream(uint32_t now_us, bool final) {
  const bool due = final || now_us - stream_due_since_us_ >= kStreamFlushUs;
  bool sent_all = true;
  note_taken_times();
  const bool all_taken = pending_taken_ == pending_samples_.count;
  if (pending_samples_.count > 0 && (due || pending_samples_.count == protocol::kMaxSamplesPerMessage) &&
      (all_taken || final)) {
    out_.type = MessageType::Samples;
    out_.sequence = 0;
    out_.samples = pending_samples_;
    out_.samples.has_taken_times = all_taken;
    if (send(stream_channel_)) {
      pending_samples_.count = 0;
      pending_taken_ = 0;
    } else {
      sent_all = false;
    }
  } else if (pending_samples_.count > 0) {
    sent_all = false;
  }
  for (;;) {
    protocol::TickRecord r;
    while (pending_ticks_.count < protocol::kMaxTicksPerMessage && ring_.pop(r)) {
      pending_ticks_.ticks[pending_ticks_.count++] = r;
    }
    if (pending_ticks_.count == 0) break;
    if (!due && pending_ticks_.count < protocol::kMaxTicksPerMessage) {
      sent_all = false;
      break;
    }
    out_.type = MessageType::Ticks;
    out_.sequence = 0;
    out_.ticks = pending_ticks_;
    if (!send(stream_channel_)) {
      sent_all = false;
      break;
    }
    pending_ticks_.count = 0;
  }
  if (sent_all) stream_due_since_us_ = now_us;
  if (final && !sent_all) {  // the host stopped the stream but has no room: drop the rest
    counters_.stream_overruns += pending_samples_.count + pending_ticks_.count + ring_.size();
    pending_samples_.count = 0;  // counted once, even if the host stops the stream again
    pending_taken_ = 0;
    pending_ticks_.count = 0;
    protocol::TickRecord r;
    while (ring_.pop(r)) {
    }
  }
}

void FirmwareApp::send_force() {
  out_.type = MessageType::Force;
  out_.sequence = 0;
  out_.force = {force_.t_us, force_.force_mN, force_.over_force};
  send(Channel::Udp);
  if (streaming_.load(std::memory_order_relaxed) && stream_channel_ == Channel::Hid && !send(Channel::Hid)) {
    ++counters_.hid_frames_dropped;
  }
}

bool FirmwareApp::send(Channel channel) {
  const size_t n = protocol::encode(out_, frame_, sizeof frame_);
  if (n == 0) {  // cannot happen for the device's messages; never retried
    ++counters_.hid_frames_dropped;
    return true;
  }
  if (channel == Channel::Udp) {
    if (udp_peer_.reachable() && !board_.udp_send(udp_peer_.endpoint(), frame_, n)) udp_peer_.send_failed();
    return true;  // datagrams are not queued: a lost one is the network's
  }
  if (!hid_out_.push(frame_, n)) return false;  // whole frames or nothing: the host reassembles
  hid_out_.drain(board_);
  return true;
}

void FirmwareApp::reply(Channel channel) {
  if (!send(channel)) ++counters_.hid_frames_dropped;
}

void FirmwareApp::set_carrier(uint32_t hz) {
  // Write the register that is not playing, then switch: no glitch in the carrier.
  const uint8_t next = static_cast<uint8_t>(dds_.selected_frequency() ^ 1u);
  dds_.set_frequency_hz(next, hz);
  dds_.select(next, dds_.selected_phase());
}

// Not through amplitude_: that is the tick's, and a tick may land in the middle of this.
void FirmwareApp::rest_plate() { dac_.write(pipeline_.amplitude_map().idle_code()); }

// ---- host messages ------------------------------------------------------------

void FirmwareApp::handle_frame(const uint8_t* frame, size_t size, Channel channel, uint32_t now_us) {
  // Header fields first: `frame` may be frame_, which the reply overwrites.
  const uint8_t sequence = size > 4 ? frame[4] : 0;
  const uint8_t type = size > 3 ? frame[3] : 0;
  const protocol::DecodeStatus status = protocol::decode(frame, size, in_);
  out_.sequence = sequence;
  if (status != protocol::DecodeStatus::Ok) {
    ++counters_.protocol_errors;
    out_.type = MessageType::Error;
    out_.error = {protocol::error_code_for(status), type};
    reply(channel);
    return;
  }
  handle_command(channel, now_us);
}

void FirmwareApp::handle_command(Channel channel, uint32_t now_us) {
  out_.type = MessageType::Ack;
  out_.ack = {in_.type, protocol::AckStatus::Ok, 0};
  switch (in_.type) {
    case MessageType::SetCondition: {
      // Prepared here, in the main loop, while the tick renders the old
      // scene; the tick switches atomically. The watchdog allows for it.
      preparing_.store(true, std::memory_order_release);
      const PrepareStatus st = pipeline_.set_condition(in_.condition.to_condition());
      out_.ack.detail = static_cast<uint8_t>(st);
      if (st == PrepareStatus::Ok) {
        condition_ = in_.condition;
        ++counters_.conditions_set;
      } else {
        out_.ack.status = protocol::AckStatus::Refused;
        ++counters_.conditions_refused;
      }
      break;
    }
    case MessageType::SetSensorProfile:
      // Checked and derived here, in the loop; the tick configures its
      // tracker from it at its next start (HapticPipeline). Kept until reset
      // or power-off: nothing is written to flash.
      if (pipeline_.set_sensor_profile(in_.sensor_profile)) {
        ++counters_.sensor_profiles_set;
      } else {
        out_.ack.status = protocol::AckStatus::Refused;
        ++counters_.sensor_profiles_refused;
      }
      break;
    case MessageType::QuerySensorProfile:  // what the tracker uses from the next tick on
      out_.type = MessageType::SensorProfile;
      out_.sensor_profile = pipeline_.tracker_config().sensor;
      break;
    case MessageType::QueryStatus: {
      out_.type = MessageType::Status;
      protocol::StatusMessage& st = out_.status;
      st.firmware_version = kFirmwareVersion;
      st.kind = condition_.kind;
      st.target = condition_.target;
      st.strength = condition_.strength;
      st.ticks = pipeline_.ticks();
      const CycleStats tick = tick_cycles_.read();
      st.tick_cycles_mean = tick.mean;
      st.tick_cycles_max = tick.max;
      const FirmwareCounters c = counters();
      st.protocol_errors = c.protocol_errors;
      st.watchdog_trips = c.watchdog_trips;
      st.stream_overruns = c.stream_overruns;
      st.force_mN = force_.force_mN;
      st.over_force = force_.over_force;
      st.finger_present = present_.load(std::memory_order_acquire);
      st.carrier_hz = carrier_hz();
      st.faults = pipeline_.faults();
      const CycleStats isr = interrupt_cycles_.read();
      st.isr_cycles_mean = isr.mean;
      st.isr_cycles_max = isr.max;
      st.isr_cycles_p99 = isr.p99;
      st.prepare_us_last = pipeline_.last_prepare_us();
      st.loop_pass_max_us = loop_pass_max_us_;
      st.zforce_layout_beside = zforce_.count(ZforceCount::TimestampBeside);
      st.zforce_layout_inside = zforce_.count(ZforceCount::TimestampInside);
      st.device = device_counts(c);
      st.sensor_state = static_cast<protocol::SensorState>(zforce_.state());
      st.sensor_count_n = static_cast<uint8_t>(ZforceCount::kCount);
      for (int i = 0; i < st.sensor_count_n; ++i) st.sensor_counts[i] = zforce_.count(static_cast<ZforceCount>(i));
      break;
    }
    case MessageType::QueryCondition:  // what renders now, as the SetCondition payload that set it
      out_.type = MessageType::Condition;
      out_.condition = condition_;
      break;
    case MessageType::StartStream:
      // Nothing is held here: a stop sent or dropped it all, and the tick,
      // an interrupt, pushes only while streaming_ is set. Started again
      // while streaming, the records held go on in the new stream. The
      // flush clock starts at this loop pass's stream(), with nothing to send.
      decimation_.store(in_.stream.tick_decimation, std::memory_order_relaxed);  // >= 1: the codec checks
      stream_channel_ = channel;
      streaming_.store(true, std::memory_order_release);
      break;
    case MessageType::StopStream: {
      streaming_.store(false, std::memory_order_release);
      const uint8_t sequence = out_.sequence;
      stream(now_us, true);  // uses out_ for what is left
      out_.type = MessageType::Ack;  // out_.ack is as handle_command set it: the stream does not touch it
      out_.sequence = sequence;
      break;
    }
    case MessageType::SetCarrier: {
      const float hz = in_.carrier.frequency_hz;
      if (carrier_in_range(hz)) {
        sweep_.stop();
        set_carrier(static_cast<uint32_t>(hz + 0.5f));
      } else {
        out_.ack.status = protocol::AckStatus::Refused;
      }
      break;
    }
    case MessageType::StartSweep: {
      const protocol::SweepMessage& s = in_.sweep;
      SweepConfig c;
      bool ok = carrier_in_range(s.start_hz) && carrier_in_range(s.end_hz) && s.duration_ms > 0 &&
                s.duration_ms <= kSweepMaxMs;
      if (ok) {
        c.start_hz = static_cast<uint32_t>(s.start_hz + 0.5f);
        c.stop_hz = static_cast<uint32_t>(s.end_hz + 0.5f);
        c.duration_us = s.duration_ms * 1000u;
        ok = sweep_.begin(c, now_us);
      }
      if (!ok) out_.ack.status = protocol::AckStatus::Refused;
      break;
    }
    case MessageType::RebootToBootloader:
      // The plate rests first, and the tick keeps it resting until the reset.
      force_idle_.store(true, std::memory_order_release);
      rest_plate();
      reply(channel);
      // The restart waits for the reply to leave: _reboot_Teensyduino_() (usb_dev.c) is a bkpt
      // that hands the chip to the bootloader, and what the SEREMU queue still holds is lost.
      reboot_pending_ = true;
      reboot_at_us_ = now_us + kRebootDelayUs;
      return;
    default:  // device-to-host types sent to the device
      ++counters_.protocol_errors;
      out_.type = MessageType::Error;
      out_.error = {protocol::ErrorCode::UnknownType, static_cast<uint8_t>(in_.type)};
      break;
  }
  reply(channel);
}

}  // namespace ff::firmware
