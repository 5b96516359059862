#include "frictionfield/core/grid_table.hpp"

#include "frictionfield/core/fastrun.hpp"

#include <cmath>
#include <cstring>

namespace ff {

namespace {

size_t element_bytes(TableStorage s) { return s == TableStorage::Int16 ? 2u : 4u; }

}  // namespace

uint16_t GridTable::nodes_for(float extent, float spacing_px) {
  return static_cast<uint16_t>(std::ceil(extent / spacing_px) + 1.0f);
}

size_t GridTable::bytes_needed(uint16_t cols, uint16_t rows, int channels, TableStorage storage) {
  return static_cast<size_t>(cols) * rows * static_cast<size_t>(channels) * element_bytes(storage);
}

size_t GridTable::bytes_needed(float spacing_px, int channels, TableStorage storage) {
  if (!(spacing_px >= 0.25f) || !(spacing_px <= kScreenMaxY)) return SIZE_MAX;
  return bytes_needed(nodes_for(kScreenMaxX, spacing_px), nodes_for(kScreenMaxY, spacing_px),
                      channels, storage);
}

bool GridTable::init(void* memory, size_t capacity, uint16_t cols, uint16_t rows,
                     float spacing_px, int channels, TableStorage storage) {
  if (memory == nullptr || cols < 2 || rows < 2 || channels < 1 || channels > 2 ||
      !(spacing_px > 0.0f) || !std::isfinite(spacing_px) ||
      (reinterpret_cast<uintptr_t>(memory) & 3u) != 0 ||
      bytes_needed(cols, rows, channels, storage) > capacity) {
    return false;
  }
  data_ = memory;
  cols_ = cols;
  rows_ = rows;
  channels_ = static_cast<uint8_t>(channels);
  storage_ = storage;
  spacing_ = spacing_px;
  inv_spacing_ = 1.0f / spacing_px;
  scale_[0] = scale_[1] = 1.0f;
  std::memset(memory, 0, bytes_needed(cols, rows, channels, storage));
  return true;
}

void GridTable::set_int16_scale(int channel, float max_abs) {
  scale_[channel] = (max_abs > 0.0f && std::isfinite(max_abs)) ? max_abs / 32767.0f : 1.0f;
}

void GridTable::set(int col, int row, int channel, float value) {
  const int i = (row * cols_ + col) * channels_ + channel;
  if (storage_ == TableStorage::Float32) {
    static_cast<float*>(data_)[i] = value;
  } else {
    const float q = clamp_finite(std::nearbyint(value / scale_[channel]), -32767.0f, 32767.0f, 0.0f);
    static_cast<int16_t*>(data_)[i] = static_cast<int16_t>(q);
  }
}

FF_FASTRUN float GridTable::fetch(int index) const {
  if (storage_ == TableStorage::Float32) return static_cast<const float*>(data_)[index];
  return static_cast<float>(static_cast<const int16_t*>(data_)[index]);
}

FF_FASTRUN float GridTable::node(int col, int row, int channel) const {
  return fetch((row * cols_ + col) * channels_ + channel) * scale_[channel];
}

FF_FASTRUN GridTable::Cell GridTable::locate(Vec2 p) const {
  // NaN lands on node 0; the clamp keeps every index inside the grid.
  const float gx = clamp_finite(p.x * inv_spacing_, 0.0f, static_cast<float>(cols_ - 1), 0.0f);
  const float gy = clamp_finite(p.y * inv_spacing_, 0.0f, static_cast<float>(rows_ - 1), 0.0f);
  int c = static_cast<int>(gx);
  int r = static_cast<int>(gy);
  if (c > cols_ - 2) c = cols_ - 2;
  if (r > rows_ - 2) r = rows_ - 2;
  return {(r * cols_ + c) * channels_, gx - static_cast<float>(c), gy - static_cast<float>(r)};
}

FF_FASTRUN float GridTable::sample(Vec2 p, int channel) const {
  const Cell k = locate(p);
  const int i = k.index + channel;
  const int down = cols_ * channels_;
  const float top = fetch(i) + k.fx * (fetch(i + channels_) - fetch(i));
  const float bottom = fetch(i + down) + k.fx * (fetch(i + down + channels_) - fetch(i + down));
  // Interpolation is linear, so the int16 scale is applied once, at the end.
  return (top + k.fy * (bottom - top)) * scale_[channel];
}

FF_FASTRUN Vec2 GridTable::sample2(Vec2 p) const {
  const Cell k = locate(p);
  const int down = cols_ * 2;
  const int i = k.index;
  float out[2];
  for (int ch = 0; ch < 2; ++ch) {
    const float a = fetch(i + ch), b = fetch(i + 2 + ch);
    const float c = fetch(i + down + ch), d = fetch(i + down + 2 + ch);
    const float top = a + k.fx * (b - a);
    const float bottom = c + k.fx * (d - c);
    out[ch] = (top + k.fy * (bottom - top)) * scale_[ch];
  }
  return {out[0], out[1]};
}

}  // namespace ff
