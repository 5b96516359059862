#pragma once
// The firmware, Teensyduino-free: the main loop (sensor, host messages, load
// cells, mouse, streaming) and the 2 kHz tick, bound to the core's bus
// interfaces and a Board. firmware/src/main.cpp binds it to the Teensy.
//
// Threading: loop() runs in the main loop, tick() in the IntervalTimer
// interrupt (priority above USB), which preempts the loop but never the
// other way round. They share the pipeline (its own SPSC mailbox, atomic
// scene swap and tracker configuration handover), the heartbeat, the mouse position, the tick ring, the cycle
// statistics (a sequence counter, cycle_histogram.hpp) and a few counters:
// every word has one writer, and the tick's words are 32-bit atomics the
// loop only reads.
#include <atomic>
#include <cstdint>

#include "firmware/app/board.hpp"
#include "firmware/app/cycle_histogram.hpp"
#include "firmware/app/hid_outbox.hpp"
#include "firmware/app/tick_ring.hpp"
#include "firmware/app/udp_peer.hpp"
#include "frictionfield/bus/adc.hpp"
#include "frictionfield/bus/dac.hpp"
#include "frictionfield/bus/data_ready.hpp"
#include "frictionfield/bus/i2c.hpp"
#include "frictionfield/bus/spi.hpp"
#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/drivers/ad9834.hpp"
#include "frictionfield/drivers/frequency_sweep.hpp"
#include "frictionfield/drivers/fsadjust_amplitude.hpp"
#include "frictionfield/drivers/load_cells.hpp"
#include "frictionfield/drivers/zforce_sensor.hpp"
#include "frictionfield/protocol/codec.hpp"
#include "frictionfield/protocol/hid_channel.hpp"

namespace ff::firmware {

constexpr uint16_t kFirmwareVersion = 0x0101;    // 1.1: Status carries the device and sensor counts
constexpr uint32_t kDefaultCarrierHz = 34900;    // plate mode (0;12)
constexpr uint32_t kMouseIntervalUs = 3000;      // thesis: cursor every 3 ms
// Main loop silent this long: the tick rests the plate. Ten sensor periods;
// a healthy loop comes round every few hundred microseconds.
constexpr uint32_t kWatchdogUs = 50000;
// ... while it prepares a scene (a 96 KiB table takes ~70 ms on the M4).
constexpr uint32_t kPreparationWatchdogUs = 1000000;
// No tick for this long: the loop rests the plate itself (20 missed ticks).
constexpr uint32_t kTickStallUs = 10000;
// From acknowledging RebootToBootloader to restarting: the host polls the IN
// endpoint every 1 ms and the queue holds at most 6 reports (Teensyduino
// waits 15 ms after its own serial request, usb_dev.c usb_reboot_timer).
constexpr uint32_t kRebootDelayUs = 20000;
// The zForce gave up configuring: start it again after this long.
constexpr uint32_t kSensorRetryUs = 2000000;
constexpr uint32_t kStreamFlushUs = 10000;       // streamed records wait at most this long
// Host input handled per loop, so that a flood cannot starve the sensor.
constexpr int kMaxDatagramsPerLoop = 4;
constexpr int kMaxReportsPerLoop = 2 * static_cast<int>(protocol::kMaxHidReports);
constexpr uint32_t kCarrierMinHz = 1000;         // SetCarrier and StartSweep refuse frequencies outside
constexpr uint32_t kCarrierMaxHz = 1000000;
constexpr bool carrier_in_range(float hz) {
  return hz >= static_cast<float>(kCarrierMinHz) && hz <= static_cast<float>(kCarrierMaxHz);  // NaN: no
}
constexpr uint32_t kSweepMaxMs = 600000;         // 10 min

struct Peripherals {
  SpiBus16& spi;
  uint8_t dds_chip_select;
  I2cInitiator& i2c;
  DataReadyInput& data_ready;
  Dac12& dac;
  Adc& adc;
};

// A snapshot for the host (counters()). The tick counts watchdog_trips and
// the tick records of stream_overruns in its own atomics; the loop counts
// everything else; counters() adds them up.
struct FirmwareCounters {
  uint32_t protocol_errors = 0;     // malformed or unknown messages (answered with Error)
  uint32_t conditions_set = 0;
  uint32_t conditions_refused = 0;
  uint32_t sensor_profiles_set = 0;
  uint32_t sensor_profiles_refused = 0;  // outside SensorProfileLimits (also the pipeline's Fault::BadSensorProfile)
  uint32_t watchdog_trips = 0;      // the loop stalled: the tick rested the plate
  uint32_t tick_stalls = 0;         // the tick stopped: the loop rested the plate
  uint32_t stream_overruns = 0;     // streamed records dropped: the host did not read in time (reports: loop, ticks: tick)
  uint32_t hid_frames_dropped = 0;  // replies or telemetry the USB host channel had no room for
  uint32_t sensor_restarts = 0;     // zForce configuration started again after it failed
  uint32_t mouse_moves_skipped = 0; // the USB host did not poll the mouse: no move queued
  uint32_t udp_send_failures = 0;   // the reply address did not answer ARP: quiet until it speaks again
};

class FirmwareApp {
 public:
  FirmwareApp(const Peripherals& io, Board& board, HapticPipeline& pipeline);

  // Plate at rest in the board's DAC direction (`wiring`: dac_wiring.hpp), carrier at 34.9 kHz, sensor, tare.
  void begin(uint32_t now_us, const DacCalibration& wiring = DacCalibration::linear());
  void loop(uint32_t now_us);   // main loop: call as often as possible
  void tick(uint32_t now_us);   // the 2 kHz interrupt
  // The whole interrupt handler's cost in DWT cycles, as the board measured
  // it around tick() (entry to exit of its handler); tick only.
  void note_interrupt_cycles(uint32_t cycles) { interrupt_cycles_.add(cycles); }
  uint32_t loop_pass_max_us() const { return loop_pass_max_us_; }

  FirmwareCounters counters() const;
  // The code that rests the plate (the active scene's idle amplitude): for
  // the board's fault handlers.
  uint16_t rest_code() const { return pipeline_.amplitude_map().idle_code(); }
  float carrier_hz() const;
  const Ad9834& carrier() const { return dds_; }
  const ZforceSensor& sensor() const { return zforce_; }
  const LoadReading& last_force() const { return force_; }

 private:
  enum class Channel : uint8_t { Udp, Hid };
  // counters() and the load cells' counts in the Status message's order.
  protocol::DeviceCounts device_counts(const FirmwareCounters& c) const;
  bool tick_alive(uint32_t now_us);
  void read_sensor(uint32_t now_us);
  void read_host(uint32_t now_us);
  void move_mouse(uint32_t now_us);
  void stream(uint32_t now_us, bool final);
  void note_taken_times();
  void handle_frame(const uint8_t* frame, size_t size, Channel channel, uint32_t now_us);
  void handle_command(Channel channel, uint32_t now_us);
  bool send(Channel channel);   // out_; false: the HID channel had no room
  void reply(Channel channel);  // send(), a dropped reply counted
  void send_force();
  void set_carrier(uint32_t hz);
  void rest_plate();  // the loop's own DAC write, for when the tick cannot

  Board& board_;
  HapticPipeline& pipeline_;
  Ad9834 dds_;
  FrequencySweep sweep_;
  Dac12& dac_;                   // the tick writes through amplitude_; the loop's rest_plate() directly
  FsAdjustAmplitude amplitude_;  // tick only (its code and error count)
  ZforceSensor zforce_;
  LoadCellMonitor load_cells_;
  protocol::HidReassembler hid_in_;

  // Written by the loop, read by the tick.
  std::atomic<uint32_t> heartbeat_us_{0};
  std::atomic<bool> preparing_{false};  // set before a preparation, cleared at the next loop
  std::atomic<bool> force_idle_{false};
  bool reboot_pending_ = false;  // loop only: restart at reboot_at_us_
  uint32_t reboot_at_us_ = 0;
  std::atomic<bool> streaming_{false};
  std::atomic<uint8_t> decimation_{1};
  // Written by the tick, read by the loop.
  TickRing ring_;
  std::atomic<float> mouse_x_{0.0f}, mouse_y_{0.0f};
  std::atomic<bool> present_{false};
  std::atomic<uint32_t> watchdog_trips_{0};
  std::atomic<uint32_t> ring_overruns_{0};
  // While streaming: the time of the tick that took mailbox sample k, at [k % 8] (the mailbox holds 8).
  std::atomic<uint32_t> taken_us_by_slot_[SampleMailbox::kCapacity] = {};
  CycleHistogram tick_cycles_;
  CycleHistogram interrupt_cycles_;
  bool watchdog_tripped_ = false;  // tick only
  uint32_t stream_tick_ = 0;       // tick only

  // Main loop only.
  FirmwareCounters counters_;  // the loop's counts (not watchdog_trips, not the tick's overruns)
  protocol::ConditionMessage condition_;  // what the host last set (status)
  LoadReading force_;
  uint32_t last_mouse_us_ = 0;
  uint32_t last_loop_us_ = 0;
  uint32_t loop_pass_max_us_ = 0;
  UdpPeer udp_peer_;
  Channel stream_channel_ = Channel::Hid;
  uint32_t seen_ticks_ = 0;
  uint32_t ticks_seen_us_ = 0;
  bool tick_stalled_ = false;
  bool sensor_failed_ = false;
  uint32_t sensor_failed_us_ = 0;
  uint32_t stream_due_since_us_ = 0;
  protocol::SamplesMessage pending_samples_;  // with the tick that took each (taken_us), once known
  uint32_t pending_index_[protocol::kMaxSamplesPerMessage] = {};  // mailbox index of each pending sample
  uint8_t pending_taken_ = 0;  // how many of the pending samples have their tick's time
  protocol::TicksMessage pending_ticks_;
  protocol::Message in_;   // large: members, not on the loop's stack
  protocol::Message out_;
  uint8_t frame_[protocol::kMaxFrame];  // a datagram in, then any frame out
  HidOutbox hid_out_;
};

}  // namespace ff::firmware
