#pragma once
// The devices on the Teensy's pins, emulated, wired to the Teensyduino model
// as firmware/app/pins.hpp says: the zForce on Wire (0x50) with its DR line,
// the AD9834 on SPI (FSYNC), four load cells on their analog pins, and a
// network. Used by the binding's tests and by ff-sim.
#include <cstdint>
#include <deque>
#include <vector>

#include "frictionfield/core/sensor_sample.hpp"
#include "frictionfield/emulated/ad9834_model.hpp"
#include "frictionfield/emulated/zforce_model.hpp"
#include "teensy_model.hpp"

namespace teensy_model {

// A network of one host: datagrams it sends arrive at the device; what the
// device sends is kept. `answers_arp` false: the host address never answers.
class ScriptedNetwork final : public UdpNetwork {
 public:
  static constexpr uint32_t kHostIp = 0x0A01A8C0u;  // 192.168.1.10
  static constexpr uint16_t kHostPort = 50000;
  bool receive(std::vector<uint8_t>& payload, uint32_t& ip, uint16_t& port) override;
  bool deliver(uint32_t ip, uint16_t port, const std::vector<uint8_t>& payload) override;
  void host_send(std::vector<uint8_t> datagram) { to_device.push_back(std::move(datagram)); }

  bool answers_arp = true;
  std::deque<std::vector<uint8_t>> to_device;
  std::vector<std::vector<uint8_t>> from_device;
  uint32_t unanswered = 0;
};

class SimDevices {
 public:
  static constexpr uint16_t kRestCounts = 100;     // each load cell with nothing on the plate
  static constexpr float kMilliNewtonPerCount = 10.508f;  // of the four cells' sum: 1.0712 g x 9.81 (drivers/load_cells)

  explicit SimDevices(const ff::emulated::ZforceModel::Options& zforce = ff::emulated::ZforceModel::Options());
  // Attach to the (reset) model.
  void wire(UdpNetwork& network);

  ff::emulated::ZforceModel zforce;
  ff::emulated::Ad9834Model dds;
  // The finger's force on the plate, shared equally by the four cells.
  void set_force_mN(float mN) { force_mN_ = mN; }
  // Per-pin counts override (tests): pin -> counts.
  uint16_t counts_on_pin[70] = {};
  bool use_pin_counts = false;

 private:
  float force_mN_ = 0.0f;
};

}  // namespace teensy_model
