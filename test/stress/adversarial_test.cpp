// Hand-derived answers to single adversarial inputs (the classes in
// stress_classes.cpp cover each kind at random; these pin exact values).
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>
#include <memory>

#include "frictionfield/core/haptic_pipeline.hpp"
#include "frictionfield/core/scenes.hpp"

namespace ff {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

std::unique_ptr<HapticPipeline> with(const SceneDefinition& scene, float strength = 1.0f) {
  auto p = std::make_unique<HapticPipeline>();
  Condition c;
  c.scene = scene;
  c.amplitude.strength = strength;
  p->set_condition(c);
  return p;
}

// A finger moving right at 300 px/s along y = 240 for `ticks` ticks.
TickOutput stroke(HapticPipeline& p, int ticks, uint32_t t0 = 0) {
  TickOutput out;
  for (int k = 0; k < ticks; ++k) {
    const uint32_t t = t0 + static_cast<uint32_t>(k) * kTickPeriodUs;
    if (k % 10 == 0) p.post_sample({t, 100.0f + 300.0f * static_cast<float>(k) * 5e-4f, 240.0f, true});
    out = p.tick(t);
  }
  return out;
}

TEST(Adversarial, StrengthWithoutMeaningRendersNoModulation) {
  // NaN, 0, -0 and negative strengths: A_s = 0.5 + 0 (A - 0.5) = 0.5 exactly, code round(2047.5) = 2048.
  for (float s : {kNaN, 0.0f, -0.0f, -1.0f, -kInf}) {
    auto p = with(scenes::heightmap(Target::Top), s);
    const TickOutput t = stroke(*p, 400);
    EXPECT_TRUE(t.present);
    EXPECT_EQ(t.amplitude, 0.5f) << s;
    EXPECT_EQ(t.dac, 2048) << s;
    EXPECT_EQ(p->faults()[Fault::BadStrength], 1u);
  }
}

TEST(Adversarial, StrengthAboveOneActsAsOne) {
  auto one = with(scenes::heightmap(Target::Bottom), 1.0f);
  for (float s : {1.0000001f, 1.5f, 1e30f, kInf}) {
    auto p = with(scenes::heightmap(Target::Bottom), s);
    for (int k = 0; k < 400; ++k) {
      const uint32_t t = static_cast<uint32_t>(k) * kTickPeriodUs;
      if (k % 10 == 0) {
        p->post_sample({t, 100.0f + 0.15f * static_cast<float>(k), 240.0f, true});
        if (s == 1.5f) one->post_sample({t, 100.0f + 0.15f * static_cast<float>(k), 240.0f, true});
      }
      const TickOutput a = p->tick(t);
      if (s == 1.5f) {
        const TickOutput b = one->tick(t);
        EXPECT_EQ(a.amplitude, b.amplitude);
        EXPECT_EQ(a.dac, b.dac);
      }
      EXPECT_LE(a.amplitude, 1.0f);
      EXPECT_GE(a.amplitude, 0.0f);
    }
  }
}

TEST(Adversarial, FieldsThatCancelRenderExactlyHalf) {
  // A cone and an equal source on the same point: G = 0 everywhere, max|G| = 0.
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  s.add(FieldElement::point_sink({300.0f, 200.0f}, 2.5f));
  s.add(FieldElement::point_sink({300.0f, 200.0f}, -2.5f));
  auto p = with(s);
  EXPECT_EQ(p->plan().stats().max_gradient, 0.0f);
  const TickOutput t = stroke(*p, 400);
  EXPECT_EQ(t.amplitude, 0.5f);
  EXPECT_EQ(t.dac, 2048);
}

TEST(Adversarial, SingularPointsHaveNoGradient) {
  // Exactly on the apex of the heightmap's cone (the target, where u = 0 too),
  // a vortex's centre and a saddle's centre: G = 0, so A = 0.5 for any direction.
  const Vec2 dirs[] = {{1.0f, 0.0f}, {0.0f, -1.0f}, {-0.6f, 0.8f}};
  auto heightmap = with(scenes::heightmap(Target::Middle));
  auto vortex = with(scenes::vortex());
  SceneDefinition saddle;
  saddle.rendering = Rendering::Directional;
  saddle.add(FieldElement::saddle({123.5f, 321.25f}));
  auto sad = with(saddle);
  for (const Vec2& d : dirs) {
    EXPECT_EQ(heightmap->plan().amplitude({700.0f, 240.0f}, d), 0.5f);
    EXPECT_EQ(vortex->plan().amplitude({400.0f, 240.0f}, d), 0.5f);
    EXPECT_EQ(sad->plan().amplitude({123.5f, 321.25f}, d), 0.5f);
  }
}

TEST(Adversarial, NonFiniteAndFarCoordinatesAreDroppedAndCounted) {
  auto p = with(scenes::heightmap(Target::Top));
  stroke(*p, 100);
  const TickOutput before = p->tick(50000);
  const float bad[][2] = {{kNaN, 240.0f}, {300.0f, kInf}, {-kInf, kNaN}, {1e6f, 240.0f}, {-1e6f, -1e6f}, {FLT_MAX, 0.0f}};
  uint32_t t = 50001;
  for (const auto& b : bad) p->post_sample({t++, b[0], b[1], true});
  TickOutput after;
  for (uint32_t k = 1; k <= 6; ++k) after = p->tick(50000 + k * 500);  // one report per tick
  EXPECT_EQ(p->faults()[Fault::NonFiniteCoordinate], 3u);
  EXPECT_EQ(p->faults()[Fault::OffScreen], 3u);
  EXPECT_TRUE(std::isfinite(after.position.x) && std::isfinite(after.position.y));
  EXPECT_NEAR(static_cast<double>(after.position.x), static_cast<double>(before.position.x), 1.0);  // held on the track
}

TEST(Adversarial, SubnormalCoordinatesAreOrdinaryEdgePositions) {
  // 1e-40 px is on the screen (at its left edge): a touch-down there, finite output.
  auto p = with(scenes::heightmap(Target::Top));
  p->post_sample({0, 1e-40f, FLT_TRUE_MIN, true});
  const TickOutput t = p->tick(0);
  EXPECT_TRUE(t.present);
  EXPECT_GE(t.position.x, 0.0f);
  EXPECT_LE(t.position.x, 1e-3f);
  EXPECT_TRUE(std::isfinite(t.amplitude));
}

TEST(Adversarial, MailboxBacklogIsCountedPostByPost) {
  auto p = with(scenes::heightmap(Target::Top));
  int refused = 0;
  for (uint32_t i = 0; i < 100; ++i) refused += p->post_sample({i * 10u, 100.0f + 0.01f * static_cast<float>(i), 240.0f, true}) ? 0 : 1;
  EXPECT_EQ(refused, 100 - static_cast<int>(SampleMailbox::kCapacity));
  EXPECT_EQ(p->faults()[Fault::MailboxOverflow], static_cast<uint32_t>(refused));
  EXPECT_TRUE(p->tick(1000).present);
  EXPECT_TRUE(p->post_sample({1010, 101.0f, 240.0f, true}));  // room again after the tick
}

TEST(Adversarial, TenMinutesWithoutTicksLoseTheFingerAndIdle) {
  auto p = with(scenes::heightmap(Target::Top));
  stroke(*p, 100);
  // The next ticks ten minutes later: a single leap may be a corrupted timer
  // read (the core repeats its state until a second tick confirms the new
  // time); the confirmed one finds the last report 10 min old: lift-off.
  const uint32_t later = 600u * 1000000u;
  p->tick(later);
  const TickOutput t = p->tick(later + 500u);
  EXPECT_FALSE(t.present);
  EXPECT_EQ(t.amplitude, 0.0f);
  EXPECT_EQ(t.dac, 0);
  const TickOutput back = stroke(*p, 400, later + 1000u);  // a new touch-down tracks again
  EXPECT_TRUE(back.present);
  EXPECT_GT(back.amplitude, 0.5f);  // moving right along the path towards the target: assisted
}

}  // namespace
}  // namespace ff
