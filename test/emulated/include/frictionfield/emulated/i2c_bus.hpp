#pragma once
// An emulated I2C bus: targets attach at an address and see each write and
// read as the wire would deliver it. Unknown addresses NACK. Bus failures
// can be injected.
#include <cstddef>
#include <cstdint>
#include <map>

#include "frictionfield/bus/i2c.hpp"

namespace ff::emulated {

class I2cTarget {
 public:
  virtual ~I2cTarget() = default;
  virtual BusStatus on_write(const uint8_t* data, size_t n) = 0;
  virtual BusStatus on_read(uint8_t* data, size_t n) = 0;
};

class EmulatedI2cBus final : public I2cInitiator {
 public:
  void attach(uint8_t address, I2cTarget& target) { targets_[address] = &target; }
  // The next `count` transactions fail with `status` without reaching the target.
  void fail_next(uint32_t count, BusStatus status) {
    fail_count_ = count;
    fail_status_ = status;
  }
  uint32_t transactions() const { return transactions_; }

 private:
  BusStatus do_write_read(uint8_t address, const uint8_t* tx, size_t tx_len, uint8_t* rx, size_t rx_len,
                          uint32_t timeout_us) override;

  std::map<uint8_t, I2cTarget*> targets_;
  uint32_t fail_count_ = 0;
  BusStatus fail_status_ = BusStatus::Ok;
  uint32_t transactions_ = 0;
};

}  // namespace ff::emulated
