// float32 against the double reference (stress_precision.hpp, written from
// docs/spec.md#elements): the rendering of every closed-form scene at random positions and
// directions, the core's max|G|, and the whole thesis chain (tracking +
// rendering) on random clean traces. The worst deviations are printed and bounded.
#include "stress_precision.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "stress_classes.hpp"
#include "stress_random.hpp"

#ifndef FF_STRESS_TEST_CASES
#define FF_STRESS_TEST_CASES 12
#endif

namespace ff::stress {
namespace {

constexpr double kGeneralSceneMaxGradientBound = 0.06;

TEST(Precision, ClosedFormRenderingAgainstDouble) {
  const RenderingPrecision r = rendering_precision(base_seed(), cases_or(FF_STRESS_TEST_CASES) * 10);
  std::printf("[precision] %d closed-form scenes, %llu evaluations: worst |A_float - A_double| %.3g; max|G| relative "
              "error: thesis scenes %.3g, general scenes %.3g\n", r.scenes, static_cast<unsigned long long>(r.evaluations),
              r.worst_amplitude, r.worst_max_builtin, r.worst_max_general);
  EXPECT_LE(r.worst_amplitude, 1e-4);
  EXPECT_LE(r.worst_max_builtin, 1e-4);
  // Random general scenes: the scan + compass search is a heuristic there (a
  // narrow peak between 32 px nodes can be missed); the stress report measures
  // 4.1 % to 5.5 % over 1000 such scenes, depending on the draw (docs/stress.md). The thesis' scenes
  // above, which the studies use, are held to 1e-4.
  EXPECT_LE(r.worst_max_general, kGeneralSceneMaxGradientBound) << r.worst_max_scene;
}

TEST(Precision, ThesisChainAgainstDouble) {
  // The thesis tracker (docs/spec.md#thesis-tracker) and the heightmap, float32 end to end, against the
  // same chain in double on the same clean reports.
  const ChainPrecision r = thesis_chain_precision(base_seed(), cases_or(FF_STRESS_TEST_CASES));
  std::printf("[precision] thesis chain, %d traces, %llu ticks (%llu moving): worst position %.3g px, worst amplitude %.3g\n",
              r.traces, static_cast<unsigned long long>(r.ticks), static_cast<unsigned long long>(r.moving_ticks),
              r.worst_position, r.worst_amplitude);
  EXPECT_LE(r.worst_position, 0.005);
  EXPECT_LE(r.worst_amplitude, 0.005);
}

}  // namespace
}  // namespace ff::stress
