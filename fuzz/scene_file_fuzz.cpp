// libFuzzer target: the scene file parser (host/scene_file). Whatever the
// text: no crash; a rejected file says which line; an accepted one formats
// to text that parses back to the same text (a fixpoint); the core either
// refuses the scene or prepares it, and then renders every point of the
// screen, and a finger moving over it, finite and inside [0, 1].
//
// Build: clang++ -fsanitize=fuzzer,address,undefined with ff_host + ff_core.
// FF_FUZZ_NO_ENTRY leaves out LLVMFuzzerTestOneInput for the regression test.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/host/scene_file.hpp"

namespace ff::fuzz {

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "scene_file_fuzz: %s\n", what);
    std::abort();
  }
}

}  // namespace

int scene_file_one_input(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  SceneDefinition scene;
  std::string error;
  if (!host::parse_scene_text(text, scene, error)) {
    check(error.rfind("line ", 0) == 0, "a rejected scene does not name its line");
    return 0;
  }
  const std::string formatted = host::format_scene_text(scene);
  SceneDefinition again;
  check(host::parse_scene_text(formatted, again, error), "the formatted scene does not parse");
  check(host::format_scene_text(again) == formatted, "format(parse(format(s))) != format(s)");

  auto pipeline = std::make_unique<HapticPipeline>();
  Condition condition;
  condition.scene = scene;
  if (pipeline->set_condition(condition) != PrepareStatus::Ok) return 0;  // refused: nothing changes
  const ScenePlan& plan = pipeline->plan();
  check(std::isfinite(plan.stats().max_gradient) && plan.stats().max_gradient >= 0.0f, "max|G| not finite");
  const Vec2 directions[] = {{1, 0}, {0, 1}, {-0.6f, 0.8f}, {0, 0}};
  for (float y = 0.0f; y <= kScreenMaxY; y += 47.9f) {
    for (float x = 0.0f; x <= kScreenMaxX; x += 79.9f) {
      for (const Vec2& d : directions) {
        const float a = plan.amplitude({x, y}, d);
        check(a >= 0.0f && a <= 1.0f, "raw amplitude not finite or outside [0, 1]");
        check(is_finite(plan.normalized_gradient({x, y})), "normalised gradient not finite");
      }
    }
  }
  // A finger crossing the screen diagonally, 200 Hz reports, 2 kHz ticks.
  for (uint32_t k = 0; k < 800; ++k) {
    const uint32_t now = k * kTickPeriodUs;
    if (k % 10 == 0) pipeline->post_sample({now, static_cast<float>(k), static_cast<float>(k) * 0.6f, true});
    const TickOutput t = pipeline->tick(now);
    check(std::isfinite(t.amplitude) && t.amplitude >= 0.0f && t.amplitude <= 1.0f, "tick amplitude outside [0, 1]");
    check(t.dac <= kDacMax, "DAC code above 4095");
  }
  return 0;
}

}  // namespace ff::fuzz

#ifndef FF_FUZZ_NO_ENTRY
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return ff::fuzz::scene_file_one_input(data, size);
}
#endif
