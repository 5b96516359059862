#pragma once
// I2C initiator (controller), in the style of Pigweed's pw_i2c: one virtual
// primitive (write, repeated start, read) and inline wrappers around it.
//
// Why virtual and not a template parameter: a transaction takes tens of
// microseconds on the wire, so one indirect call costs nothing measurable,
// and a virtual interface lets the same compiled driver run against the
// Teensy's Wire port, the emulated devices and the replay mocks. The
// destructor is protected and non-virtual: drivers only hold references, so
// no object is ever deleted through the interface and no operator delete
// (heap) is pulled into the firmware.
#include <cstddef>
#include <cstdint>

#include "frictionfield/bus/bus_status.hpp"

namespace ff {

class I2cInitiator {
 public:
  static constexpr uint8_t kMaxAddress = 0x7F;  // 7-bit addressing only

  // Writes `tx`, then (repeated start, no stop in between) reads `rx`.
  // Either part may be empty, not both.
  BusStatus write_read(uint8_t address, const uint8_t* tx, size_t tx_len, uint8_t* rx, size_t rx_len,
                       uint32_t timeout_us) {
    if (address > kMaxAddress || (tx_len == 0 && rx_len == 0) || (tx_len != 0 && tx == nullptr) ||
        (rx_len != 0 && rx == nullptr)) {
      return BusStatus::InvalidArgument;
    }
    return do_write_read(address, tx, tx_len, rx, rx_len, timeout_us);
  }
  BusStatus write(uint8_t address, const uint8_t* tx, size_t len, uint32_t timeout_us) {
    return write_read(address, tx, len, nullptr, 0, timeout_us);
  }
  BusStatus read(uint8_t address, uint8_t* rx, size_t len, uint32_t timeout_us) {
    return write_read(address, nullptr, 0, rx, len, timeout_us);
  }

 protected:
  ~I2cInitiator() = default;

 private:
  virtual BusStatus do_write_read(uint8_t address, const uint8_t* tx, size_t tx_len, uint8_t* rx,
                                  size_t rx_len, uint32_t timeout_us) = 0;
};

// One target on a bus: the address bound once (pw_i2c::Device).
class I2cDevice {
 public:
  I2cDevice(I2cInitiator& bus, uint8_t address) : bus_(bus), address_(address) {}
  BusStatus write(const uint8_t* tx, size_t len, uint32_t timeout_us) { return bus_.write(address_, tx, len, timeout_us); }
  BusStatus read(uint8_t* rx, size_t len, uint32_t timeout_us) { return bus_.read(address_, rx, len, timeout_us); }
  BusStatus write_read(const uint8_t* tx, size_t tx_len, uint8_t* rx, size_t rx_len, uint32_t timeout_us) {
    return bus_.write_read(address_, tx, tx_len, rx, rx_len, timeout_us);
  }
  uint8_t address() const { return address_; }

 private:
  I2cInitiator& bus_;
  uint8_t address_;
};

}  // namespace ff
