#include "frictionfield/core/haptic_pipeline.hpp"

#include "frictionfield/core/fastrun.hpp"

namespace ff {

HapticPipeline::HapticPipeline(const TrackerConfig& tracker) : HapticPipeline(tracker, fade_noise(tracker)) {}

HapticPipeline::HapticPipeline(const TrackerConfig& tracker, const FadeNoise& fade)
    : tracker_(tracker, fade), tracker_slots_{{tracker, fade}, {tracker, fade}} {}

PrepareStatus HapticPipeline::set_condition(const Condition& condition) {
  const uint8_t next = static_cast<uint8_t>(active_.load(std::memory_order_acquire) ^ 1u);
  Slot& slot = slots_[next];
  const uint32_t start = micros_ ? micros_() : 0u;
  const PrepareStatus status = slot.plan.prepare(condition.scene, slot.table, sizeof(slot.table));
  last_prepare_us_ = micros_ ? micros_() - start : 0u;
  if (status != PrepareStatus::Ok) return status;
  if (!slot.map.configure(condition.amplitude)) {
    const AmplitudeSettings& in = condition.amplitude;
    if (!(in.strength > 0.0f && in.strength <= 1.0f)) main_faults_.add(Fault::BadStrength);
    if (!in.calibration.valid()) main_faults_.add(Fault::BadCalibration);
  }
  slot.constant_amplitude = slot.map.scale(slot.plan.amplitude({}, {}));
  slot.constant_code = slot.map.dac_code(slot.constant_amplitude);
  active_.store(next, std::memory_order_release);  // the next tick renders the new scene
  return PrepareStatus::Ok;
}

bool HapticPipeline::set_sensor_profile(const SensorProfile& profile) {
  if (!is_valid(profile)) {
    main_faults_.add(Fault::BadSensorProfile);
    return false;
  }
  // The tick reads only the slot tracker_published_ names, and it runs to
  // completion between two instructions of the loop: the other slot is free.
  const uint32_t next = tracker_published_.load(std::memory_order_relaxed) + 1u;
  TrackerSlot& slot = tracker_slots_[next & 1u];
  slot.config = TrackerConfig::recommended(profile);
  slot.fade = fade_noise(slot.config);  // here, not in the tick: it settles three filters
  tracker_published_.store(next, std::memory_order_release);
  return true;
}

bool HapticPipeline::post_sample(const SensorSample& s) {
  if (mailbox_.post(s)) return true;
  main_faults_.add(Fault::MailboxOverflow);
  return false;
}

FF_FASTRUN TickOutput HapticPipeline::tick(uint32_t now_us) {
  ++ticks_;
  // A new tracker configuration first, so that this tick's report is the
  // first the new tracker sees (never a configuration changed mid-tick).
  const uint32_t published = tracker_published_.load(std::memory_order_acquire);
  if (published != tracker_applied_) {
    const TrackerSlot& slot = tracker_slots_[published & 1u];
    tracker_.configure(slot.config, slot.fade);
    tracker_applied_ = published;
  }
  const Slot& slot = slots_[active_.load(std::memory_order_acquire)];
  const Needs needs = slot.plan.needs();
  const bool track_motion = needs != Needs::Nothing;

  // At most one report per tick keeps the tick's work bounded: a burst (the
  // main loop stalled) is taken in order over the next ticks, none is lost.
  SensorSample s;
  if (mailbox_.take(s)) tracker_.on_sample(s, track_motion);
  const TrackState& track = tracker_.on_tick(now_us, track_motion);

  TickOutput out;
  out.present = track.present;
  out.position = track.position;
  if (!track.present) {
    out.amplitude = slot.map.idle_amplitude();
    out.dac = slot.map.idle_code();
    return out;
  }
  if (!track_motion) {  // constant scene: output computed once, at preparation
    out.amplitude = slot.constant_amplitude;
    out.dac = slot.constant_code;
    return out;
  }
  if (needs == Needs::PositionAndDirection) out.direction = track.direction;
  const AmplitudeMap::Output o = slot.map.output(slot.plan.amplitude(track.position, out.direction));
  out.amplitude = o.amplitude;
  out.dac = o.dac;
  return out;
}

FaultCounters HapticPipeline::faults() const {
  FaultCounters all = tracker_.faults().snapshot();  // the tick may be counting meanwhile
  for (int i = 0; i < static_cast<int>(Fault::kCount); ++i) {
    const uint64_t sum = static_cast<uint64_t>(all.count[i]) + main_faults_[static_cast<Fault>(i)];
    all.count[i] = sum > UINT32_MAX ? UINT32_MAX : static_cast<uint32_t>(sum);
  }
  return all;
}

}  // namespace ff
