#include "frictionfield/host/scene_hash.hpp"

#include <cstdio>
#include <cstring>

namespace ff::host {

namespace {

class Fnv1a64 {
 public:
  void byte(uint8_t b) {
    hash_ ^= b;
    hash_ *= 0x100000001b3ull;
  }
  void u32(uint32_t v) {
    for (int i = 0; i < 4; ++i) byte(static_cast<uint8_t>(v >> (8 * i)));
  }
  void f32(float v) {
    if (v == 0.0f) v = 0.0f;  // -0 and 0 define the same value
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    u32(bits);
  }
  void vec(Vec2 v) {
    f32(v.x);
    f32(v.y);
  }
  uint64_t value() const { return hash_; }

 private:
  uint64_t hash_ = 0xcbf29ce484222325ull;
};

void add_curve(Fnv1a64& h, const PathCurve& c) {
  h.byte(static_cast<uint8_t>(c.kind));
  for (float v : {c.x0, c.y0, c.length, c.rise, c.amplitude, c.wavelength}) h.f32(v);
  h.byte(c.count);
  for (int i = 0; i < c.count && i < kMaxPolylinePoints; ++i) h.vec(c.points[i]);
}

// Only the parameters of the element's kind, so another kind's defaults
// cannot make two identical definitions differ (a kind's own parameters count
// even where the rendering does not read them).
void add_element(Fnv1a64& h, const FieldElement& e) {
  h.byte(static_cast<uint8_t>(e.kind));
  h.f32(e.weight);
  switch (e.kind) {
    case ElementKind::PointSink:
      h.vec(e.point.centre);
      h.f32(e.point.radius);
      h.f32(e.point.feather);
      break;
    case ElementKind::PathSink:
      add_curve(h, e.valley.curve);
      for (float v : {e.valley.a, e.valley.band_half_width, e.valley.band_feather}) h.f32(v);
      break;
    case ElementKind::Tunnel:
      for (float v : {e.tunnel.x_start, e.tunnel.length, e.tunnel.width_start, e.tunnel.width_end, e.tunnel.scale,
                      e.tunnel.y_centre})
        h.f32(v);
      break;
    case ElementKind::Vortex:
    case ElementKind::Saddle:
      h.vec(e.point.centre);
      break;
    case ElementKind::Texture:
      for (float v : {e.texture.wavelength_x, e.texture.wavelength_y, e.texture.height}) h.f32(v);
      break;
  }
}

}  // namespace

uint64_t condition_hash(const Condition& c) {
  Fnv1a64 h;
  const SceneDefinition& s = c.scene;
  h.byte(static_cast<uint8_t>(s.rendering));
  if (s.rendering == Rendering::Constant) h.f32(s.constant);
  if (s.rendering == Rendering::PositionOnly) h.f32(s.bias);
  h.byte(static_cast<uint8_t>(s.evaluation));
  if (s.evaluation == Evaluation::Table) {
    h.f32(s.table.spacing_px);
    h.byte(static_cast<uint8_t>(s.table.storage));
    h.byte(static_cast<uint8_t>(s.table.source));
  }
  h.byte(s.element_count);
  for (int i = 0; i < s.element_count && i < kMaxSceneElements; ++i) add_element(h, s.elements[i]);
  const SampledHeightMap& m = s.sampled;
  const bool sampled = m.heights != nullptr && m.cols > 0 && m.rows > 0;
  h.byte(sampled ? 1 : 0);
  if (sampled) {
    h.u32(m.cols);
    h.u32(m.rows);
    h.f32(m.spacing_px);
    for (uint32_t i = 0; i < uint32_t{m.cols} * m.rows; ++i) h.f32(m.heights[i]);
  }
  const AmplitudeSettings& a = c.amplitude;
  for (float v : {a.strength, a.s_curve, a.idle_amplitude}) h.f32(v);
  h.byte(a.calibration.count);
  for (int i = 0; i < a.calibration.count && i < kMaxCalibrationPoints; ++i) {
    h.f32(a.calibration.amplitude[i]);
    h.f32(a.calibration.code[i]);
  }
  return h.value();
}

std::string hash_hex(uint64_t hash) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash));
  return buf;
}

}  // namespace ff::host
