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

// Length of the decimal number at the start of s ([+-] digits [. digits]
// [e [+-] digits]), 0 if there is none; *nonzero_digit says whether its
// digits before the exponent are not all 0. strtof alone would also take
// hex floats (0x1p3), inf and nan.
size_t decimal_length(const char* s, bool* nonzero_digit) {
  size_t i = (s[0] == '+' || s[0] == '-') ? 1 : 0;
  size_t digits = 0;
  *nonzero_digit = false;
  auto run = [&]() {
    while (s[i] >= '0' && s[i] <= '9') {
      *nonzero_digit |= s[i] != '0';
      ++i;
      ++digits;
    }
  };
  run();
  if (s[i] == '.') {
    ++i;
    run();
  }
  if (digits == 0) return 0;
  if (s[i] == 'e' || s[i] == 'E') {
    size_t j = i + 1 + ((s[i + 1] == '+' || s[i + 1] == '-') ? 1 : 0);
    if (s[j] < '0' || s[j] > '9') return i;
    while (s[j] >= '0' && s[j] <= '9') ++j;
    i = j;
  }
  return i;
}

// A decimal float at the start of s, of `length` characters: false (with
// why) if it is too large for a float, or so small that it would read as 0.
bool decimal_value(const char* s, size_t length, bool nonzero_digit, float& out, std::string& why) {
  const std::string text(s, length);
  const float v = std::strtof(text.c_str(), nullptr);
  if (!std::isfinite(v)) return why = text + " is too large for a float", false;
  if (v == 0.0f && nonzero_digit) return why = text + " is too small for a float (it would be 0)", false;
  out = v;
  return true;
}

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
  // The word the last number() read, as typed (errors quote it: 1.0000001,
  // not 1 with six digits).
  const std::string& last() const { return last_; }
  // The word last read into `value` as typed, or its value printed if none was.
  std::string typed(const float& value) const {
    for (auto it = typed_.rbegin(); it != typed_.rend(); ++it) {
      if (it->first == &value) return it->second;
    }
    std::ostringstream o;
    o << value;
    return o.str();
  }
  // Why the last number() or point() refused its word ("" if it was no number at all).
  const std::string& why() const { return why_; }
  bool number(float& out) {
    why_.clear();
    if (done()) return false;
    const std::string& w = words_[next_];
    bool nonzero = false;
    const size_t n = decimal_length(w.c_str(), &nonzero);
    if (n == 0 || n != w.size()) return not_decimal(w);
    if (!decimal_value(w.c_str(), n, nonzero, out, why_)) return false;
    last_ = w;
    typed_.emplace_back(&out, w);
    ++next_;
    return true;
  }
  bool point(Vec2& out) {  // "x,y", after peek_point()
    why_.clear();
    const std::string& w = words_[next_];
    bool x_nonzero = false, y_nonzero = false;
    const size_t nx = decimal_length(w.c_str(), &x_nonzero);
    if (nx == 0 || w[nx] != ',') return false;
    const char* ys = w.c_str() + nx + 1;
    const size_t ny = decimal_length(ys, &y_nonzero);
    if (ny == 0 || nx + 1 + ny != w.size()) return false;
    Vec2 p;
    if (!decimal_value(w.c_str(), nx, x_nonzero, p.x, why_) || !decimal_value(ys, ny, y_nonzero, p.y, why_)) {
      return false;
    }
    out = p;
    ++next_;
    return true;
  }
  bool peek_point() const {
    return !done() && words_[next_].find(',') != std::string::npos;
  }

 private:
  bool not_decimal(const std::string& w) {
    char* end = nullptr;
    std::strtof(w.c_str(), &end);
    // What strtof reads but a scene file does not: say so rather than "needs a number".
    if (end == w.c_str() + w.size() && !w.empty()) why_ = w + " is not a decimal number";
    return false;
  }

  std::vector<std::string> words_;
  size_t next_ = 0;
  std::string last_;
  std::string why_;
  std::vector<std::pair<const float*, std::string>> typed_;
};

// ": why" after a message, if the last number had a reason to be refused.
std::string reason(const Words& w) { return w.why().empty() ? std::string() : ": " + w.why(); }

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
      if (!w.point(pts[n++])) return err = "polyline points are x,y pairs" + reason(w), false;
    }
    curve = PathCurve::polyline(pts, n);
    if (curve.count == 0) return err = "polyline needs 2..16 points with increasing x", false;
    return true;
  }
  return err = "unknown curve '" + kind + "' (cubic, sine, polyline)", false;
}

// Values a scene cannot mean are refused with the key that carries them, as
// the core's preparation (ScenePlan::prepare) would refuse them later without
// a line: a feather of 0 is a step the profile's smoothstep divides by.
bool check_element(const FieldElement& e, const std::string& kind, const Words& w, std::string& err) {
  // value refers to the element's own float, so typed() finds the word read into it.
  struct Bound { const char* key; const float& value; bool zero_ok; };
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
      err = std::string("element ") + kind + ": '" + b.key + "' " + w.typed(b.value) + " must be " +
            (b.zero_ok ? ">= 0" : "> 0");
      return false;
    }
  }
  if (e.kind == ElementKind::PathSink && e.valley.curve.kind == CurveKind::Sine && !(e.valley.curve.wavelength > 0.0f)) {
    return err = "curve sine: the wavelength must be > 0", false;
  }
  if (e.kind == ElementKind::PathSink && e.valley.curve.kind == CurveKind::Cubic && !(e.valley.curve.length > 0.0f)) {
    return err = "curve cubic: the length L " + w.typed(e.valley.curve.length) + " must be > 0", false;
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
    if (!ok) return err = "'" + key + "' needs finite number(s)" + reason(w), false;
  }
  return check_element(e, kind, w, err);
}

}  // namespace

bool parse_scene_text(const std::string& text, SceneDefinition& out, std::string& error) {
  SceneDefinition s;
  s.rendering = Rendering::Directional;
  // A UTF-8 byte order mark (some editors write one) is not part of the first
  // directive; every trace reader skips it too.
  const bool bom = text.compare(0, 3, "\xEF\xBB\xBF") == 0;
  std::istringstream in(bom ? text.substr(3) : text);
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
      if (!w.number(s.constant)) return fail("constant needs a number" + reason(w));
      if (!(s.constant >= 0.0f && s.constant <= 1.0f)) {
        return fail("constant " + w.last() + " is outside [0, 1] (an amplitude)");
      }
    } else if (key == "bias") {
      if (!w.number(s.bias)) return fail("bias needs a number" + reason(w));
      if (!(s.bias >= -1.0f && s.bias <= 1.0f)) return fail("bias " + w.last() + " is outside [-1, 1]");
    } else if (key == "evaluation") {
      const std::string e = w.take();
      if (e == "closed") {
        s.evaluation = Evaluation::ClosedForm;
      } else if (e == "table") {
        s.evaluation = Evaluation::Table;
        if (!w.number(s.table.spacing_px)) return fail("evaluation table needs the spacing in px" + reason(w));
        if (!(s.table.spacing_px >= 1.0f && s.table.spacing_px <= 100.0f)) {
          return fail("table spacing " + w.last() + " is outside [1, 100] px");
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
  // One byte more than allowed tells a file at the limit from a larger one.
  std::string text(kMaxSceneFileBytes + 1, '\0');
  in.read(&text[0], static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<size_t>(in.gcount()));
  if (text.size() > kMaxSceneFileBytes) {
    error = path + ": larger than 1 MiB: not a scene file (a scene is a few KB)";
    return false;
  }
  if (!parse_scene_text(text, out, error)) {
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
