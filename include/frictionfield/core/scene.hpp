#pragma once
// What a researcher asks for: a scene definition. It is plain data (no
// pointers into the core), so it can travel in a message, live in a file,
// and be prepared into a ScenePlan outside the 2 kHz interrupt.
#include <cstdint>

#include "frictionfield/core/field_element.hpp"
#include "frictionfield/core/path_curve.hpp"

namespace ff {

constexpr int kMaxSceneElements = 8;

enum class Rendering : uint8_t {
  Constant,     // amplitude = constant; needs nothing (neutral)
  PositionOnly, // amplitude = clamp(bias + sum w_i profile_i(p)); needs position
  Directional,  // amplitude = 0.5 - v_hat . G / (2 max|G|); needs position + direction
};

enum class Needs : uint8_t { Nothing, Position, PositionAndDirection };

enum class Evaluation : uint8_t { ClosedForm, Table };
enum class TableStorage : uint8_t { Float32, Int16 };
enum class TableSource : uint8_t {
  TabulatedGradient,       // store G (or the profile) per node; bilinear
  HeightCentralDifferences // store Z per node; G by central differences of the bilinear Z
};

struct TableConfig {
  float spacing_px = 4.0f;
  TableStorage storage = TableStorage::Int16;
  TableSource source = TableSource::TabulatedGradient;
};

// A height map sampled on a regular grid (e.g. from a picture); the caller
// keeps the samples alive until prepare() returns (they are copied).
struct SampledHeightMap {
  const float* heights = nullptr;  // row-major, rows x cols, row 0 at y = 0
  uint16_t cols = 0;
  uint16_t rows = 0;
  float spacing_px = 1.0f;
};

struct SceneDefinition {
  Rendering rendering = Rendering::Constant;
  float constant = 0.5f;  // Constant rendering
  float bias = 0.0f;      // PositionOnly rendering
  uint8_t element_count = 0;
  FieldElement elements[kMaxSceneElements] = {};
  SampledHeightMap sampled;  // optional extra height term (weight 1), always via a table
  Evaluation evaluation = Evaluation::ClosedForm;
  TableConfig table;

  // Appends an element; false (and nothing added) when full.
  bool add(const FieldElement& e);
};

constexpr Needs needs_of(Rendering r) {
  return r == Rendering::Constant ? Needs::Nothing
         : r == Rendering::PositionOnly ? Needs::Position
                                        : Needs::PositionAndDirection;
}

}  // namespace ff
