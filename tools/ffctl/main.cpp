// ffctl: see what a frictionfield device does, record it, prove it, flash it.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "device_client.hpp"
#include "frictionfield/host/scene_spec.hpp"
#include "halfkay.hpp"
#include "hid_transport.hpp"

namespace {

using ff::protocol::Message;
using ff::protocol::MessageType;

int fail(const std::string& what) {
  std::cerr << "ffctl: " << what << "\n";
  return 1;
}

ff::protocol::ConditionMessage condition_message(const ff::host::SceneSpec& spec, const ff::Condition& c) {
  ff::protocol::ConditionMessage m;
  m.strength = spec.strength;
  m.idle_amplitude = spec.idle_amplitude;
  m.inverted_dac = spec.inverted_dac;
  m.target = spec.target == "top" ? ff::Target::Top : spec.target == "bottom" ? ff::Target::Bottom : ff::Target::Middle;
  const bool builtin = spec.evaluation == "closed";
  if (builtin && spec.scene == "heightmap") m.kind = ff::protocol::ConditionKind::Heightmap;
  else if (builtin && spec.scene == "frictionmap") m.kind = ff::protocol::ConditionKind::Frictionmap;
  else if (spec.scene == "neutral") m.kind = ff::protocol::ConditionKind::Neutral;
  else {
    m.kind = ff::protocol::ConditionKind::General;
    m.scene = c.scene;
  }
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ffctl: talk to a frictionfield device (Teensy 3.6) over USB.\n"
               "  ffctl list | status | scene --scene heightmap --target top --strength 0.66\n"
               "  ffctl record -o trace.csv --seconds 30 | verify trace.csv --scene ... | reboot | flash firmware.hex"};
  app.require_subcommand(1);
  std::string serial;
  app.add_option("--serial", serial, "the device's USB serial number (default: the first device)");

  auto* list = app.add_subcommand("list", "frictionfield devices on USB");
  auto* status = app.add_subcommand("status", "firmware version, scene, tick cost, error counters, force");
  ff::host::SceneSpec scene_spec;
  auto* scene = app.add_subcommand("scene", "set the rendered condition (the same words as ff-replay)");
  ff::host::add_scene_options(*scene, scene_spec);
  std::string record_out;
  double seconds = 10.0;
  auto* rec = app.add_subcommand("record", "stream the raw sensor reports and the rendered ticks into a trace");
  rec->add_option("-o,--output", record_out, "trace CSV (ticks go to NAME.ticks.csv)")->required();
  rec->add_option("--seconds", seconds, "how long to record")->capture_default_str();
  std::string verify_in;
  ff::host::SceneSpec verify_spec;
  auto* ver = app.add_subcommand("verify", "replay a recording natively and compare tick by tick with the device");
  ver->add_option("trace", verify_in, "trace CSV written by ffctl record")->required();
  ff::host::add_scene_options(*ver, verify_spec);
  auto* reboot = app.add_subcommand("reboot", "restart the device into its bootloader");
  std::string hex;
  auto* flash = app.add_subcommand("flash", "write a firmware image (Intel HEX) through the Teensy bootloader");
  flash->add_option("firmware", hex, "firmware.hex from `pio run -e teensy36`")->required();
  CLI11_PARSE(app, argc, argv);

  try {
    if (*list) {
      const auto devices = ff::ffctl::list_devices();
      if (devices.empty()) std::cout << "no frictionfield devices (16c0:0482, serial-emulation interface)\n";
      for (const auto& d : devices) std::cout << d.serial << "  " << d.product << "  " << d.path << "\n";
      return 0;
    }
    if (*ver) {
      ff::ffctl::Recording r;
      std::string error;
      if (!ff::ffctl::read_recording(verify_in, r, error)) return fail(error);
      ff::Condition c;
      if (!ff::host::make_condition(verify_spec, c, error)) return fail(error);
      const auto v = ff::ffctl::verify(r, c);
      std::printf("compared %zu ticks: max |d amplitude| %.6f, max |d dac| %d, %zu beyond one code\n", v.compared,
                  static_cast<double>(v.max_amplitude_difference), v.max_dac_difference, v.beyond_one_code);
      for (const auto& m : v.first) {
        std::printf("  t %llu us: device %.5f (%u), native %.5f (%u)\n", static_cast<unsigned long long>(m.t_us),
                    static_cast<double>(m.device_amplitude), m.device_dac, static_cast<double>(m.native_amplitude),
                    m.native_dac);
      }
      return v.beyond_one_code == 0 && v.compared > 0 ? 0 : 1;
    }
    if (*flash) {
      std::ifstream in(hex);
      if (!in) return fail("cannot open " + hex);
      std::stringstream text;
      text << in.rdbuf();
      ff::ffctl::FlashImage image;
      std::string error;
      if (!ff::ffctl::parse_intel_hex(text.str(), image, error)) return fail(hex + ": " + error);
      const auto writes = ff::ffctl::halfkay_writes(image);
      std::fprintf(stderr, "%s: %zu bytes, %zu blocks to write\n", hex.c_str(), image.highest, writes.size() - 1);
      const bool ok = ff::ffctl::halfkay_flash(writes, [](size_t done, size_t total) {
        const int bar = static_cast<int>(40 * done / total);
        std::fprintf(stderr, "\r[%.*s%*s] %zu/%zu", bar, "########################################", 40 - bar, "",
                     done, total);
      }, error);
      std::fprintf(stderr, "\n");
      return ok ? 0 : fail(error);
    }

    ff::ffctl::HidTransport transport(serial);
    ff::ffctl::DeviceClient client(transport);
    Message reply;
    std::string error;
    if (*status) {
      Message q;
      q.type = MessageType::QueryStatus;
      if (!client.request(q, reply, error)) return fail(error);
      const auto& s = reply.status;
      std::printf("firmware %u.%u, scene kind %d target %d strength %.2f, finger %s\n", s.firmware_version >> 8,
                  s.firmware_version & 0xFF, static_cast<int>(s.kind), static_cast<int>(s.target),
                  static_cast<double>(s.strength), s.finger_present ? "down" : "up");
      std::printf("ticks %u, tick cost mean %u / max %u cycles (of 90000), carrier %.1f Hz\n", s.ticks,
                  s.tick_cycles_mean, s.tick_cycles_max, static_cast<double>(s.carrier_hz));
      std::printf("force %.1f mN%s, protocol errors %u\n", static_cast<double>(s.force_mN),
                  s.over_force ? " (over 0.5 N)" : "", s.protocol_errors);
      for (int i = 0; i < static_cast<int>(ff::Fault::kCount); ++i) {
        if (s.faults.count[i]) std::printf("  %s: %u\n", ff::to_string(static_cast<ff::Fault>(i)), s.faults.count[i]);
      }
      return 0;
    }
    if (*scene) {
      ff::Condition c;
      if (!ff::host::make_condition(scene_spec, c, error)) return fail(error);
      Message m;
      m.type = MessageType::SetCondition;
      m.condition = condition_message(scene_spec, c);
      if (!client.request(m, reply, error)) return fail(error);
      if (reply.ack.status != ff::protocol::AckStatus::Ok) {
        return fail(std::string("the device refused the scene: ") + ff::to_string(static_cast<ff::PrepareStatus>(reply.ack.detail)));
      }
      std::printf("scene set\n");
      return 0;
    }
    if (*rec) {
      ff::ffctl::Recording r;
      const bool ok = ff::ffctl::record(client, seconds, r, error, [&](double done, size_t s, size_t t) {
        std::fprintf(stderr, "\rrecording %5.1f / %.1f s: %zu reports, %zu ticks", done, seconds, s, t);
      });
      std::fprintf(stderr, "\n");
      std::string werr;
      if (!ff::ffctl::write_recording(record_out, r, werr)) return fail(werr);
      std::fprintf(stderr, "wrote %s and %s\n", record_out.c_str(), ff::ffctl::ticks_path_for(record_out).c_str());
      return ok ? 0 : fail(error + " (what arrived was kept)");
    }
    if (*reboot) {
      Message m;
      m.type = MessageType::RebootToBootloader;
      if (!client.request(m, reply, error)) return fail(error);
      std::printf("rebooting into the bootloader: `ffctl flash firmware.hex` next\n");
      return 0;
    }
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  return 0;
}
