#pragma once
// Bus mocks that replay a list of expected transactions, in order, in the
// manner of Pigweed's pw_i2c MockInitiator: each call is compared with the
// next expectation (address, bytes written, length read / mode, chip select,
// words), answered with the expectation's bytes and status, and any mismatch
// is recorded. finished() says whether everything was consumed and matched.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "frictionfield/bus/i2c.hpp"
#include "frictionfield/bus/spi.hpp"

namespace ff::emulated {

struct I2cTransaction {
  uint8_t address = 0;
  std::vector<uint8_t> write;  // expected bytes written (empty: a read only)
  std::vector<uint8_t> read;   // bytes returned (empty: a write only)
  BusStatus status = BusStatus::Ok;
};

inline I2cTransaction expect_write(uint8_t address, std::vector<uint8_t> bytes, BusStatus s = BusStatus::Ok) {
  return {address, std::move(bytes), {}, s};
}
inline I2cTransaction expect_read(uint8_t address, std::vector<uint8_t> bytes, BusStatus s = BusStatus::Ok) {
  return {address, {}, std::move(bytes), s};
}
inline I2cTransaction expect_write_read(uint8_t address, std::vector<uint8_t> tx, std::vector<uint8_t> rx,
                                        BusStatus s = BusStatus::Ok) {
  return {address, std::move(tx), std::move(rx), s};
}

class MockI2cInitiator final : public I2cInitiator {
 public:
  explicit MockI2cInitiator(std::vector<I2cTransaction> expected) : expected_(std::move(expected)) {}
  // True if every expectation was used and every call matched; else `why` says what went wrong first.
  bool finished(std::string* why = nullptr) const;
  size_t used() const { return next_; }

 private:
  BusStatus do_write_read(uint8_t address, const uint8_t* tx, size_t tx_len, uint8_t* rx, size_t rx_len,
                          uint32_t timeout_us) override;

  std::vector<I2cTransaction> expected_;
  size_t next_ = 0;
  std::string first_mismatch_;
};

struct SpiTransaction {
  SpiMode mode = SpiMode::Mode0;
  uint8_t chip_select = 0;
  std::vector<uint16_t> words;
  BusStatus status = BusStatus::Ok;
};

class MockSpiBus16 final : public SpiBus16 {
 public:
  explicit MockSpiBus16(std::vector<SpiTransaction> expected) : expected_(std::move(expected)) {}
  bool finished(std::string* why = nullptr) const;
  size_t used() const { return next_; }

 private:
  BusStatus do_write(const SpiConfig& config, uint8_t chip_select, const uint16_t* words, size_t count) override;

  std::vector<SpiTransaction> expected_;
  size_t next_ = 0;
  std::string first_mismatch_;
};

}  // namespace ff::emulated
