#include "sim_devices.hpp"

#include "firmware/app/pins.hpp"

namespace teensy_model {

bool ScriptedNetwork::receive(std::vector<uint8_t>& payload, uint32_t& ip, uint16_t& port) {
  if (to_device.empty()) return false;
  payload = std::move(to_device.front());
  to_device.pop_front();
  ip = kHostIp;
  port = kHostPort;
  return true;
}

bool ScriptedNetwork::deliver(uint32_t ip, uint16_t port, const std::vector<uint8_t>& payload) {
  if (!answers_arp || ip != kHostIp || port != kHostPort) {
    ++unanswered;
    return false;
  }
  from_device.push_back(payload);
  return true;
}

SimDevices::SimDevices(const ff::emulated::ZforceModel::Options& zforce_options) : zforce(zforce_options) {}

void SimDevices::wire(UdpNetwork& network) {
  namespace pins = ff::firmware::pins;
  attach_i2c(0x50, zforce);
  attach_spi(pins::kDdsChipSelect, dds);
  set_time_hook([this](uint64_t now) { zforce.advance_to(static_cast<uint32_t>(now)); });
  set_data_ready_source([this](uint64_t now) {
    zforce.advance_to(static_cast<uint32_t>(now));
    return zforce.asserted();
  });
  set_analog_source([this](uint8_t pin, uint64_t) -> uint16_t {
    if (use_pin_counts) return pin < 70 ? counts_on_pin[pin] : 0;
    for (uint8_t p : pins::kLoadCells) {
      if (p == pin) return static_cast<uint16_t>(kRestCounts + force_mN_ / (4.0f * kMilliNewtonPerCount) + 0.5f);
    }
    return 0;
  });
  set_network(&network);
}

}  // namespace teensy_model
