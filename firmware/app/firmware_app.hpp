#pragma once
// The firmware, Teensyduino-free: the main loop (sensor, host messages, load
// cells, mouse, streaming) and the 2 kHz tick, bound to the core's bus
// interfaces and a Board. firmware/src/main.cpp binds it to the Teensy.
//
// Threading: loop() runs in the main loop, tick() in the IntervalTimer
// interrupt (priority above USB). They share the pipeline (its own SPSC
// mailbox and atomic scene swap), the heartbeat and the tick ring.
#include <atomic>
#include <cstdint>

#include "firmware/app/board.hpp"
#include "firmware/app/tick_ring.hpp"
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

constexpr uint16_t kFirmwareVersion = 0x0100;  // 1.0
constexpr uint32_t kDefaultCarrierHz = 34900;   // plate mode (0;12)
constexpr uint32_t kMouseIntervalUs = 3000;     // thesis: cursor every 3 ms
constexpr uint32_t kWatchdogUs = 50000;         // main loop silent this long: plate to idle

struct Peripherals {
  SpiBus16& spi;
  uint8_t dds_chip_select;
  I2cInitiator& i2c;
  DataReadyInput& data_ready;
  Dac12& dac;
  Adc& adc;
};

struct FirmwareCounters {
  uint32_t protocol_errors = 0;   // malformed or unknown messages (answered with Error)
  uint32_t watchdog_trips = 0;    // ticks forced idle because the loop stalled
  uint32_t conditions_set = 0;
  uint32_t conditions_refused = 0;
  uint32_t stream_overruns = 0;   // tick records dropped: the loop did not drain in time
};

class FirmwareApp {
 public:
  FirmwareApp(const Peripherals& io, Board& board, HapticPipeline& pipeline);

  void begin(uint32_t now_us);  // carrier at 34.9 kHz, sensor, tare, plate idle
  void loop(uint32_t now_us);   // main loop: call as often as possible
  void tick(uint32_t now_us);   // the 2 kHz interrupt

  const FirmwareCounters& counters() const { return counters_; }
  uint32_t tick_cycles_mean() const;
  uint32_t tick_cycles_max() const { return cycles_max_; }
  const Ad9834& carrier() const { return dds_; }
  const ZforceSensor& sensor() const { return zforce_; }
  const LoadReading& last_force() const { return force_; }

 private:
  enum class Channel : uint8_t { Udp, Hid };
  void handle_frame(const uint8_t* frame, size_t size, Channel channel, uint32_t now_us);
  void reply(const protocol::Message& m, Channel channel);
  void send_force(uint32_t now_us);
  void flush_stream(uint32_t now_us, bool force);
  void set_carrier(uint32_t hz);

  Board& board_;
  HapticPipeline& pipeline_;
  Ad9834 dds_;
  FrequencySweep sweep_;
  FsAdjustAmplitude amplitude_;
  ZforceSensor zforce_;
  LoadCellMonitor load_cells_;
  protocol::HidReassembler hid_in_;

  // Shared with the tick.
  std::atomic<uint32_t> heartbeat_us_{0};
  std::atomic<bool> streaming_{false};
  std::atomic<uint8_t> decimation_{1};
  TickRing ring_;
  std::atomic<float> mouse_x_{0.0f}, mouse_y_{0.0f};
  std::atomic<bool> present_{false};
  bool watchdog_tripped_ = false;
  uint32_t tick_count_ = 0;
  uint64_t cycles_sum_ = 0;
  uint32_t cycles_count_ = 0;
  uint32_t cycles_max_ = 0;

  // Main loop only.
  FirmwareCounters counters_;
  protocol::ConditionMessage condition_;  // what the host last set (status)
  LoadReading force_;
  uint32_t last_mouse_us_ = 0;
  uint32_t last_stream_flush_us_ = 0;
  uint32_t carrier_hz_ = kDefaultCarrierHz;
  uint8_t sequence_ = 0;
  protocol::SamplesMessage pending_samples_;
  protocol::Message out_;  // reused: large
  uint8_t frame_[protocol::kMaxFrame];
};

}  // namespace ff::firmware
