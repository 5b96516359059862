#pragma once
// Bounds-checked little-endian writer and reader: every access checks room,
// a failed one poisons the stream so that one check at the end suffices.
// Floats travel as their IEEE-754 bits; a NaN or an infinity is refused both
// ways, so that every decoded number is finite.
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace ff::protocol {

// Exponent all ones: infinity or NaN.
constexpr bool finite_bits(uint32_t bits) { return (bits & 0x7F800000u) != 0x7F800000u; }

class WireWriter {
 public:
  WireWriter(uint8_t* data, size_t capacity) : data_(data), capacity_(capacity) {}
  void u8(uint8_t v) { put(&v, 1); }
  void u16(uint16_t v) { const uint8_t b[2] = {uint8_t(v), uint8_t(v >> 8)}; put(b, 2); }
  void u32(uint32_t v) {
    const uint8_t b[4] = {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)};
    put(b, 4);
  }
  void f32(float v) {
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    if (!finite_bits(bits)) ok_ = false;
    u32(bits);
  }
  size_t size() const { return size_; }
  bool ok() const { return ok_; }

 private:
  void put(const uint8_t* b, size_t n) {
    if (!ok_ || capacity_ - size_ < n) {
      ok_ = false;
      return;
    }
    std::memcpy(data_ + size_, b, n);
    size_ += n;
  }
  uint8_t* data_;
  size_t capacity_;
  size_t size_ = 0;
  bool ok_ = true;
};

class WireReader {
 public:
  WireReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  uint8_t u8() { uint8_t b = 0; get(&b, 1); return b; }
  uint16_t u16() { uint8_t b[2] = {}; get(b, 2); return uint16_t(b[0] | (b[1] << 8)); }
  uint32_t u32() {
    uint8_t b[4] = {};
    get(b, 4);
    return uint32_t(b[0]) | (uint32_t(b[1]) << 8) | (uint32_t(b[2]) << 16) | (uint32_t(b[3]) << 24);
  }
  float f32() {
    const uint32_t bits = u32();
    if (!finite_bits(bits)) {
      ok_ = false;
      return 0.0f;
    }
    float v;
    std::memcpy(&v, &bits, 4);
    return v;
  }
  bool ok() const { return ok_; }
  bool at_end() const { return ok_ && pos_ == size_; }
  void fail() { ok_ = false; }

 private:
  void get(uint8_t* b, size_t n) {
    if (!ok_ || size_ - pos_ < n) {
      ok_ = false;
      return;
    }
    std::memcpy(b, data_ + pos_, n);
    pos_ += n;
  }
  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  bool ok_ = true;
};

}  // namespace ff::protocol
