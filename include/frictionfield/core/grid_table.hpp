#pragma once
// A regular grid over the screen, 1 or 2 channels, float or int16 storage,
// bilinear interpolation. It never owns memory: it is laid out in a slice of
// a TableArena at preparation.
#include <cstddef>
#include <cstdint>

#include "frictionfield/core/geometry.hpp"
#include "frictionfield/core/scene.hpp"

namespace ff {

class GridTable {
 public:
  // Nodes that cover 0 .. extent at this spacing, both ends included.
  static uint16_t nodes_for(float extent, float spacing_px);
  // Bytes needed for a table covering the screen at `spacing_px`.
  static size_t bytes_needed(float spacing_px, int channels, TableStorage storage);
  static size_t bytes_needed(uint16_t cols, uint16_t rows, int channels, TableStorage storage);

  // Lays the table out in `memory` (aligned to 4); false if it does not fit.
  bool init(void* memory, size_t capacity, uint16_t cols, uint16_t rows, float spacing_px,
            int channels, TableStorage storage);

  // Fills every node from `f(node position, float out[2])`.
  template <typename Fn>
  void fill(Fn&& f);

  // Node access (for sampled height maps and tests).
  void set(int col, int row, int channel, float value);
  float node(int col, int row, int channel) const;
  void set_int16_scale(int channel, float max_abs);

  // Bilinear value at p (clamped to the grid).
  float sample(Vec2 p, int channel) const;
  Vec2 sample2(Vec2 p) const;  // channels 0 and 1 together

  uint16_t cols() const { return cols_; }
  uint16_t rows() const { return rows_; }
  float spacing() const { return spacing_; }
  int channels() const { return channels_; }
  size_t bytes() const { return bytes_needed(cols_, rows_, channels_, storage_); }
  bool valid() const { return data_ != nullptr; }

 private:
  struct Cell {
    int index;     // of the top-left node, channel 0
    float fx, fy;  // fractions inside the cell
  };
  Cell locate(Vec2 p) const;
  float fetch(int index) const;  // stored node value, before the int16 scale

  void* data_ = nullptr;
  uint16_t cols_ = 0;
  uint16_t rows_ = 0;
  uint8_t channels_ = 1;
  TableStorage storage_ = TableStorage::Float32;
  float spacing_ = 1.0f;
  float inv_spacing_ = 1.0f;
  float scale_[2] = {1.0f, 1.0f};  // stored -> value (1 for float storage)
};

template <typename Fn>
void GridTable::fill(Fn&& f) {
  auto each_node = [&](auto&& use) {
    for (int r = 0; r < rows_; ++r) {
      for (int c = 0; c < cols_; ++c) {
        float v[2] = {0.0f, 0.0f};
        f(Vec2{static_cast<float>(c) * spacing_, static_cast<float>(r) * spacing_}, v);
        use(c, r, v);
      }
    }
  };
  if (storage_ == TableStorage::Int16) {
    // int16 needs each channel's range first: one extra pass, at preparation only.
    float max_abs[2] = {0.0f, 0.0f};
    each_node([&](int, int, const float* v) {
      for (int ch = 0; ch < channels_; ++ch) {
        const float a = v[ch] < 0.0f ? -v[ch] : v[ch];
        if (a > max_abs[ch]) max_abs[ch] = a;
      }
    });
    for (int ch = 0; ch < channels_; ++ch) set_int16_scale(ch, max_abs[ch]);
  }
  each_node([&](int c, int r, const float* v) {
    for (int ch = 0; ch < channels_; ++ch) set(c, r, ch, v[ch]);
  });
}

}  // namespace ff
