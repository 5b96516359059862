// Writes the protocol fuzzer's seed corpus: one valid frame of every message
// type the encoder knows, plus fuller ones (a general scene, samples, ticks),
// each encoded by the project's own encoder. Seeds are generated at build
// time, never committed: when the wire format changes, they follow it.
//   ff-fuzz-protocol-seeds OUT_DIR
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "frictionfield/core/scenes.hpp"
#include "frictionfield/protocol/codec.hpp"

namespace {

using namespace ff::protocol;

int written = 0;

bool write_seed(const std::string& dir, const std::string& name, const Message& m) {
  static uint8_t frame[kMaxFrame];
  const size_t n = encode(m, frame, sizeof frame);
  static Message check;
  if (n == 0 || decode(frame, n, check) != DecodeStatus::Ok) return false;  // not a frame of this type
  const std::string path = dir + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr || std::fwrite(frame, 1, n, f) != n) {
    std::fprintf(stderr, "ff-fuzz-protocol-seeds: cannot write %s\n", path.c_str());
    std::exit(2);
  }
  std::fclose(f);
  ++written;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: ff-fuzz-protocol-seeds OUT_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  auto m = std::make_unique<Message>();
  // Every type byte the encoder accepts, with default payloads.
  for (int t = 0; t < 256; ++t) {
    *m = Message{};
    m->type = static_cast<MessageType>(t);
    m->sequence = static_cast<uint8_t>(t);
    char name[32];
    std::snprintf(name, sizeof name, "type_%02x", t);
    write_seed(dir, name, *m);
  }
  // Fuller payloads: every condition kind, a general scene, samples, ticks, sensor profiles.
  for (int k = 0; k < 4; ++k) {
    *m = Message{};
    m->type = MessageType::SetCondition;
    m->condition.kind = static_cast<ConditionKind>(k);
    m->condition.target = ff::Target::Top;
    m->condition.strength = 0.66f;
    m->condition.s_curve = 0.5f;
    if (m->condition.kind == ConditionKind::General) {
      m->condition.scene = ff::scenes::heightmap(ff::Target::Bottom);
      m->condition.scene.add(ff::FieldElement::vortex({400.0f, 240.0f}, 0.1f));
      m->condition.scene.add(ff::FieldElement::sine_texture(160.0f, 120.0f, 20.0f, 0.2f));
    }
    write_seed(dir, "condition_" + std::to_string(k), *m);
  }
  *m = Message{};
  m->type = MessageType::Samples;
  m->samples.count = 3;
  for (uint32_t i = 0; i < 3; ++i) {
    m->samples.samples[i] = {5000u * i, 100.0f + 10.0f * static_cast<float>(i), 240.0f, i != 2};
  }
  write_seed(dir, "samples_3", *m);
  *m = Message{};
  m->type = MessageType::Ticks;
  m->ticks.count = 3;
  for (uint32_t i = 0; i < 3; ++i) {
    m->ticks.ticks[i] = {500u * i, 0.25f * static_cast<float>(i), static_cast<uint16_t>(1000u * i), true};
  }
  write_seed(dir, "ticks_3", *m);
  // A measured sensor profile, and one the device refuses (finite, but a wander without its time).
  *m = Message{};
  m->type = MessageType::SetSensorProfile;
  m->sensor_profile = {1.5f, 0.5f, 250.0f, 0.25f, 180.0f, 400.0f, 3000u};
  write_seed(dir, "sensor_profile", *m);
  m->sensor_profile.correlation_time_ms = 0.0f;
  write_seed(dir, "sensor_profile_refused", *m);
  if (written == 0) {
    std::fprintf(stderr, "ff-fuzz-protocol-seeds: the encoder produced no frame\n");
    return 1;
  }
  std::printf("%d seed frames in %s\n", written, dir.c_str());
  return 0;
}
