#pragma once
// A scene prepared for the 2 kHz tick: zero-weight terms dropped, max|G|
// found, a table built only if asked for. Evaluation never allocates and does
// only what the scene needs.
#include <cstddef>
#include <cstdint>

#include "frictionfield/core/grid_table.hpp"
#include "frictionfield/core/scene.hpp"

namespace ff {

// Table memory for the Teensy: two slots (the live plan's and the next one's),
// so a new scene is built while the old one is still rendered.
#ifndef FF_TABLE_SLOT_BYTES
#define FF_TABLE_SLOT_BYTES (96u * 1024u)
#endif
constexpr size_t kTableSlotBytes = FF_TABLE_SLOT_BYTES;

// Preparation runs in the firmware's main loop, which refreshes the 1 s
// hardware watchdog only between commands: a scene whose preparation the cost
// model prices above this many M4 instructions is refused (TooCostlyToPrepare)
// before any work, on the host as on the device. 36 M = 0.4 s at 180 MHz at
// the cycle model's worst 2 cycles per instruction (docs/spec.md "Preparation cost").
constexpr uint32_t kMaxPreparationInstructions = 36000000u;

enum class PrepareStatus : uint8_t {
  Ok,
  TooManyElements,
  InvalidParameter,  // NaN / infinite / out-of-range parameter
  TableTooLarge,     // over the slot budget: scene unchanged
  InvalidSampledMap,
  NonFiniteField,    // the field overflows float where the tick evaluates it (e.g. a
                     // height table of a saddle far off-screen: inf - inf at every node)
  TooCostlyToPrepare,  // over kMaxPreparationInstructions (e.g. a fine texture scan times
                       // many polylines): the device would stall past its watchdogs
};
const char* to_string(PrepareStatus s);

struct PlanStats {
  float max_gradient = 0.0f;        // max|G| over the screen (Directional); FLT_MAX if larger
  uint32_t gradient_evaluations = 0;  // work spent at preparation
  uint32_t modelled_instructions = 0;  // that work priced by the cost model: <= the budget
  uint32_t table_bytes = 0;
  uint32_t plan_bytes = 0;          // sizeof(ScenePlan)
  uint16_t table_cols = 0;
  uint16_t table_rows = 0;
};

class ScenePlan {
 public:
  // Prepares `def` into this plan using `table_memory` for a table if one is
  // needed. On failure the plan is left as it was. `max_instructions`: the
  // preparation budget; only benchmarks of strategies the Teensy refuses raise it.
  PrepareStatus prepare(const SceneDefinition& def, void* table_memory, size_t table_capacity,
                        uint32_t max_instructions = kMaxPreparationInstructions);

  Needs needs() const { return needs_; }
  const PlanStats& stats() const { return stats_; }

  // Raw amplitude in [0, 1] (before strength and calibration). `direction` is
  // the unit (or faded, shorter) direction of motion; ignored unless needed.
  float amplitude(Vec2 position, Vec2 direction) const;

  // G / (2 max|G|) at p, |result| <= 0.5 (Directional scenes; else 0).
  Vec2 normalized_gradient(Vec2 position) const;
  // Unnormalised field G at p (sum of weighted terms or the table).
  Vec2 field(Vec2 position) const;
  // Position-only amplitude at p (PositionOnly scenes).
  float profile(Vec2 position) const;

 private:
  Vec2 scaled_field(Vec2 p) const;  // G / field_scale_: what the tick evaluates
  Vec2 closed_form_field(Vec2 p) const;
  float closed_form_profile(Vec2 p) const;
  // max|G| of the scaled field into *max_g; false (nothing found) if a second,
  // scaled search would take the preparation past `max_instructions`.
  bool find_max_gradient(uint64_t max_instructions, float* max_g);
  // The scan and compass search of find_max_gradient. squared: compare
  // |G|^2 (no division or root per evaluation) and set *out_of_range when a
  // square overflowed or the maximum is too small for squares to resolve it.
  float search_max_gradient(bool squared, bool* out_of_range);
  float scan_step() const;  // the search's scan spacing, px
  bool max_gradient_in_closed_form() const;
  // The cost model (docs/spec.md "Preparation cost"): M4 instructions of one
  // field evaluation of the search, and the most one search can spend.
  uint32_t search_evaluation_instructions() const;
  uint64_t search_instruction_bound() const;

  Rendering rendering_ = Rendering::Constant;
  Needs needs_ = Needs::Nothing;
  float constant_ = 0.5f;
  float bias_ = 0.0f;
  float inv_two_max_ = 0.0f;  // 1 / (2 max|G|) of the scaled field, 0 for a flat field
  float field_scale_ = 1.0f;  // the largest |weight|: weights are stored divided by it
  uint8_t count_ = 0;
  FieldElement elements_[kMaxSceneElements] = {};
  Evaluation evaluation_ = Evaluation::ClosedForm;
  TableSource table_source_ = TableSource::TabulatedGradient;
  GridTable table_;
  PlanStats stats_;
};

}  // namespace ff
