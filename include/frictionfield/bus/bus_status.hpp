#pragma once
// Result of one bus transaction. Drivers count what goes wrong and carry on;
// nothing on a bus path throws or allocates.
#include <cstdint>

namespace ff {

enum class BusStatus : uint8_t {
  Ok,
  Timeout,          // the transaction did not finish within its time limit
  Nack,             // I2C: no device acknowledged the address or a byte
  BusError,         // arbitration lost, stuck line, FIFO error
  InvalidArgument,  // rejected before touching the bus (bad address, length, code, channel)
  Busy,             // the peripheral is in use by another transaction
};

const char* to_string(BusStatus s);

}  // namespace ff
