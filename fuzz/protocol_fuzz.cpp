// libFuzzer target: the message decoder and the HID reassembler. Whatever
// the bytes: no crash; a decoded message re-encodes and decodes to the same
// frame; a decoded condition prepares (or is refused) without harm; a
// decoded sensor profile the device accepts makes a tracker that tracks.
// Seeds: valid frames of every message type, written by the encoder itself at
// build time (protocol_seeds.cpp). protocol_fixed_fuzz.cpp runs the same
// checks on frames whose length and CRC are made right first.
// FF_FUZZ_NO_ENTRY leaves out LLVMFuzzerTestOneInput (for that variant).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "frictionfield/core/geometry.hpp"
#include "frictionfield/core/scene_plan.hpp"
#include "frictionfield/core/tracker.hpp"
#include "frictionfield/protocol/codec.hpp"
#include "frictionfield/protocol/hid_channel.hpp"

namespace ff::fuzz {

int protocol_one_input(const uint8_t* data, size_t size) {
  using namespace ff::protocol;
  static Message m;  // large: keep it off the stack
  if (decode(data, size, m) == DecodeStatus::Ok) {
    static uint8_t again[kMaxFrame];
    const size_t n = encode(m, again, sizeof again);
    static Message m2;
    if (n == 0 || decode(again, n, m2) != DecodeStatus::Ok) {
      std::fprintf(stderr, "protocol_fuzz: a decoded message does not re-encode\n");
      std::abort();
    }
    if (m.type == MessageType::SetCondition) {
      static auto plan = std::make_unique<ff::ScenePlan>();
      static std::vector<uint32_t> table(ff::kTableSlotBytes / 4);
      (void)plan->prepare(m.condition.to_condition().scene, table.data(), table.size() * 4);
    }
    if (m.type == MessageType::SetSensorProfile && ff::is_valid(m.sensor_profile)) {
      // Every profile the device accepts makes a tracker that answers a report with a finite position.
      static ff::Tracker tracker;
      tracker.configure(ff::TrackerConfig::recommended(m.sensor_profile));
      tracker.reset();  // configure() keeps the tick clock; every input starts at the same times
      tracker.on_sample({1000, 400.0f, 240.0f, true});
      const ff::TrackState& s = tracker.on_tick(1500);
      if (!s.present || !ff::is_finite(s.position.x) || !ff::is_finite(s.position.y)) {
        std::fprintf(stderr, "protocol_fuzz: a valid sensor profile does not track\n");
        std::abort();
      }
    }
  }
  // The same bytes as a stream of HID reports.
  static HidReassembler reassembler;
  for (size_t off = 0; off + kHidReportBytes <= size; off += kHidReportBytes) {
    if (reassembler.push(data + off)) (void)decode(reassembler.frame(), reassembler.size(), m);
  }
  return 0;
}

}  // namespace ff::fuzz

#ifndef FF_FUZZ_NO_ENTRY
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return ff::fuzz::protocol_one_input(data, size);
}
#endif
