#include "frictionfield/bus/bus_status.hpp"

namespace ff {

const char* to_string(BusStatus s) {
  switch (s) {
    case BusStatus::Ok: return "ok";
    case BusStatus::Timeout: return "timeout";
    case BusStatus::Nack: return "nack";
    case BusStatus::BusError: return "bus error";
    case BusStatus::InvalidArgument: return "invalid argument";
    case BusStatus::Busy: return "busy";
  }
  return "?";
}

}  // namespace ff
