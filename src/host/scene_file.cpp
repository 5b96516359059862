#include "frictionfield/host/scene_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "frictionfield/host/input_file.hpp"

namespace ff::host {

namespace {

class Words {
 public:
  explicit Words(const std::string& line) {
    std::istringstream s(line.substr(0, line.find('#')));
    std::string w;
    while (s >> w) words_.push_back(w);
  }
  bool empty() const { return words_.empty(); }
  bool done() const { return next_ >= words_.size(); }
  std::string take() { return done() ? std::string() : words_[next_++]; }
  bool number(float& out) {
    if (done()) return false;
    const std::string& w = words_[next_];
    char* end = nullptr;
    const float v = std::strtof(w.c_str(), &end);
    if (end == w.c_str() || end != w.c_str() + w.size() || !std::isfinite(v)) return false;
    out = v;
    ++next_;
    return true;
  }
  bool point(Vec2& out) {  // "x,y", after peek_point()
    const std::string& w = words_[next_];
    char* end = nullptr;
    const float x = std::strtof(w.c_str(), &end);
    if (end == w.c_str() || *end != ',') return false;
    const char* ys = end + 1;
    const float y = std::strtof(ys, &end);
    if (end == ys || end != w.c_str() + w.size() || !std::isfinite(x) || !std::isfinite(y)) return false;
    out = {x, y};
    ++next_;
    return true;
  }
  bool peek_point() const {
    return !done() && words_[next_].find(',') != std::string::npos;
  }

 private:
  std::vector<std::string> words_;
  size_t next_ = 0;
};

bool parse_curve(Words& w, PathCurve& curve, std::string& err) {
  const std::string kind = w.take();
  if (kind == "cubic") {
    float rise, x0 = 100.0f, y0 = 240.0f, length = 600.0f;
    if (!w.number(rise)) return err = "curve cubic needs the rise T (e.g. -200) [x0 y0 length]", false;
    if (w.number(x0) && !(w.number(y0) && w.number(length))) {
      return err = "curve cubic takes T, or T x0 y0 length", false;
    }
    curve = PathCurve::cubic(rise, x0, y0, length);
    return true;
  }
  if (kind == "sine") {
    float y0, amp, wavelength, x0 = 0.0f;
    if (!w.number(y0) || !w.number(amp) || !w.number(wavelength)) {
      return err = "curve sine needs y0 amplitude wavelength [x0]", false;
    }
    w.number(x0);
    curve = PathCurve::sine(y0, amp, wavelength, x0);
    return true;
  }
  if (kind == "polyline") {
    Vec2 pts[kMaxPolylinePoints];
    int n = 0;
    while (w.peek_point()) {
      if (n == kMaxPolylinePoints) return err = "polyline has more than 16 points", false;
      if (!w.point(pts[n++])) return err = "polyline points are x,y pairs", false;
    }
    curve = PathCurve::polyline(pts, n);
    if (curve.count == 0) return err = "polyline needs 2..16 points with increasing x", false;
    return true;
  }
  return err = "unknown curve '" + kind + "' (cubic, sine, polyline)", false;
}

std::string number_text(float v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

// Values a scene cannot mean are refused with the key that carries them, as
// the core's preparation (ScenePlan::prepare) would refuse them later without
// a line: a feather of 0 is a step the profile's smoothstep divides by.
bool check_element(const FieldElement& e, const std::string& kind, std::string& err) {
  struct Bound { const char* key; float value; bool zero_ok; };
  const Bound bounds[] = {
      {"radius", e.point.radius, true},       {"feather", e.point.feather, false},
      {"a", e.valley.a, false},               {"band", e.valley.band_half_width, true},
      {"band", e.valley.band_feather, false}, {"length", e.tunnel.length, false},
      {"width", e.tunnel.width_start, false}, {"width", e.tunnel.width_end, false},
      {"scale", e.tunnel.scale, false},       {"wavelength", e.texture.wavelength_x, false},
      {"wavelength", e.texture.wavelength_y, false},
  };
  for (const Bound& b : bounds) {
    if (b.zero_ok ? b.value < 0.0f : b.value <= 0.0f) {
      err = std::string("element ") + kind + ": '" + b.key + "' " + number_text(b.value) + " must be " +
            (b.zero_ok ? ">= 0" : "> 0");
      return false;
    }
  }
  if (e.kind == ElementKind::PathSink && e.valley.curve.kind == CurveKind::Sine && !(e.valley.curve.wavelength > 0.0f)) {
    return err = "curve sine: the wavelength must be > 0", false;
  }
  if (e.kind == ElementKind::PathSink && e.valley.curve.kind == CurveKind::Cubic && !(e.valley.curve.length > 0.0f)) {
    return err = "curve cubic: the length L " + number_text(e.valley.curve.length) + " must be > 0", false;
  }
  return true;
}

bool parse_element(Words& w, FieldElement& e, std::string& err) {
  const std::string kind = w.take();
  if (kind == "point_sink") e.kind = ElementKind::PointSink;
  else if (kind == "path_sink") e.kind = ElementKind::PathSink;
  else if (kind == "tunnel") e.kind = ElementKind::Tunnel;
  else if (kind == "vortex") e.kind = ElementKind::Vortex;
  else if (kind == "saddle") e.kind = ElementKind::Saddle;
  else if (kind == "texture") e.kind = ElementKind::Texture;
  else return err = "unknown element '" + kind + "'", false;

  while (!w.done()) {
    const std::string key = w.take();
    bool ok = true;
    if (key == "weight") ok = w.number(e.weight);
    else if (key == "centre" || key == "center") ok = w.number(e.point.centre.x) && w.number(e.point.centre.y);
    else if (key == "radius") ok = w.number(e.point.radius);
    else if (key == "feather") ok = w.number(e.point.feather);
    else if (key == "a") ok = w.number(e.valley.a);
    else if (key == "curve") { if (!parse_curve(w, e.valley.curve, err)) return false; }
    else if (key == "band") ok = w.number(e.valley.band_half_width) && w.number(e.valley.band_feather);
    else if (key == "x_start") ok = w.number(e.tunnel.x_start);
    else if (key == "length") ok = w.number(e.tunnel.length);
    else if (key == "width") ok = w.number(e.tunnel.width_start) && w.number(e.tunnel.width_end);
    else if (key == "scale") ok = w.number(e.tunnel.scale);
    else if (key == "y_centre" || key == "y_center") ok = w.number(e.tunnel.y_centre);
    else if (key == "wavelength") ok = w.number(e.texture.wavelength_x) && w.number(e.texture.wavelength_y);
    else if (key == "height") ok = w.number(e.texture.height);
    else return err = "unknown key '" + key + "' for element " + kind, false;
    if (!ok) return err = "'" + key + "' needs finite number(s)", false;
  }
  return check_element(e, kind, err);
}

}  // namespace

bool parse_scene_text(const std::string& text, SceneDefinition& out, std::string& error) {
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  auto fail = [&](const std::string& msg) {
    error = "line " + std::to_string(line_no) + ": " + msg;
    return false;
  };
  bool any_directive = false;
  while (std::getline(in, line)) {
    ++line_no;
    Words w(line);
    if (w.empty()) continue;
    any_directive = true;
    const std::string key = w.take();
    std::string err;
    if (key == "rendering") {
      const std::string r = w.take();
      if (r == "constant") s.rendering = Rendering::Constant;
      else if (r == "position") s.rendering = Rendering::PositionOnly;
      else if (r == "directional") s.rendering = Rendering::Directional;
      else return fail("rendering is constant, position or directional (got '" + r + "')");
    } else if (key == "constant") {
      if (!w.number(s.constant)) return fail("constant needs a number");
      if (!(s.constant >= 0.0f && s.constant <= 1.0f)) {
        return fail("constant " + number_text(s.constant) + " is outside [0, 1] (an amplitude)");
      }
    } else if (key == "bias") {
      if (!w.number(s.bias)) return fail("bias needs a number");
      if (!(s.bias >= -1.0f && s.bias <= 1.0f)) return fail("bias " + number_text(s.bias) + " is outside [-1, 1]");
    } else if (key == "evaluation") {
      const std::string e = w.take();
      if (e == "closed") {
        s.evaluation = Evaluation::ClosedForm;
      } else if (e == "table") {
        s.evaluation = Evaluation::Table;
        if (!w.number(s.table.spacing_px)) return fail("evaluation table needs the spacing in px");
        if (!(s.table.spacing_px >= 1.0f && s.table.spacing_px <= 100.0f)) {
          return fail("table spacing " + number_text(s.table.spacing_px) + " is outside [1, 100] px");
        }
        const std::string storage = w.take();
        if (storage == "int16" || storage.empty()) s.table.storage = TableStorage::Int16;
        else if (storage == "float") s.table.storage = TableStorage::Float32;
        else return fail("table storage is int16 or float");
        const std::string source = w.take();
        if (source == "gradient" || source.empty()) s.table.source = TableSource::TabulatedGradient;
        else if (source == "height") s.table.source = TableSource::HeightCentralDifferences;
        else return fail("table source is gradient or height");
      } else {
        return fail("evaluation is closed or table");
      }
    } else if (key == "element") {
      FieldElement e;
      if (!parse_element(w, e, err)) return fail(err);
      if (!s.add(e)) return fail("more than 8 elements");
    } else {
      return fail("unknown directive '" + key + "'");
    }
    if (!w.done()) return fail("unexpected '" + w.take() + "'");
  }
  // An empty scene would silently render flat: say so instead.
  line_no = std::max(line_no, 1);  // errors name a line, also for an empty text
  if (!any_directive) return fail("no directives: a scene needs at least 'rendering ...' (see docs)");
  if (s.rendering != Rendering::Constant && s.element_count == 0) {
    return fail("a position or directional scene needs at least one 'element' line");
  }
  out = s;
  return true;
}

bool read_scene_file(const std::string& path, SceneDefinition& out, std::string& error) {
  std::ifstream in;
  std::string why;
  if (!open_input_file(path, in, why)) {
    error = path + ": " + why;
    return false;
  }
  std::stringstream buf;
  buf << in.rdbuf();
  if (!parse_scene_text(buf.str(), out, error)) {
    error = path + ": " + error;
    return false;
  }
  return true;
}

std::string format_scene_text(const SceneDefinition& s) {
  std::ostringstream o;
  o.precision(9);
  const char* r = s.rendering == Rendering::Constant ? "constant"
                  : s.rendering == Rendering::PositionOnly ? "position" : "directional";
  o << "rendering " << r << "\n";
  if (s.rendering == Rendering::Constant) o << "constant " << s.constant << "\n";
  if (s.rendering == Rendering::PositionOnly) o << "bias " << s.bias << "\n";
  if (s.evaluation == Evaluation::Table) {
    o << "evaluation table " << s.table.spacing_px << ' '
      << (s.table.storage == TableStorage::Int16 ? "int16" : "float") << ' '
      << (s.table.source == TableSource::TabulatedGradient ? "gradient" : "height") << "\n";
  }
  for (int i = 0; i < s.element_count; ++i) {
    const FieldElement& e = s.elements[i];
    o << "element ";
    switch (e.kind) {
      case ElementKind::PointSink:
        o << "point_sink weight " << e.weight << " centre " << e.point.centre.x << ' ' << e.point.centre.y
          << " radius " << e.point.radius << " feather " << e.point.feather;
        break;
      case ElementKind::PathSink: {
        const PathCurve& c = e.valley.curve;
        o << "path_sink weight " << e.weight << " a " << e.valley.a << " band " << e.valley.band_half_width
          << ' ' << e.valley.band_feather << " curve ";
        if (c.kind == CurveKind::Cubic) o << "cubic " << c.rise << ' ' << c.x0 << ' ' << c.y0 << ' ' << c.length;
        else if (c.kind == CurveKind::Sine) o << "sine " << c.y0 << ' ' << c.amplitude << ' ' << c.wavelength << ' ' << c.x0;
        else {
          o << "polyline";
          for (int k = 0; k < c.count; ++k) o << ' ' << c.points[k].x << ',' << c.points[k].y;
        }
        break;
      }
      case ElementKind::Tunnel:
        o << "tunnel weight " << e.weight << " x_start " << e.tunnel.x_start << " length " << e.tunnel.length
          << " width " << e.tunnel.width_start << ' ' << e.tunnel.width_end << " scale " << e.tunnel.scale
          << " y_centre " << e.tunnel.y_centre;
        break;
      case ElementKind::Vortex:
        o << "vortex weight " << e.weight << " centre " << e.point.centre.x << ' ' << e.point.centre.y;
        break;
      case ElementKind::Saddle:
        o << "saddle weight " << e.weight << " centre " << e.point.centre.x << ' ' << e.point.centre.y;
        break;
      case ElementKind::Texture:
        o << "texture weight " << e.weight << " wavelength " << e.texture.wavelength_x << ' '
          << e.texture.wavelength_y << " height " << e.texture.height;
        break;
    }
    o << "\n";
  }
  return o.str();
}

}  // namespace ff::host
