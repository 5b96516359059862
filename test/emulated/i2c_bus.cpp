#include "frictionfield/emulated/i2c_bus.hpp"

namespace ff::emulated {

BusStatus EmulatedI2cBus::do_write_read(uint8_t address, const uint8_t* tx, size_t tx_len, uint8_t* rx,
                                        size_t rx_len, uint32_t) {
  ++transactions_;
  if (fail_count_ > 0) {
    --fail_count_;
    return fail_status_;
  }
  const auto it = targets_.find(address);
  if (it == targets_.end()) return BusStatus::Nack;
  if (tx_len != 0) {
    const BusStatus s = it->second->on_write(tx, tx_len);
    if (s != BusStatus::Ok) return s;
  }
  if (rx_len != 0) return it->second->on_read(rx, rx_len);
  return BusStatus::Ok;
}

}  // namespace ff::emulated
