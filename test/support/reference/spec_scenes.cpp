#include "support/reference/spec_scenes.hpp"

#include <initializer_list>

namespace ff::reference::spec {

namespace {

PathCurve cubic(double rise) {
  PathCurve c;
  c.kind = CurveKind::Cubic;
  c.x0 = 100.0f;
  c.y0 = 240.0f;
  c.length = 600.0f;
  c.rise = static_cast<float>(rise);
  return c;
}

FieldElement valley(const PathCurve& curve, float a, float weight) {
  FieldElement e;
  e.kind = ElementKind::PathSink;
  e.weight = weight;
  e.valley.curve = curve;
  e.valley.a = a;
  e.valley.band_half_width = 10.0f;  // the frictionmap's band: |u| <= 10 slippery,
  e.valley.band_feather = 20.0f;     // sticky from 30
  return e;
}

SceneDefinition directional(std::initializer_list<FieldElement> elements) {
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  for (const FieldElement& e : elements) s.elements[s.element_count++] = e;
  return s;
}

SceneDefinition band_along(const PathCurve& curve) {
  SceneDefinition s;
  s.rendering = Rendering::PositionOnly;
  s.bias = 0.0f;
  s.elements[s.element_count++] = valley(curve, 0.2f, 1.0f);
  return s;
}

}  // namespace

SceneDefinition heightmap(double rise) {
  FieldElement cone;
  cone.kind = ElementKind::PointSink;
  cone.weight = 0.5f;
  cone.point.centre = {700.0f, static_cast<float>(240.0 + rise)};
  return directional({valley(cubic(rise), 0.2f, 0.5f), cone});
}

SceneDefinition frictionmap(double rise) { return band_along(cubic(rise)); }

SceneDefinition pilot_c(double rise) { return directional({valley(cubic(rise), 0.5f, 1.0f)}); }

SceneDefinition steering_tunnel(double scale) {
  FieldElement e;
  e.kind = ElementKind::Tunnel;
  e.weight = 1.0f;
  e.tunnel.x_start = 100.0f;
  e.tunnel.length = 400.0f;
  e.tunnel.width_start = 60.0f;
  e.tunnel.width_end = 20.0f;
  e.tunnel.scale = static_cast<float>(scale);
  e.tunnel.y_centre = 240.0f;
  return directional({e});
}

SceneDefinition bump_map() {
  FieldElement e;
  e.kind = ElementKind::Texture;
  e.weight = 1.0f;
  e.texture.wavelength_x = 160.0f;
  e.texture.wavelength_y = 160.0f;
  e.texture.height = 20.0f;
  return directional({e});
}

SceneDefinition vortex() {
  FieldElement e;
  e.kind = ElementKind::Vortex;
  e.weight = 1.0f;
  e.point.centre = {400.0f, 240.0f};
  return directional({e});
}

SceneDefinition familiarisation_path() {
  PathCurve c;
  c.kind = CurveKind::Sine;
  c.x0 = 0.0f;
  c.y0 = 240.0f;
  c.amplitude = 120.0f;
  c.wavelength = 400.0f;
  return band_along(c);
}

SceneDefinition neutral() {
  SceneDefinition s;
  s.rendering = Rendering::Constant;
  s.constant = 0.5f;
  return s;
}

}  // namespace ff::reference::spec
