#include "frictionfield/core/scenes.hpp"

namespace ff::scenes {

namespace {

// A position-only scene of one slippery band along `curve`: fully slippery
// for |u| <= 10 px, a 20 px quintic feather, sticky beyond (docs/spec.md#frictionmap).
SceneDefinition slippery_band(const PathCurve& curve) {
  SceneDefinition s;
  s.rendering = Rendering::PositionOnly;
  FieldElement band = FieldElement::path_sink(curve, 0.2f, 1.0f);
  band.valley.band_half_width = 10.0f;
  band.valley.band_feather = 20.0f;
  s.add(band);
  return s;
}

}  // namespace

SceneDefinition heightmap(Target target) {
  // Thesis eq. E.1-E.4: Z = 1/2 Z_path + 1/2 Z_cone, a = 1/5.
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  s.add(FieldElement::path_sink(PathCurve::cubic(target_rise(target)), 0.2f, 0.5f));
  s.add(FieldElement::point_sink(target_point(target), 0.5f));
  return s;
}

SceneDefinition frictionmap(Target target) {
  // A = S5((30 - |u|) / 20): slippery for |u| <= 10, sticky beyond 30.
  return slippery_band(PathCurve::cubic(target_rise(target)));
}

SceneDefinition neutral() {
  SceneDefinition s;
  s.rendering = Rendering::Constant;
  s.constant = 0.5f;
  return s;
}

SceneDefinition steering_tunnel(const TunnelParams& tunnel, TunnelMode mode) {
  if (mode == TunnelMode::Neutral) return neutral();
  // Converging renders grad H (downhill towards the centre line is slippery);
  // diverging renders -grad H.
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  s.add(FieldElement::tunnel_valley(tunnel, mode == TunnelMode::Converging ? 1.0f : -1.0f));
  return s;
}

SceneDefinition pilot_c_valley(Target target) {
  // Width 20, s = 10: a = s / w = 1/2, H = |2 atan(u/2) - u|.
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  s.add(FieldElement::path_sink(PathCurve::cubic(target_rise(target)), 0.5f, 1.0f));
  return s;
}

SceneDefinition familiarisation_path() {
  return slippery_band(PathCurve::sine(240.0f, 120.0f, 400.0f, 0.0f));  // a winding low-friction path
}

SceneDefinition bump_map() {
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  s.add(FieldElement::sine_texture(160.0f, 160.0f, 20.0f));
  return s;
}

SceneDefinition vortex() {
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  s.add(FieldElement::vortex({400.0f, 240.0f}));
  return s;
}

}  // namespace ff::scenes
