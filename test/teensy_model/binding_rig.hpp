#pragma once
// The binding's test bench: the Teensyduino model reset, the emulated devices
// on their pins, and the two hosts (USB and network) speaking the protocol.
#include <cmath>
#include <vector>

#include "frictionfield/core/scenes.hpp"
#include "frictionfield/protocol/codec.hpp"
#include "frictionfield/protocol/hid_channel.hpp"
#include "sim_devices.hpp"

namespace teensy_model {

// A finger sliding left and right along y = 240 at 300 px/s, a report every 5 ms.
inline std::vector<ff::SensorSample> back_and_forth(uint32_t from_us, uint32_t to_us) {
  std::vector<ff::SensorSample> trace;
  for (uint32_t t = from_us; t < to_us; t += 5000) {
    const double phase = std::fmod((t - from_us) * 1e-6 * 300.0, 1200.0);
    const double x = 100.0 + (phase < 600.0 ? phase : 1200.0 - phase);
    trace.push_back({t, static_cast<float>(x), 240.0f, true});
  }
  trace.push_back({to_us, trace.back().x, 240.0f, false});
  return trace;
}

// The DAC code playing at time t (the last change at or before it).
inline int dac_code_at(uint64_t t) {
  int code = -1;
  for (const DacState& d : dac_history()) {
    if (d.t_us > t) break;
    code = d.enabled ? d.code : -1;
  }
  return code;
}

struct BindingRig {
  explicit BindingRig(const Options& options = Options()) {
    reset(options);
    devices.wire(network);
  }
  void boot() { teensy_model::boot(); }
  void run_until(uint64_t t) { teensy_model::run_until(t); }

  static std::vector<uint8_t> encode(const ff::protocol::Message& m) {
    std::vector<uint8_t> f(ff::protocol::kMaxFrame);
    f.resize(ff::protocol::encode(m, f.data(), f.size()));
    return f;
  }
  // As ffctl writes it: each 64-byte report as two 32-byte SEREMU OUT reports.
  void usb_send(const ff::protocol::Message& m) {
    const std::vector<uint8_t> f = encode(m);
    uint8_t reports[ff::protocol::kMaxHidReports][ff::protocol::kHidReportBytes];
    const size_t n = ff::protocol::split_into_reports(f.data(), f.size(), reports, ff::protocol::kMaxHidReports);
    for (size_t i = 0; i < n; ++i) {
      host_write_out_packet(reports[i], 32);
      host_write_out_packet(reports[i] + 32, 32);
    }
  }
  std::vector<ff::protocol::Message> usb_received() {
    std::vector<ff::protocol::Message> out;
    for (const std::vector<uint8_t>& packet : host_take_seremu_in()) {
      if (!usb_in.push(packet.data())) continue;
      ff::protocol::Message m;
      if (ff::protocol::decode(usb_in.frame(), usb_in.size(), m) == ff::protocol::DecodeStatus::Ok) out.push_back(m);
    }
    return out;
  }
  void udp_send(const ff::protocol::Message& m) { network.host_send(encode(m)); }
  std::vector<ff::protocol::Message> udp_received() {
    std::vector<ff::protocol::Message> out;
    for (const std::vector<uint8_t>& d : network.from_device) {
      ff::protocol::Message m;
      if (ff::protocol::decode(d.data(), d.size(), m) == ff::protocol::DecodeStatus::Ok) out.push_back(m);
    }
    network.from_device.clear();
    return out;
  }
  ff::protocol::Message udp_status() {
    ff::protocol::Message q;
    q.type = ff::protocol::MessageType::QueryStatus;
    udp_send(q);
    run_until(now_us() + 50000);
    ff::protocol::Message last;
    for (const ff::protocol::Message& m : udp_received()) {
      if (m.type == ff::protocol::MessageType::Status) last = m;
    }
    return last;
  }

  ScriptedNetwork network;
  SimDevices devices;
  ff::protocol::HidReassembler usb_in;
};

}  // namespace teensy_model
