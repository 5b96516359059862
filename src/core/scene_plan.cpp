#include "frictionfield/core/scene_plan.hpp"

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <initializer_list>

#include "frictionfield/core/fastrun.hpp"

namespace ff {

const char* to_string(PrepareStatus s) {
  switch (s) {
    case PrepareStatus::Ok: return "ok";
    case PrepareStatus::TooManyElements: return "too many elements";
    case PrepareStatus::InvalidParameter: return "invalid parameter (NaN, infinite or out of range)";
    case PrepareStatus::TableTooLarge: return "table larger than the RAM budget";
    case PrepareStatus::InvalidSampledMap: return "invalid sampled height map";
    case PrepareStatus::NonFiniteField: return "field not finite on the screen (heights or gradients overflow float)";
    case PrepareStatus::TooCostlyToPrepare:
      return "too costly to prepare within the device's watchdog (fewer elements, longer textures or coarser table)";
  }
  return "?";
}

namespace {

// The preparation cost model, in M4 instructions: preparation's work is field
// evaluations, so counting and pricing them bounds its time. Measured under
// qemu mps2-an386 -icount shift=0 (one instruction per ns), preparing scenes
// of 2 and of 8 elements of one kind (32 px search, 8 px tables): per element
// and evaluation at most 190 (a texture in the search; sine or 16-point
// polyline valleys in an int16 height table: 184-187), and beside the
// elements at most ~65 per search evaluation and ~165 per int16 node and pass.
// The dearest whole evaluations measured: 1,582 (search, 8 textures), 1,735
// (int16 height table of 8 16-point polyline valleys at 7 px); the model
// prices them at 1,880 and 1,960. One element's gradient, height or profile:
constexpr uint32_t kTermInstructions = 220;
// The search's own work per evaluation (|G|^2, or the scaled pass's division
// and root; the candidates' bookkeeping):
constexpr uint32_t kSearchEvaluationInstructions = 120;
// A search evaluation of a table: height central differences, four bilinear
// samples, is the dearest (510, docs/benchmarks.md "Every strategy"):
constexpr uint32_t kTableReadInstructions = 600;
// A table fill's own work per node and pass (int16 quantisation and store, a
// sampled map's node lookup):
constexpr uint32_t kTableNodeInstructions = 200;
// The compass search's evaluations from one candidate, so that a search's
// cost is known before it runs: a climb through the ten step halvings takes
// a few dozen; a longer one stops where it is (a max|G| found a little low
// saturates the steepest amplitudes, never more).
constexpr uint32_t kMaxCompassEvaluations = 512;
constexpr int kCandidates = 6;

// a + b, saturated: the stat stays meaningful under a benchmark's raised budget.
uint32_t add_saturated(uint32_t a, uint64_t b) {
  const uint64_t sum = a + b;
  return sum > UINT32_MAX ? UINT32_MAX : static_cast<uint32_t>(sum);
}

bool finite_positive(float v) { return std::isfinite(v) && v > 0.0f; }

bool valid_curve(const PathCurve& c) {
  switch (c.kind) {
    case CurveKind::Cubic:
      return std::isfinite(c.x0) && std::isfinite(c.y0) && std::isfinite(c.rise) &&
             finite_positive(c.length);
    case CurveKind::Sine:
      return std::isfinite(c.x0) && std::isfinite(c.y0) && std::isfinite(c.amplitude) &&
             finite_positive(c.wavelength);
    case CurveKind::Polyline:
      if (c.count < 2 || c.count > kMaxPolylinePoints) return false;
      for (int i = 0; i < c.count; ++i) {
        if (!is_finite(c.points[i]) || (i > 0 && !(c.points[i].x > c.points[i - 1].x))) return false;
      }
      return true;
  }
  return false;
}

bool valid_element(const FieldElement& e) {
  if (!std::isfinite(e.weight)) return false;
  switch (e.kind) {
    case ElementKind::PointSink:
      return is_finite(e.point.centre) && std::isfinite(e.point.radius) && e.point.radius >= 0.0f &&
             finite_positive(e.point.feather);
    case ElementKind::Vortex:
    case ElementKind::Saddle:
      return is_finite(e.point.centre);
    case ElementKind::PathSink:
      return valid_curve(e.valley.curve) && finite_positive(e.valley.a) &&
             std::isfinite(e.valley.band_half_width) && e.valley.band_half_width >= 0.0f &&
             finite_positive(e.valley.band_feather);
    case ElementKind::Tunnel: {
      const TunnelParams& t = e.tunnel;
      return std::isfinite(t.x_start) && finite_positive(t.length) && finite_positive(t.width_start) &&
             finite_positive(t.width_end) && finite_positive(t.scale) && std::isfinite(t.y_centre);
    }
    case ElementKind::Texture:
      return finite_positive(e.texture.wavelength_x) && finite_positive(e.texture.wavelength_y) &&
             std::isfinite(e.texture.height);
  }
  return false;
}

// |G| without overflow or underflow of the squares: scale by the larger
// component. A non-finite G gives infinity, so the search's maximum says the
// field is not finite and preparation refuses it. In flash (only the rare
// fallback search).
__attribute__((noinline)) float safe_length(Vec2 g) {
  if (!std::isfinite(g.x) || !std::isfinite(g.y)) return INFINITY;
  const float m = std::fmax(std::fabs(g.x), std::fabs(g.y));
  if (!(m > 0.0f)) return 0.0f;
  const Vec2 u = (1.0f / m) * g;
  return m * length(u);
}

}  // namespace

PrepareStatus ScenePlan::prepare(const SceneDefinition& def, void* table_memory, size_t table_capacity,
                                 uint32_t max_instructions) {
  if (def.element_count > kMaxSceneElements) return PrepareStatus::TooManyElements;
  if (def.rendering != Rendering::Constant && def.rendering != Rendering::PositionOnly &&
      def.rendering != Rendering::Directional) {
    return PrepareStatus::InvalidParameter;
  }
  if (!std::isfinite(def.constant) || !std::isfinite(def.bias)) return PrepareStatus::InvalidParameter;

  ScenePlan next;
  next.rendering_ = def.rendering;
  next.needs_ = needs_of(def.rendering);
  next.constant_ = clamp(def.constant, 0.0f, 1.0f);
  next.bias_ = def.bias;
  next.stats_.plan_bytes = sizeof(ScenePlan);

  if (def.rendering == Rendering::Constant) {  // needs nothing: no terms kept
    *this = next;
    return PrepareStatus::Ok;
  }

  bool has_vortex = false;
  float max_weight = 0.0f;
  for (int i = 0; i < def.element_count; ++i) {
    const FieldElement& e = def.elements[i];
    if (!valid_element(e)) return PrepareStatus::InvalidParameter;
    if (e.weight == 0.0f) continue;  // contributes nothing: not evaluated
    has_vortex |= e.kind == ElementKind::Vortex;
    max_weight = std::fmax(max_weight, std::fabs(e.weight));
    next.elements_[next.count_++] = e;
  }
  if (def.rendering == Rendering::Directional && def.sampled.heights == nullptr) {
    // G / (2 max|G|) does not care about a common factor: scale the weights
    // to at most 1 so that 1e30 or 1e-30 neither overflow nor vanish.
    for (int i = 0; i < next.count_; ++i) next.elements_[i].weight /= max_weight;
    next.field_scale_ = max_weight;
  }

  const SampledHeightMap& sm = def.sampled;
  const bool sampled = sm.heights != nullptr;
  if (sampled) {
    if (def.rendering != Rendering::Directional || sm.cols < 2 || sm.rows < 2 ||
        !finite_positive(sm.spacing_px)) {
      return PrepareStatus::InvalidSampledMap;
    }
    for (uint32_t i = 0; i < static_cast<uint32_t>(sm.cols) * sm.rows; ++i) {
      if (!std::isfinite(sm.heights[i])) return PrepareStatus::InvalidSampledMap;
    }
  }

  next.evaluation_ = sampled ? Evaluation::Table : def.evaluation;
  // Priced before any work: the table's fill (if any) and one max|G| search.
  const bool directional = def.rendering == Rendering::Directional;
  auto too_costly = [&](uint64_t fill_instructions) {
    const uint64_t search = directional ? next.search_instruction_bound() : 0;
    return fill_instructions + search > max_instructions;
  };
  if (next.evaluation_ == Evaluation::Table) {
    const TableConfig& tc = def.table;
    const float spacing = sampled ? sm.spacing_px : tc.spacing_px;
    if (!finite_positive(spacing) || spacing < 0.25f || spacing > kScreenMaxY) {
      return PrepareStatus::InvalidParameter;
    }
    next.table_source_ = sampled ? TableSource::HeightCentralDifferences : tc.source;
    const bool heights = directional && next.table_source_ == TableSource::HeightCentralDifferences;
    if (heights && has_vortex) return PrepareStatus::InvalidParameter;  // a vortex has no height
    const int channels = (directional && !heights) ? 2 : 1;
    const uint16_t cols = sampled ? sm.cols : GridTable::nodes_for(kScreenMaxX, spacing);
    const uint16_t rows = sampled ? sm.rows : GridTable::nodes_for(kScreenMaxY, spacing);
    const TableStorage storage = tc.storage;
    if (GridTable::bytes_needed(cols, rows, channels, storage) > table_capacity) {
      return PrepareStatus::TableTooLarge;
    }
    // int16 takes a pass for the range first (GridTable::fill).
    const uint64_t passes = storage == TableStorage::Int16 ? 2 : 1;
    const uint64_t node_instructions = kTableNodeInstructions + uint64_t{kTermInstructions} * next.count_;
    const uint64_t fill_instructions = passes * cols * rows * node_instructions;
    if (too_costly(fill_instructions)) return PrepareStatus::TooCostlyToPrepare;
    if (!next.table_.init(table_memory, table_capacity, cols, rows, spacing, channels, storage)) {
      return PrepareStatus::TableTooLarge;
    }
    uint32_t evaluations = 0;
    bool finite = true;  // an overflowing node would poison every difference taken across it
    next.table_.fill([&](Vec2 p, float* out) {
      ++evaluations;
      if (!directional) {
        out[0] = next.closed_form_profile(p);
      } else if (heights) {
        float z = 0.0f;
        for (int i = 0; i < next.count_; ++i) {
          z += next.elements_[i].weight * element_height(next.elements_[i], p);
        }
        if (sampled) {
          const int c = static_cast<int>(std::lround(p.x / spacing));
          const int r = static_cast<int>(std::lround(p.y / spacing));
          z += sm.heights[r * sm.cols + c];
        }
        out[0] = z;
      } else {
        const Vec2 g = next.closed_form_field(p);
        out[0] = g.x;
        out[1] = g.y;
      }
      finite = finite && std::isfinite(out[0]) && (channels < 2 || std::isfinite(out[1]));
    });
    if (!finite) return PrepareStatus::NonFiniteField;
    next.stats_.gradient_evaluations += evaluations;
    next.stats_.modelled_instructions =
        add_saturated(next.stats_.modelled_instructions, evaluations * node_instructions);
    next.stats_.table_bytes = static_cast<uint32_t>(next.table_.bytes());
    next.stats_.table_cols = cols;
    next.stats_.table_rows = rows;
  } else if (too_costly(0)) {
    return PrepareStatus::TooCostlyToPrepare;
  }

  if (directional) {
    float max_g = 0.0f;
    if (!next.find_max_gradient(max_instructions, &max_g)) return PrepareStatus::TooCostlyToPrepare;
    // A field or max|G| past float on the screen would normalise to NaN or 0
    // at every tick: refused, as a table's non-finite node is.
    if (!std::isfinite(max_g)) return PrepareStatus::NonFiniteField;
    // In the definition's units; weights near 1e36 take it past float: saturate.
    const float max_in_units = max_g * next.field_scale_;
    next.stats_.max_gradient = std::isfinite(max_in_units) ? max_in_units : FLT_MAX;
    // A field that is flat everywhere renders 0.5 (no direction to favour).
    next.inv_two_max_ = max_g > 0.0f ? 0.5f / max_g : 0.0f;
  }
  *this = next;
  return PrepareStatus::Ok;
}

FF_FASTRUN Vec2 ScenePlan::closed_form_field(Vec2 p) const {
  Vec2 g;
  for (int i = 0; i < count_; ++i) g = g + elements_[i].weight * element_gradient(elements_[i], p);
  return g;
}

FF_FASTRUN float ScenePlan::closed_form_profile(Vec2 p) const {
  float a = bias_;
  for (int i = 0; i < count_; ++i) a += elements_[i].weight * element_profile(elements_[i], p);
  return a;
}

Vec2 ScenePlan::field(Vec2 p) const { return field_scale_ * scaled_field(p); }

FF_FASTRUN Vec2 ScenePlan::scaled_field(Vec2 p) const {
  if (evaluation_ == Evaluation::ClosedForm) return closed_form_field(p);
  if (table_source_ == TableSource::TabulatedGradient) return table_.sample2(p);
  // Central differences of the bilinear height, one node spacing either side.
  const float h = table_.spacing();
  const float inv = 0.5f / h;
  return {(table_.sample({p.x + h, p.y}, 0) - table_.sample({p.x - h, p.y}, 0)) * inv,
          (table_.sample({p.x, p.y + h}, 0) - table_.sample({p.x, p.y - h}, 0)) * inv};
}

FF_FASTRUN float ScenePlan::profile(Vec2 p) const {
  const float a = evaluation_ == Evaluation::Table ? table_.sample(p, 0) : closed_form_profile(p);
  return clamp_finite(a, 0.0f, 1.0f, 0.0f);
}

FF_FASTRUN Vec2 ScenePlan::normalized_gradient(Vec2 p) const {
  if (rendering_ != Rendering::Directional) return {};
  return inv_two_max_ * scaled_field(p);
}

// flatten: the field's evaluation in this file is compiled in (calls cost more than they do on the M4).
FF_FASTRUN __attribute__((flatten)) float ScenePlan::amplitude(Vec2 position, Vec2 direction) const {
  switch (rendering_) {
    case Rendering::Constant:
      return constant_;
    case Rendering::PositionOnly:
      return profile(position);
    case Rendering::Directional: {
      // friction mu = 0.5 + v . G_norm; amplitude A = 1 - mu.
      const float a = 0.5f - dot(direction, normalized_gradient(position));
      return clamp_finite(a, 0.0f, 1.0f, 0.5f);
    }
  }
  return 0.5f;
}

// The lone texture and the lone vortex of a closed-form scene have their
// maximum in closed form (find_max_gradient): no search.
bool ScenePlan::max_gradient_in_closed_form() const {
  if (count_ != 1 || evaluation_ != Evaluation::ClosedForm) return false;
  if (elements_[0].kind == ElementKind::Vortex) return true;
  const TextureParams& t = elements_[0].texture;
  return elements_[0].kind == ElementKind::Texture && t.wavelength_x <= kScreenMaxY && t.wavelength_y <= kScreenMaxY;
}

uint32_t ScenePlan::search_evaluation_instructions() const {
  const uint32_t field = evaluation_ == Evaluation::Table ? kTableReadInstructions : kTermInstructions * count_;
  return kSearchEvaluationInstructions + field;
}

uint64_t ScenePlan::search_instruction_bound() const {
  if (max_gradient_in_closed_form()) return 0;
  const float step = scan_step();
  uint64_t evaluations = static_cast<uint64_t>(static_cast<int>(kScreenMaxX / step) + 2) *
                         static_cast<uint64_t>(static_cast<int>(kScreenMaxY / step) + 2);
  for (int e = 0; e < count_; ++e) {  // the seeds of search_max_gradient
    const FieldElement& el = elements_[e];
    if (el.kind == ElementKind::PathSink && el.valley.curve.kind == CurveKind::Polyline) {
      evaluations += 4u * static_cast<uint64_t>(el.valley.curve.count - 1);
    }
    if (el.kind == ElementKind::Tunnel) evaluations += 8;
  }
  evaluations += uint64_t{kCandidates} * kMaxCompassEvaluations;
  return evaluations * search_evaluation_instructions();
}

bool ScenePlan::find_max_gradient(uint64_t max_instructions, float* max_g) {
  // Coarse scan of the screen (edges included), then a compass search from
  // the best few nodes: ~700 field evaluations instead of 384k pixels, so a
  // closed-form scene prepares in under 2 ms on the M4 (docs/benchmarks.md).
  // A lone texture (the bump map) has its maximum in closed form:
  // |G| = |w h| 2 pi / lambda at a crest, if a whole period fits on the screen.
  if (max_gradient_in_closed_form() && elements_[0].kind == ElementKind::Texture) {
    const TextureParams& t = elements_[0].texture;
    // 2 pi / lambda first: |w h| near FLT_MAX must not overflow when the maximum does not.
    *max_g = std::fabs(elements_[0].weight * t.height) * (2.0f * kPi / std::fmin(t.wavelength_x, t.wavelength_y));
    return true;
  }
  // A lone vortex: |G| = |w| |p - c|, largest at the corner farthest from the centre.
  if (max_gradient_in_closed_form()) {
    const Vec2 c = elements_[0].point.centre;
    const float dx = std::fmax(std::fabs(c.x), std::fabs(kScreenMaxX - c.x));
    const float dy = std::fmax(std::fabs(c.y), std::fabs(kScreenMaxY - c.y));
    *max_g = std::fabs(elements_[0].weight) * std::hypot(dx, dy);
    return true;
  }
  // The scan must resolve the finest feature: |G| of a texture peaks twice
  // per wavelength, so an eighth of the shortest one, and six candidates for
  // its rows of nearly equal peaks. Without textures the field's hills are
  // broad (cones, valleys whose slope saturates): a 48 px scan and the four
  // best hills, refined by the compass search, keep max|G| within 1e-5 of
  // a dense scan for every built-in scene at a third of the evaluations
  // (preparation <= 2 ms of modelled MK66 time, docs/benchmarks.md).
  // 48 px and four hills made every built-in scene prepare in <= 1.87 ms but
  // missed max|G| by 5e-4 on randomised thesis scenes (test/stress precision),
  // and 32 px with four hills by 2.7e-4 (FF_STRESS_CASES=100): 32 px and six;
  // the search's own code is what got cheaper (search_max_gradient).
  // Squares first (no division or root per evaluation); the scaled search
  // of old only for fields whose squares leave float's normal range.
  // The scaled search is a second whole search: priced again (a scene whose
  // field is tiny everywhere may fit once but not twice).
  bool out_of_range = false;
  const float best_squared = search_max_gradient(true, &out_of_range);
  if (!out_of_range) {
    *max_g = std::sqrt(best_squared);
    return true;
  }
  if (stats_.modelled_instructions + search_instruction_bound() > max_instructions) return false;
  *max_g = search_max_gradient(false, &out_of_range);
  return true;
}

float ScenePlan::scan_step() const {
  float scan_step = 32.0f;
  for (int e = 0; e < count_; ++e) {
    if (elements_[e].kind != ElementKind::Texture) continue;
    const TextureParams& t = elements_[e].texture;
    scan_step = std::fmin(scan_step, 0.125f * std::fmin(t.wavelength_x, t.wavelength_y));
  }
  return std::fmax(scan_step, 2.0f);
}

// In RAM on the M4 (no flash wait states), with the field's evaluation in this
// file compiled in (flatten: 2.5 KB of RAM): preparation evaluates ~800 times.
FF_FASTRUN __attribute__((flatten)) float ScenePlan::search_max_gradient(bool squared, bool* out_of_range) {
  const float kStep = scan_step();
  Vec2 best_p[kCandidates];
  float best_m[kCandidates];  // |G|^2 if squared, else |G|
  for (int i = 0; i < kCandidates; ++i) best_m[i] = -1.0f;

  uint32_t evaluations = 0;  // in a register, not the plan's memory
  auto magnitude = [&](Vec2 p) __attribute__((always_inline)) {
    ++evaluations;
    const Vec2 g = scaled_field(p);
    if (!squared) return safe_length(g);
    const float m2 = g.x * g.x + g.y * g.y;
    if (!(m2 <= FLT_MAX)) *out_of_range = true;  // overflow, or a non-finite field
    return m2;
  };
  // Keep the best node of each hill: a node next to a kept one competes only
  // with it, so the candidates spread over distinct peaks (textures have rows
  // of nearly equal ones).
  const float neighbourhood = 1.5f * kStep;
  // The lowest kept value: a node at or below it replaces nothing (its
  // neighbour's slot holds at least as much), so most of the scan skips the slots.
  float lowest_kept = -1.0f;
  auto consider = [&](Vec2 p, float m) __attribute__((always_inline)) {
    if (!(m > lowest_kept)) return;
    int slot = -1;
    for (int i = 0; i < kCandidates && slot < 0; ++i) {
      if (best_m[i] >= 0.0f && std::fabs(best_p[i].x - p.x) <= neighbourhood &&
          std::fabs(best_p[i].y - p.y) <= neighbourhood) {
        slot = i;
      }
    }
    if (slot < 0) {
      slot = 0;
      for (int i = 1; i < kCandidates; ++i) slot = best_m[i] < best_m[slot] ? i : slot;
    }
    if (m > best_m[slot]) {
      best_m[slot] = m;
      best_p[slot] = p;
      lowest_kept = best_m[0];
      for (int i = 1; i < kCandidates; ++i) lowest_kept = best_m[i] < lowest_kept ? best_m[i] : lowest_kept;
    }
  };

  const int nx = static_cast<int>(kScreenMaxX / kStep) + 2;
  const int ny = static_cast<int>(kScreenMaxY / kStep) + 2;
  for (int j = 0; j < ny; ++j) {
    const float y = j == ny - 1 ? kScreenMaxY : static_cast<float>(j) * kStep;
    for (int i = 0; i < nx; ++i) {
      const float x = i == nx - 1 ? kScreenMaxX : static_cast<float>(i) * kStep;
      consider({x, y}, magnitude({x, y}));
    }
  }
  // A polyline segment can be steeper and narrower than the scan step: seed
  // the search on every segment, where a valley's slope saturates (the
  // screen's top and bottom edges) and near the path.
  for (int e = 0; e < count_; ++e) {
    const FieldElement& el = elements_[e];
    if (el.kind != ElementKind::PathSink || el.valley.curve.kind != CurveKind::Polyline) continue;
    const PathCurve& c = el.valley.curve;
    for (int k = 1; k < c.count; ++k) {
      const float x = clamp(0.5f * (c.points[k - 1].x + c.points[k].x), 0.0f, kScreenMaxX);
      const float near = 3.0f / el.valley.a;
      const float yp = c.at(x).y;
      for (float y : {0.0f, kScreenMaxY, yp - near, yp + near}) {
        const Vec2 p{x, clamp(y, 0.0f, kScreenMaxY)};
        consider(p, magnitude(p));
      }
    }
  }

  // A tunnel ends abruptly: its width's x-gradient, largest far from its
  // centre line, stops at x_start and x_start + length, so the steepest point
  // can sit just inside an end, narrower than the scan step: seed there too.
  for (int e = 0; e < count_; ++e) {
    const FieldElement& el = elements_[e];
    if (el.kind != ElementKind::Tunnel) continue;
    const TunnelParams& t = el.tunnel;
    const float inset = 1.0f / 32.0f;  // the refinement's finest step
    for (int end = 0; end < 2; ++end) {
      const float x = end == 0 ? t.x_start + inset : t.x_start + t.length - inset;
      if (!(x > 0.0f && x < kScreenMaxX)) continue;
      const float near = 3.0f * (end == 0 ? t.width_start : t.width_end) / t.scale;
      for (float y : {0.0f, kScreenMaxY, t.y_centre - near, t.y_centre + near}) {
        const Vec2 p{x, clamp(y, 0.0f, kScreenMaxY)};
        consider(p, magnitude(p));
      }
    }
  }

  float best = 0.0f;
  for (int c = 0; c < kCandidates; ++c) {
    if (best_m[c] < 0.0f) continue;
    Vec2 p = best_p[c];
    Vec2 from = p;  // where the last move came from: known to be lower
    float m = best_m[c];
    const uint32_t compass_limit = evaluations + kMaxCompassEvaluations;
    for (float step = 0.5f * kStep; step >= 1.0f / 32.0f && evaluations + 4 <= compass_limit;) {
      const Vec2 moves[4] = {{step, 0}, {-step, 0}, {0, step}, {0, -step}};
      bool moved = false;
      for (const Vec2& d : moves) {
        const Vec2 q{clamp(p.x + d.x, 0.0f, kScreenMaxX), clamp(p.y + d.y, 0.0f, kScreenMaxY)};
        if (q.x == p.x && q.y == p.y) continue;  // pinned at the screen's edge
        if (q.x == from.x && q.y == from.y) continue;  // back where it was: not higher
        const float mq = magnitude(q);
        if (mq > m) {
          m = mq;
          from = p;
          p = q;
          moved = true;
        }
      }
      if (!moved) step *= 0.5f;
    }
    best = m > best ? m : best;
  }
  // Below 2^-100, squares of the smaller values underflow: not resolved.
  if (squared && best < 0x1p-100f) *out_of_range = true;
  stats_.gradient_evaluations += evaluations;
  stats_.modelled_instructions =
      add_saturated(stats_.modelled_instructions, uint64_t{evaluations} * search_evaluation_instructions());
  return best;
}

}  // namespace ff
