// ff-m4trace: the calls whose exact cost tools/cyclemodel measures from
// qemu's per-instruction trace (-singlestep -d exec,nochain), and the
// amplitudes of the M4 build for the accuracy check against the double
// reference. No stopwatch: the trace counts every instruction from a call's
// entry to its return.
//
// Command line (semihosting):
//   "trace [smoke]" : per built-in scene: preparation (set_condition), then its
//                     workload tick by tick; prints one "call" line per traced
//                     call, in the order they run (the trace has them in the same
//                     order). smoke: one scene, a short stroke.
//   "accuracy"      : per built-in scene, amplitudes and DAC codes at kEvalPoints
//                     points, with a strength and a calibration that are not
//                     the identity.
#include <cmath>
#include <cstring>

#include "bench_cases.hpp"
#include "bench_workload.hpp"
#include "frictionfield/core/haptic_pipeline.hpp"
#include "scene_workload.hpp"
#include "semihosting.hpp"

namespace {

using namespace ff;
using namespace ff::bench;
using ff::m4::Line;

// 1 s of stroke per scene: the p99.9 of 2,000 ticks is their third largest.
constexpr int kStrokeTicks = 2000;

HapticPipeline g_pipeline;
EvalPoint g_points[kEvalPoints];
int g_failures = 0;
uint32_t g_now_us = 1000;

// The calls the trace measures: never inlined, so their entry is in the trace.
__attribute__((noinline)) TickOutput traced_tick(uint32_t now_us) { return g_pipeline.tick(now_us); }
__attribute__((noinline)) PrepareStatus traced_prepare(const Condition& c) { return g_pipeline.set_condition(c); }

void note(const char* kind, const char* scene, int index) {
  Line().field("call").field(kind).field(scene).field(index).print();
}

TickOutput tick(const char* kind, const char* scene, int index) {
  note(kind, scene, index);
  const TickOutput out = traced_tick(g_now_us);
  g_now_us += 500u;
  if (out.dac > kDacMax) ++g_failures;
  return out;
}

SensorSample sample_at(const StrokePoint& p, bool touch) {
  SensorSample s;
  s.t_us = g_now_us;
  s.x = p.x;
  s.y = p.y;
  s.touch = touch;
  return s;
}

// One scene: swap to it with the finger down, its stroke, a full mailbox and
// the ticks that drain it, lift-off, touch-down.
void trace_scene(SceneId id, int moving_ticks) {
  const char* name = scene_name(id);
  Condition condition;
  condition.scene = scene_definition(id);
  const SceneWorkload workload(condition.scene);

  note("prepare", name, 0);
  if (traced_prepare(condition) != PrepareStatus::Ok) {
    ++g_failures;
    Line().field("error").field(name).field("prepare").print();
    return;
  }
  tick("swap", name, 0);  // the first tick of the new scene (the finger stays down)

  for (int k = 0; k < moving_ticks; ++k) {
    if (k % FingerStroke::kSampleEveryTicks == 0) {
      g_pipeline.post_sample(sample_at(workload.at(k * 0.0005f), true));
    }
    const TickOutput out = tick("stroke", name, k);
    if (k > 0 && !out.present) ++g_failures;
  }
  // Eight reports waiting at one tick (the main loop stalled, the mailbox is
  // full), each with its own stamp and on the stroke, so that the tracker
  // accepts every one: the tick takes one, the next seven one each.
  constexpr int kWaiting = static_cast<int>(SampleMailbox::kCapacity);
  for (int i = 0; i < kWaiting; ++i) {
    const int k = moving_ticks - kWaiting + 1 + i;  // the last eight tick times, the newest now
    SensorSample s = sample_at(workload.at(k * 0.0005f), true);
    s.t_us = g_now_us - static_cast<uint32_t>(kWaiting - 1 - i) * 500u;
    g_pipeline.post_sample(s);
  }
  tick("mailbox-full", name, 0);
  for (int i = 1; i < kWaiting; ++i) tick("mailbox-drain", name, i);
  g_pipeline.post_sample(sample_at(workload.at(0.0f), false));
  tick("lift-off", name, 0);
  for (int k = 0; k < 4; ++k) tick("no-finger", name, k);
  g_pipeline.post_sample(sample_at(workload.at(0.0f), true));
  tick("touch-down", name, 0);
  for (int k = 1; k < 4; ++k) tick("after-touch-down", name, k);
}

void trace(bool smoke) {
  Line().text("# call,kind,scene,index (one per traced call, in trace order)").print();
  // The finger is down when the first scene arrives, as in a session.
  g_pipeline.post_sample(sample_at({400.0f, 240.0f}, true));
  for (int k = 0; k < 4; ++k) tick("warm-up", "neutral", k);
  for (int i = 0; i < kSceneCount; ++i) {
    const auto id = static_cast<SceneId>(i);
    if (!is_builtin(id)) continue;
    if (smoke && id != SceneId::HeightmapTop) continue;
    trace_scene(id, smoke ? 200 : kStrokeTicks);
  }
}

uint32_t float_bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof(u));
  return u;
}

// Amplitudes through a pipeline slot's own path: plan, strength, calibration, DAC.
void accuracy() {
  make_eval_points(g_points);
  AmplitudeSettings settings;
  settings.strength = kAccuracyStrength;
  settings.calibration = accuracy_calibration();
  AmplitudeMap map;
  if (!map.configure(settings)) ++g_failures;
  static ScenePlan plan;
  static unsigned char table[kTableSlotBytes];
  Line().field("strength_milli").field(static_cast<int64_t>(kAccuracyStrength * 1000.0f + 0.5f)).print();
  Line().text("# amplitude,scene,point,x_bits,y_bits,dx_bits,dy_bits,raw_bits,scaled_bits,dac").print();
  for (int i = 0; i < kSceneCount; ++i) {
    const auto id = static_cast<SceneId>(i);
    if (!is_builtin(id)) continue;
    if (plan.prepare(scene_definition(id), table, sizeof(table)) != PrepareStatus::Ok) {
      ++g_failures;
      continue;
    }
    for (int k = 0; k < kEvalPoints; ++k) {
      const float raw = plan.amplitude(g_points[k].position, g_points[k].direction);
      const float scaled = map.scale(raw);
      const EvalPoint& p = g_points[k];
      Line()
          .field("amplitude").field(scene_name(id)).field(k)
          .field(static_cast<int64_t>(float_bits(p.position.x))).field(static_cast<int64_t>(float_bits(p.position.y)))
          .field(static_cast<int64_t>(float_bits(p.direction.x))).field(static_cast<int64_t>(float_bits(p.direction.y)))
          .field(static_cast<int64_t>(float_bits(raw)))
          .field(static_cast<int64_t>(float_bits(scaled)))
          .field(static_cast<int64_t>(map.dac_code(scaled)))
          .print();
    }
  }
}

}  // namespace

int main() {
  char command[64];
  ff::m4::command_line(command, sizeof(command));
  const bool smoke = std::strstr(command, "smoke") != nullptr;
  if (std::strstr(command, "accuracy") != nullptr) {
    Line().field("m4trace").field("accuracy").print();
    accuracy();
  } else {
    Line().field("m4trace").field(smoke ? "trace-smoke" : "trace").print();
    trace(smoke);
  }
  Line().field("done").field(g_failures).print();
  return g_failures == 0 ? 0 : 1;
}
