// libFuzzer target: the message decoder and the HID reassembler. Whatever
// the bytes: no crash; a decoded message re-encodes and decodes to the same
// frame; a decoded condition prepares (or is refused) without harm.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "frictionfield/core/scene_plan.hpp"
#include "frictionfield/protocol/codec.hpp"
#include "frictionfield/protocol/hid_channel.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
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
  }
  // The same bytes as a stream of HID reports.
  static HidReassembler reassembler;
  for (size_t off = 0; off + kHidReportBytes <= size; off += kHidReportBytes) {
    if (reassembler.push(data + off)) (void)decode(reassembler.frame(), reassembler.size(), m);
  }
  return 0;
}
