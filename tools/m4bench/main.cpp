// ff-m4bench: Cortex-M4F cost of every evaluation strategy, of scene
// preparation, of each tracker configuration and of the whole 2 kHz tick,
// in instructions, under qemu mps2-an386 with -icount shift=0 (deterministic:
// the same numbers every run). Prints CSV records through semihosting; the
// host's ff-bench supplies the errors, tools/bench/make_report.py merges both.
//
// Command line (semihosting): "smoke" runs closed forms, 8 px int16 tables and
// every tracker briefly; nothing else runs everything.
#include <cstdint>
#include <cstring>

#include "bench_cases.hpp"
#include "bench_workload.hpp"
#include "frictionfield/core/field_element.hpp"
#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/core/scene_plan.hpp"
#include "semihosting.hpp"
#include "systick_counter.hpp"

namespace {

using namespace ff;
using namespace ff::bench;
using ff::m4::Line;
using ff::m4::SystickCounter;

// The largest table measured (1 px, float, gradient: 800 x 480 x 2 x 4 bytes)
// lives in PSRAM: the AN386 has room, the Teensy does not.
constexpr size_t kBigTableBytes = 3u * 1024u * 1024u;
alignas(8) __attribute__((section(".psram"))) unsigned char g_table[kBigTableBytes];

// Static, as on the Teensy: two table slots of FF_TABLE_SLOT_BYTES each.
HapticPipeline g_pipeline;
ScenePlan g_plan;
EvalPoint g_points[kEvalPoints];

uint32_t g_instructions_per_count = 0;
uint32_t g_clock_us = 1000;  // the stroke clock: strokes follow each other
int g_failures = 0;

int64_t instructions(uint64_t counts) { return static_cast<int64_t>(counts * g_instructions_per_count); }

struct TickCost {
  int64_t total = 0;
  int64_t max = 0;
  int ticks = 0;
  uint32_t dac_sum = 0;
};

// One stroke through the pipeline; only tick() is timed (post_sample is the main loop's).
TickCost run_pipeline_stroke() {
  TickCost cost;
  const FingerStroke stroke(g_clock_us);
  for (int k = 0; k < FingerStroke::kTotalTicks; ++k) {
    SensorSample s;
    if (stroke.report_before(k, s)) g_pipeline.post_sample(s);
    const uint64_t c0 = SystickCounter::counts();
    const TickOutput out = g_pipeline.tick(stroke.tick_time(k));
    const int64_t spent = instructions(SystickCounter::counts() - c0);
    if (out.dac > kDacMax) ++g_failures;
    if (k >= FingerStroke::kMovingTicks) continue;
    if (k > 0 && !out.present) ++g_failures;  // the finger is on the glass all along
    cost.total += spent;
    cost.max = spent > cost.max ? spent : cost.max;
    cost.dac_sum += out.dac;
    ++cost.ticks;
  }
  g_clock_us += FingerStroke::kDurationUs;
  return cost;
}

TickCost run_tracker_stroke(Tracker& tracker) {
  TickCost cost;
  const FingerStroke stroke(g_clock_us);
  for (int k = 0; k < FingerStroke::kMovingTicks; ++k) {
    SensorSample s;
    const bool report = stroke.report_before(k, s);
    const uint64_t c0 = SystickCounter::counts();
    if (report) tracker.on_sample(s);
    const TrackState st = tracker.on_tick(stroke.tick_time(k), true);
    const int64_t spent = instructions(SystickCounter::counts() - c0);
    if (!st.present) ++g_failures;
    cost.total += spent;
    cost.max = spent > cost.max ? spent : cost.max;
    ++cost.ticks;
  }
  g_clock_us += FingerStroke::kDurationUs;
  return cost;
}

void measure_case(const BenchCase& c, int eval_repeats) {
  char id[96];
  case_id(c, id, sizeof(id));
  const SceneDefinition def = case_definition(c);

  uint64_t c0 = SystickCounter::counts();
  // Every strategy, those past the Teensy's preparation budget too (its cost is what is measured).
  const PrepareStatus status = g_plan.prepare(def, g_table, sizeof(g_table), UINT32_MAX);
  const int64_t prepare = instructions(SystickCounter::counts() - c0);
  if (status != PrepareStatus::Ok) {
    ++g_failures;
    Line().field("error").field(id).field(to_string(status)).print();
    return;
  }

  c0 = SystickCounter::counts();
  float sink = 0.0f;
  for (int r = 0; r < eval_repeats; ++r) {
    for (const EvalPoint& p : g_points) sink += g_plan.amplitude(p.position, p.direction);
  }
  const int64_t eval = instructions(SystickCounter::counts() - c0);
  if (!(sink >= 0.0f)) ++g_failures;  // amplitudes are in [0, 1]: keeps the loop alive too
  const uint32_t checksum = eval_checksum(g_plan, g_points, kEvalPoints);

  // The whole tick, for every table the pipeline's slot can hold.
  const PlanStats& stats = g_plan.stats();
  TickCost tick;
  int64_t pipeline_prepare = -1;
  if (stats.table_bytes <= kTableSlotBytes) {
    Condition condition;
    condition.scene = def;
    c0 = SystickCounter::counts();
    const PrepareStatus ps = g_pipeline.set_condition(condition);
    pipeline_prepare = instructions(SystickCounter::counts() - c0);
    if (ps == PrepareStatus::Ok) {
      tick = run_pipeline_stroke();
    } else if (ps == PrepareStatus::TooCostlyToPrepare) {
      pipeline_prepare = -1;  // priced past the watchdog's budget: refused before any work, as on the device
    } else {
      ++g_failures;
      Line().field("error").field(id).field(to_string(ps)).print();
      return;
    }
  }

  Line()
      .field("case").field(id).field(is_default(c) ? 1 : 0)
      .field(prepare).field(static_cast<int64_t>(stats.gradient_evaluations))
      .field(static_cast<int64_t>(stats.table_bytes)).field(static_cast<int64_t>(stats.plan_bytes))
      .field(eval).field(static_cast<int64_t>(eval_repeats) * kEvalPoints).field(static_cast<int64_t>(checksum))
      .field(tick.total).field(tick.ticks).field(tick.max).field(static_cast<int64_t>(tick.dac_sum))
      .field(pipeline_prepare)
      .print();
}

// Accumulates single measurements (each +-1 SysTick count = 40 instructions;
// over hundreds of calls the quantisation averages out).
struct Stopwatch {
  uint64_t counts = 0;
  int calls = 0;
  uint64_t start_ = 0;
  void start() { start_ = SystickCounter::counts(); }
  void stop() {
    counts += SystickCounter::counts() - start_;
    ++calls;
  }
};

// Instructions x 1000 that one empty start()/stop() pair adds (reading SysTick twice).
int64_t g_stopwatch_overhead_milli = 0;

void calibrate_stopwatch() {
  constexpr int kPairs = 4096;
  Stopwatch w;
  for (int i = 0; i < kPairs; ++i) {
    w.start();
    w.stop();
  }
  g_stopwatch_overhead_milli = instructions(w.counts) * 1000 / kPairs;
}

// Timed call by call (per_call) or as one block of w.calls calls.
void report_component(const char* name, const Stopwatch& w, bool per_call) {
  int64_t total = instructions(w.counts);
  if (per_call) total -= g_stopwatch_overhead_milli * w.calls / 1000;
  Line().field("component").field(name).field(total).field(w.calls).print();
}

// The pieces of a tick, measured alone, to say where a whole tick's time goes.
void measure_components() {
  calibrate_stopwatch();
  Line().text("# component,name,instr,count (timed one by one: minus the stopwatch's own instructions)").print();
  Line().field("stopwatch_overhead_milli").field(g_stopwatch_overhead_milli).print();
  {
    // The tracker as a scene that needs nothing uses it: presence and the last sample.
    Tracker tracker(TrackerConfig::recommended());
    const FingerStroke stroke(g_clock_us);
    Stopwatch on_sample, on_tick;
    for (int k = 0; k < FingerStroke::kMovingTicks; ++k) {
      SensorSample s;
      if (stroke.report_before(k, s)) {
        on_sample.start();
        tracker.on_sample(s);
        on_sample.stop();
      }
      on_tick.start();
      const bool present = tracker.on_tick(stroke.tick_time(k), false).present;
      on_tick.stop();
      if (!present) ++g_failures;
    }
    report_component("Tracker::on_sample (recommended(); per report)", on_sample, true);
    report_component("Tracker::on_tick need_filter=false (finger present)", on_tick, true);
    g_clock_us += FingerStroke::kDurationUs;
  }
  {
    Tracker tracker(TrackerConfig::recommended());
    const FingerStroke stroke(g_clock_us);
    Stopwatch on_tick;
    for (int k = 0; k < FingerStroke::kMovingTicks; ++k) {
      SensorSample s;
      if (stroke.report_before(k, s)) tracker.on_sample(s);
      on_tick.start();
      const bool present = tracker.on_tick(stroke.tick_time(k), true).present;
      on_tick.stop();
      if (!present) ++g_failures;
    }
    report_component("Tracker::on_tick need_filter=true (recommended())", on_tick, true);
    g_clock_us += FingerStroke::kDurationUs;
  }
  {
    Tracker tracker(TrackerConfig::recommended());
    Stopwatch on_tick;
    for (int k = 0; k < 256; ++k) {
      on_tick.start();
      const bool present = tracker.on_tick(g_clock_us + 500u * static_cast<uint32_t>(k), true).present;
      on_tick.stop();
      if (present) ++g_failures;
    }
    report_component("Tracker::on_tick without a finger", on_tick, true);
    g_clock_us += 256u * 500u;
  }
  {
    AmplitudeMap map;
    map.configure(AmplitudeSettings{});
    Stopwatch scale, code;
    uint32_t sum = 0;
    for (const EvalPoint& p : g_points) {
      const float raw = p.position.x * (1.0f / kScreenMaxX);
      scale.start();
      const float a = map.scale(raw);
      scale.stop();
      code.start();
      sum += map.dac_code(a);
      code.stop();
    }
    report_component("AmplitudeMap::scale (strength 1)", scale, true);
    report_component("AmplitudeMap::dac_code (linear calibration)", code, true);
    if (sum == 0) ++g_failures;
  }
  {
    SampleMailbox mailbox;
    SensorSample s;
    s.touch = true;
    Stopwatch post, take;
    for (int i = 0; i < kEvalPoints; ++i) {
      post.start();
      mailbox.post(s);
      post.stop();
      take.start();
      // Barriers: the inlined take is a few loads and stores, which the
      // compiler would otherwise move out of the timed region (it measured
      // below the stopwatch's own overhead).
      __asm__ volatile("" ::: "memory");
      const bool taken = mailbox.take(s);
      __asm__ volatile("" : : "r"(&s) : "memory");
      take.stop();
      if (!taken) ++g_failures;
    }
    report_component("SampleMailbox::post", post, true);
    report_component("SampleMailbox::take", take, true);
  }
  {
    // Field elements one by one (unit weight), as the closed form and the max|G| scan evaluate them.
    const FieldElement elements[] = {
        FieldElement::point_sink({700.0f, 40.0f}),
        FieldElement::path_sink(PathCurve::cubic(-200.0f), 0.2f),
        FieldElement::tunnel_valley(TunnelParams{}),
        FieldElement::vortex({400.0f, 240.0f}),
        FieldElement::saddle({400.0f, 240.0f}),
        FieldElement::sine_texture(160.0f, 160.0f, 20.0f),
    };
    const char* names[] = {"element_gradient point sink", "element_gradient path sink (cubic)",
                           "element_gradient tunnel", "element_gradient vortex", "element_gradient saddle",
                           "element_gradient sine texture"};
    for (int e = 0; e < 6; ++e) {
      Stopwatch w;
      float sink = 0.0f;
      w.start();
      for (const EvalPoint& p : g_points) sink += element_gradient(elements[e], p.position).x;
      w.stop();
      w.calls = kEvalPoints;
      if (!(sink == sink)) ++g_failures;  // NaN check; keeps the loop
      report_component(names[e], w, false);
    }
  }
  {
    // An empty tick: no finger (idle code), the neutral scene.
    Condition neutral;
    if (g_pipeline.set_condition(neutral) != PrepareStatus::Ok) ++g_failures;
    Stopwatch w;
    w.start();
    for (int k = 0; k < FingerStroke::kMovingTicks; ++k) g_pipeline.tick(g_clock_us + 500u * static_cast<uint32_t>(k));
    w.stop();
    w.calls = FingerStroke::kMovingTicks;
    report_component("HapticPipeline::tick without a finger", w, false);
    g_clock_us += FingerStroke::kDurationUs;
  }
}

bool smoke_case(const BenchCase& c) {
  return c.strategy.evaluation == Evaluation::ClosedForm ||
         (c.strategy.table.spacing_px == 8.0f && c.strategy.table.storage == TableStorage::Int16 &&
          c.strategy.table.source == TableSource::TabulatedGradient);
}

}  // namespace

int main() {
  SystickCounter::start();
  char command[64];
  ff::m4::command_line(command, sizeof(command));
  const bool smoke = std::strstr(command, "smoke") != nullptr;

  g_instructions_per_count = ff::m4::calibrate_instructions_per_count();
  Line().field("m4bench").field(smoke ? "smoke" : "full").print();
  Line().field("calibration").field(static_cast<int64_t>(g_instructions_per_count)).print();
  if (g_instructions_per_count == 0) {
    ff::m4::write_text("M4BENCH FAULT: SysTick does not count (run qemu with -icount shift=0)\n");
    return 1;
  }
  Line().text("# case,id,default,prepare_instr,gradient_evaluations,table_bytes,plan_bytes,"
              "eval_instr,evaluations,eval_checksum,tick_instr,ticks,tick_max_instr,tick_dac_sum,"
              "pipeline_prepare_instr").print();

  make_eval_points(g_points);
  for (int i = 0; i < case_count(); ++i) {
    const BenchCase c = case_at(i);
    if (smoke && !smoke_case(c)) continue;
    measure_case(c, smoke ? 1 : 8);
  }

  // A new sensor profile: the main loop derives the fade's noise
  // (fade_noise_instr), the tick then configures the tracker with it
  // (configure_instr).
  Line().text("# tracker,name,instr,ticks,max_instr,configure_instr,fade_noise_instr").print();
  for (int i = 0; i < kTrackerConfigCount; ++i) {
    const TrackerConfig config = tracker_config(i);
    Tracker tracker(config);
    uint64_t c0 = SystickCounter::counts();
    const FadeNoise fade = fade_noise(config);
    const int64_t derive = instructions(SystickCounter::counts() - c0);
    c0 = SystickCounter::counts();
    tracker.configure(config, fade);
    const int64_t configure = instructions(SystickCounter::counts() - c0);
    const TickCost cost = run_tracker_stroke(tracker);
    Line()
        .field("tracker")
        .field(tracker_config_name(i))
        .field(cost.total)
        .field(cost.ticks)
        .field(cost.max)
        .field(configure)
        .field(derive)
        .print();
  }

  measure_components();

  Line().field("done").field(g_failures).print();
  return g_failures == 0 ? 0 : 1;
}
