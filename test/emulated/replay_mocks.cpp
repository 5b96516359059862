#include "frictionfield/emulated/replay_mocks.hpp"

#include <cstdio>
#include <cstring>

namespace ff::emulated {
namespace {

std::string hex(const uint8_t* p, size_t n) {
  std::string s;
  char b[4];
  for (size_t i = 0; i < n; ++i) {
    std::snprintf(b, sizeof(b), "%02X ", p[i]);
    s += b;
  }
  return s;
}

std::string hex16(const uint16_t* p, size_t n) {
  std::string s;
  char b[8];
  for (size_t i = 0; i < n; ++i) {
    std::snprintf(b, sizeof(b), "%04X ", p[i]);
    s += b;
  }
  return s;
}

}  // namespace

bool MockI2cInitiator::finished(std::string* why) const {
  std::string w = first_mismatch_;
  if (w.empty() && next_ != expected_.size()) {
    w = "only " + std::to_string(next_) + " of " + std::to_string(expected_.size()) + " I2C transactions happened";
  }
  if (why) *why = w;
  return w.empty();
}

BusStatus MockI2cInitiator::do_write_read(uint8_t address, const uint8_t* tx, size_t tx_len, uint8_t* rx,
                                          size_t rx_len, uint32_t) {
  const std::string call = "I2C call " + std::to_string(next_ + 1) + " (addr 0x" + hex(&address, 1) + "write " +
                           hex(tx, tx_len) + "read " + std::to_string(rx_len) + ")";
  if (next_ >= expected_.size()) {
    if (first_mismatch_.empty()) first_mismatch_ = call + ": not expected";
    return BusStatus::BusError;
  }
  const I2cTransaction& e = expected_[next_++];
  const bool match = e.address == address && e.write.size() == tx_len &&
                     (tx_len == 0 || std::memcmp(e.write.data(), tx, tx_len) == 0) && e.read.size() == rx_len;
  if (!match) {
    if (first_mismatch_.empty()) {
      first_mismatch_ = call + ": expected addr 0x" + hex(&e.address, 1) + "write " + hex(e.write.data(), e.write.size()) +
                        "read " + std::to_string(e.read.size());
    }
    return BusStatus::BusError;
  }
  if (rx_len != 0) std::memcpy(rx, e.read.data(), rx_len);
  return e.status;
}

bool MockSpiBus16::finished(std::string* why) const {
  std::string w = first_mismatch_;
  if (w.empty() && next_ != expected_.size()) {
    w = "only " + std::to_string(next_) + " of " + std::to_string(expected_.size()) + " SPI transfers happened";
  }
  if (why) *why = w;
  return w.empty();
}

BusStatus MockSpiBus16::do_write(const SpiConfig& config, uint8_t chip_select, const uint16_t* words, size_t count) {
  const std::string call = "SPI transfer " + std::to_string(next_ + 1) + " (mode " +
                           std::to_string(static_cast<int>(config.mode)) + ", cs " + std::to_string(chip_select) +
                           ", words " + hex16(words, count) + ")";
  if (next_ >= expected_.size()) {
    if (first_mismatch_.empty()) first_mismatch_ = call + ": not expected";
    return BusStatus::BusError;
  }
  const SpiTransaction& e = expected_[next_++];
  const bool match = e.mode == config.mode && e.chip_select == chip_select && e.words.size() == count &&
                     std::memcmp(e.words.data(), words, count * sizeof(uint16_t)) == 0;
  if (!match) {
    if (first_mismatch_.empty()) {
      first_mismatch_ = call + ": expected mode " + std::to_string(static_cast<int>(e.mode)) + ", cs " +
                        std::to_string(e.chip_select) + ", words " + hex16(e.words.data(), e.words.size());
    }
    return BusStatus::BusError;
  }
  return e.status;
}

}  // namespace ff::emulated
