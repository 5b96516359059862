#pragma once
// The 2 kHz tick: sample in, extrapolate, filter, evaluate the prepared
// scene, amplitude, DAC code out. The firmware's interrupt and the replay
// call the same tick().
//
// Threading: set_condition(), set_sensor_profile() and post_sample() belong
// to the main loop (one producer); tick() to the interrupt (one consumer). A
// new condition is prepared in the slot the tick is not reading and published
// with one atomic store, so no tick sees half a scene; a new tracker
// configuration likewise, which the tick hands to the tracker at its start. That assumes the tick runs to
// completion while the main loop is suspended, as an interrupt on the one-core
// MK66 does: with the two on separate threads, a tick still reading the old
// slot could see the next set_condition() rewrite it. ff-sim keeps the
// interrupt's semantics (one thread, simulated time) for that reason.
#include <atomic>
#include <cstdint>

#include "frictionfield/core/amplitude_map.hpp"
#include "frictionfield/core/condition.hpp"
#include "frictionfield/core/sample_mailbox.hpp"
#include "frictionfield/core/scene_plan.hpp"
#include "frictionfield/core/tracker.hpp"

namespace ff {

struct TickOutput {
  bool present = false;   // a finger was tracked at this tick
  Vec2 position;          // filtered (or last sample's if the scene needs none)
  Vec2 direction;         // what the scene was rendered with (0,0 if unused)
  float amplitude = 0.0f; // A_s in [0, 1]; the idle amplitude without a finger
  uint16_t dac = 0;       // the code sent
};

class HapticPipeline {
 public:
  explicit HapticPipeline(const TrackerConfig& tracker = TrackerConfig::recommended());

  // Main loop side ---------------------------------------------------------
  // Prepares and atomically switches to `condition`; on error nothing changes.
  PrepareStatus set_condition(const Condition& condition);
  // Optional microsecond clock (micros() on the Teensy) to time preparation.
  void set_clock(uint32_t (*micros)()) { micros_ = micros; }
  // Time the last set_condition() took (0 without a clock).
  uint32_t last_prepare_us() const { return last_prepare_us_; }
  // The tracker for the sensor `profile` describes (TrackerConfig::recommended),
  // from the start of the next tick on: the tick configures the tracker
  // before it takes a report, which forgets the finger (not the tick clock),
  // so a finger on the screen is found again at its next report, judged by
  // the tick clock like any other. An invalid profile (is_valid) is counted
  // (Fault::BadSensorProfile) and changes nothing: false.
  bool set_sensor_profile(const SensorProfile& profile);
  // The tracker configuration the next tick uses: the last one handed over.
  const TrackerConfig& tracker_config() const {
    return tracker_slots_[tracker_published_.load(std::memory_order_relaxed) & 1u].config;
  }
  bool post_sample(const SensorSample& s);  // false: mailbox full (counted)
  // The index the next posted sample gets, and how many samples ticks have taken (both wrap):
  // sample k was taken by the first tick after which samples_taken() passed k.
  uint32_t samples_posted() const { return mailbox_.posted(); }
  uint32_t samples_taken() const { return mailbox_.taken(); }

  // Interrupt side ---------------------------------------------------------
  TickOutput tick(uint32_t now_us);

  // Inspection (main loop) --------------------------------------------------
  const ScenePlan& plan() const { return slots_[active_.load(std::memory_order_acquire)].plan; }
  const AmplitudeMap& amplitude_map() const { return slots_[active_.load(std::memory_order_acquire)].map; }
  const Tracker& tracker() const { return tracker_; }
  FaultCounters faults() const;  // tick side and main-loop side together
  uint32_t ticks() const { return ticks_; }

 private:
  HapticPipeline(const TrackerConfig& tracker, const FadeNoise& fade);  // the fade derived once
  // A default Slot is the boot condition, Condition{} prepared: the neutral
  // scene at full strength, the plate resting until a finger arrives.
  struct Slot {
    ScenePlan plan;
    AmplitudeMap map;
    float constant_amplitude = 0.5f;  // constant scenes: the output, computed once
    uint16_t constant_code = 2048;
    alignas(4) unsigned char table[kTableSlotBytes];
  };

  Slot slots_[2];
  std::atomic<uint8_t> active_{0};
  SampleMailbox mailbox_;
  Tracker tracker_;  // the tick's
  // The tracker's configuration, handed over like the scene: the main loop
  // writes the slot the last publication does not name, then counts up;
  // the tick configures the tracker from the named slot when the count
  // moved since it last looked. The loop also derives the fade's noise,
  // which costs more than a tick may spend (FadeNoise).
  struct TrackerSlot {
    TrackerConfig config;
    FadeNoise fade;
  };
  TrackerSlot tracker_slots_[2];
  std::atomic<uint32_t> tracker_published_{0};  // main loop writes
  uint32_t tracker_applied_ = 0;                // tick only
  FaultCounters main_faults_;  // counted on the main-loop side only
  uint32_t (*micros_)() = nullptr;
  uint32_t last_prepare_us_ = 0;
  uint32_t ticks_ = 0;
};

}  // namespace ff
