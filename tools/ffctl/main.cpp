// ffctl: see what a frictionfield device does, record it, prove it, flash it.
#include <CLI/CLI.hpp>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "device_client.hpp"
#include "frictionfield/host/scene_spec.hpp"
#include "halfkay.hpp"
#include "hid_transport.hpp"
#include "scene_command.hpp"

namespace {

using ff::protocol::Message;
using ff::protocol::MessageType;

volatile std::sig_atomic_t g_interrupted = 0;
void on_interrupt(int) { g_interrupted = 1; }

int fail(const std::string& what) {
  std::cerr << "ffctl: " << what << "\n";
  return 1;
}

// Whether any of the shared scene words (--scene, --target, --strength, ...) was given.
bool scene_words_given(const CLI::App& cmd) {
  for (const CLI::Option* o : cmd.get_options()) {
    const std::string name = o->get_name();
    if (name == "--help" || name == "--output" || name == "--seconds" || name == "trace") continue;
    if (o->count() > 0) return true;
  }
  return false;
}

bool set_condition(ff::ffctl::DeviceClient& client, const ff::host::SceneSpec& spec,
                   ff::protocol::ConditionMessage& sent, std::string& error) {
  Message m, reply;
  m.type = MessageType::SetCondition;
  if (!ff::ffctl::condition_message(spec, m.condition, error)) return false;
  sent = m.condition;
  if (!client.request(m, reply, error)) return false;
  if (reply.ack.status != ff::protocol::AckStatus::Ok) {
    error = std::string("the device refused the scene: ") + ff::to_string(static_cast<ff::PrepareStatus>(reply.ack.detail));
    return false;
  }
  return true;
}

// Asks a running frictionfield device to restart into the bootloader: the
// SEREMU feature report first (works even if the firmware's loop hangs), the
// protocol message if that is refused.
bool reboot_device(const std::string& serial, std::string& error) {
  ff::ffctl::HidTransport transport(serial);
  if (transport.request_bootloader()) return true;
  ff::ffctl::DeviceClient client(transport);
  Message m, reply;
  m.type = MessageType::RebootToBootloader;
  return client.request(m, reply, error);
}

bool wait_for_bootloader(int seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    if (ff::ffctl::halfkay_present()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  return false;
}

void print_verify(const ff::ffctl::VerifyResult& v) {
  std::printf("compared %zu ticks: max |d amplitude| %.6f, max |d dac| %d; %zu beyond one DAC code "
              "(%zu with a finger on one side only) in %zu runs\n",
              v.compared, static_cast<double>(v.max_amplitude_difference), v.max_dac_difference, v.beyond_one_code,
              v.presence_mismatches, v.run_count);
  if (v.warm_up > 0) {
    std::printf("  %zu ticks not compared: the device's filters held reports the recording lacks (its start, or "
                "ticks the stream lost) until a tick without a finger on both sides\n",
                v.warm_up);
  }
  if (!v.synchronised) std::printf("  the finger never left the plate: compared from the first tick, start-up included\n");
  if (v.missing_ticks > 0) std::printf("  %zu ticks missing from the stream (the device overran)\n", v.missing_ticks);
  if (!v.exact_alignment) {
    std::printf("  the recording does not say which tick took each report: reports delivered by timestamp "
                "(a report read across a tick boundary shows as a one-tick difference)\n");
  }
  auto print_tick = [](const char* what, const ff::ffctl::Mismatch& m) {
    std::printf("    %s %llu us: device %.5f (dac %u%s), native %.5f (dac %u%s)\n", what,
                static_cast<unsigned long long>(m.t_us), static_cast<double>(m.device_amplitude), m.device_dac,
                m.device_present ? "" : ", no finger", static_cast<double>(m.native_amplitude), m.native_dac,
                m.native_present ? "" : ", no finger");
  };
  for (const auto& run : v.runs) {
    std::printf("  t %llu..%llu us: %zu ticks differ, up to %d DAC codes\n",
                static_cast<unsigned long long>(run.first_t_us), static_cast<unsigned long long>(run.last_t_us),
                run.ticks, run.max_dac_difference);
    print_tick("first at", run.first);
    if (run.worst.t_us != run.first.t_us) print_tick("worst at", run.worst);
  }
  if (v.run_count > v.runs.size()) std::printf("  ... and %zu more runs\n", v.run_count - v.runs.size());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ffctl: talk to a frictionfield device (Teensy 3.6, USB type USB_HID) over USB.\n"
               "  ffctl list | status | scene --scene heightmap --target top --strength 0.66\n"
               "  ffctl record -o trace.csv [--seconds 30] [scene words] | verify trace.csv | reboot | flash firmware.hex"};
  app.require_subcommand(1);
  app.footer(
      "A session:\n"
      "  ffctl list                          is the device on USB?\n"
      "  ffctl status                        what it renders, how long a tick takes, what went wrong\n"
      "  ffctl record -o run1.csv --seconds 30 --scene heightmap --target top --strength 0.66\n"
      "  ffctl verify run1.csv               does the firmware render what the native core computes?\n"
      "  ffctl flash firmware.hex            new firmware (a running device is restarted into its bootloader)\n"
      "Permission denied? Install udev/49-frictionfield.rules (docs/ffctl.md).");
  std::string serial;
  app.add_option("--serial", serial, "the device's USB serial number (default: the first device)");

  auto* list = app.add_subcommand("list", "frictionfield devices on USB");
  auto* status = app.add_subcommand("status", "firmware version, condition, tick cost (CPU cycles per 500 us tick), fault counters, force");
  ff::host::SceneSpec scene_spec;
  auto* scene = app.add_subcommand("scene", "set the rendered condition: the same scene words as ff-replay");
  ff::host::add_scene_options(*scene, scene_spec);
  std::string record_out;
  double seconds = 0.0;
  ff::host::SceneSpec record_spec;
  auto* rec = app.add_subcommand("record", "stream the raw sensor reports (docs/spec.md sensor trace, ff-replay reads it) and every rendered tick to files");
  rec->add_option("-o,--output", record_out, "trace CSV (ticks go to NAME.ticks.csv)")->required();
  rec->add_option("--seconds", seconds, "how long to record (default: until Ctrl-C)");
  ff::host::add_scene_options(*rec, record_spec);
  rec->footer("With scene words the condition is set first and kept in NAME.condition for `ffctl verify`.");
  std::string verify_in;
  ff::host::SceneSpec verify_spec;
  auto* ver = app.add_subcommand("verify", "replay a recording through the native core and compare it tick by tick with the device; exit 1 if any tick differs by more than one DAC code");
  ver->add_option("trace", verify_in, "trace CSV written by ffctl record")->required();
  ff::host::add_scene_options(*ver, verify_spec);
  ver->footer("Without scene words: the condition `ffctl record` kept in NAME.condition.");
  auto* reboot = app.add_subcommand("reboot", "restart the device into its bootloader (HalfKay), ready for flash");
  std::string hex;
  auto* flash = app.add_subcommand("flash", "write a firmware image (Intel HEX) through the Teensy bootloader");
  flash->add_option("firmware", hex, "firmware.hex from `pio run -e teensy36`")->required();
  CLI11_PARSE(app, argc, argv);

  try {
    if (*list) {
      const auto devices = ff::ffctl::list_devices();
      if (devices.empty()) std::cout << "no frictionfield devices (16c0:0482, serial-emulation interface)\n";
      for (const auto& d : devices) std::cout << d.serial << "  " << d.product << "  " << d.path << "\n";
      if (ff::ffctl::halfkay_present()) std::cout << "a Teensy in its bootloader (16c0:0478): `ffctl flash firmware.hex`\n";
      return 0;
    }
    if (*ver) {
      ff::ffctl::Recording r;
      std::string error;
      if (!ff::ffctl::read_recording(verify_in, r, error)) return fail(error);
      ff::Condition c;
      if (scene_words_given(*ver)) {
        if (!ff::host::make_condition(verify_spec, c, error)) return fail(error);
      } else if (r.has_condition) {
        c = r.condition.to_condition();
        std::printf("condition (%s): %s\n", ff::ffctl::condition_path_for(verify_in).c_str(),
                    ff::ffctl::describe(r.condition).c_str());
      } else {
        return fail("no " + ff::ffctl::condition_path_for(verify_in) +
                    ": give the condition the device rendered, e.g. --scene heightmap --target top --strength 0.66");
      }
      const auto v = ff::ffctl::verify(r, c);
      if (!v.prepared) return fail("the condition does not prepare natively");
      print_verify(v);
      return v.beyond_one_code == 0 && v.compared > 0 ? 0 : 1;
    }
    if (*flash) {
      std::ifstream in(hex);
      if (!in) return fail("cannot open " + hex);
      std::stringstream text;
      text << in.rdbuf();
      ff::ffctl::FlashImage image;
      std::string error;
      // Checked before anything touches USB.
      if (!ff::ffctl::parse_intel_hex(text.str(), image, error)) return fail(hex + ": " + error);
      const auto writes = ff::ffctl::halfkay_writes(image);
      std::fprintf(stderr, "%s: %zu bytes (%.1f%% of the flash), %zu blocks to write\n", hex.c_str(), image.highest,
                   100.0 * static_cast<double>(image.highest) / static_cast<double>(ff::ffctl::kMk66FlashBytes),
                   writes.size() - 1);
      if (!ff::ffctl::halfkay_present() && !ff::ffctl::list_devices().empty()) {
        if (!reboot_device(serial, error)) return fail("could not restart the device into its bootloader: " + error);
        std::fprintf(stderr, "asked the device to restart into its bootloader\n");
      }
      const bool ok = ff::ffctl::halfkay_flash(writes, [](size_t done, size_t total) {
        const int bar = static_cast<int>(40 * done / total);
        std::fprintf(stderr, "\r[%.*s%*s] %zu/%zu", bar, "########################################", 40 - bar, "",
                     done, total);
      }, error);
      std::fprintf(stderr, "\n");
      if (!ok) return fail(error);
      std::fprintf(stderr, "written; the new firmware is starting\n");
      return 0;
    }
    if (*reboot) {
      std::string error;
      if (!reboot_device(serial, error)) return fail(error);
      if (!wait_for_bootloader(5)) return fail("the device did not come back as the bootloader (16c0:0478) within 5 s");
      std::printf("the bootloader is up: `ffctl flash firmware.hex` next\n");
      return 0;
    }

    // Scene words are checked before anything touches USB.
    if (*scene || (*rec && scene_words_given(*rec))) {
      ff::protocol::ConditionMessage unused;
      std::string error;
      if (!ff::ffctl::condition_message(*scene ? scene_spec : record_spec, unused, error)) return fail(error);
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
      static const char* kinds[] = {"heightmap", "frictionmap", "neutral", "general scene"};
      static const char* targets[] = {"top", "middle", "bottom"};
      std::printf("firmware %u.%u (protocol %u), %u ticks, finger %s\n", s.firmware_version >> 8,
                  s.firmware_version & 0xFF, ff::protocol::kVersion, s.ticks, s.finger_present ? "down" : "up");
      std::printf("condition: %s, target %s, strength %.3g\n", kinds[static_cast<int>(s.kind)],
                  targets[static_cast<int>(s.target)], static_cast<double>(s.strength));
      // 500 us at 180 MHz: 90,000 cycles per tick.
      std::printf("tick cost: mean %u, max %u cycles (%.1f%% / %.1f%% of the 90000 a tick has)\n", s.tick_cycles_mean,
                  s.tick_cycles_max, s.tick_cycles_mean / 900.0, s.tick_cycles_max / 900.0);
      std::printf("carrier %.1f Hz, force %.1f mN%s, protocol errors %u\n", static_cast<double>(s.carrier_hz),
                  static_cast<double>(s.force_mN), s.over_force ? " (OVER the limit)" : "", s.protocol_errors);
      bool any = false;
      for (int i = 0; i < static_cast<int>(ff::Fault::kCount); ++i) {
        if (s.faults.count[i] == 0) continue;
        std::printf("%s%s %u", any ? ", " : "faults: ", ff::to_string(static_cast<ff::Fault>(i)), s.faults.count[i]);
        any = true;
      }
      std::printf(any ? "\n" : "faults: none\n");
      return 0;
    }
    if (*scene) {
      ff::protocol::ConditionMessage sent;
      if (!set_condition(client, scene_spec, sent, error)) return fail(error);
      std::printf("condition set: %s\n", ff::ffctl::describe(sent).c_str());
      return 0;
    }
    if (*rec) {
      ff::ffctl::Recording r;
      if (scene_words_given(*rec)) {
        if (!set_condition(client, record_spec, r.condition, error)) return fail(error);
        r.has_condition = true;
        std::fprintf(stderr, "condition set: %s\n", ff::ffctl::describe(r.condition).c_str());
      }
      std::signal(SIGINT, on_interrupt);
      const bool ok = ff::ffctl::record(client, seconds, r, error, [&](double done, size_t s, size_t t) {
        if (seconds > 0.0) {
          std::fprintf(stderr, "\rrecording %6.1f / %.1f s: %zu reports, %zu ticks ", done, seconds, s, t);
        } else {
          std::fprintf(stderr, "\rrecording %6.1f s (Ctrl-C ends): %zu reports, %zu ticks ", done, s, t);
        }
        return g_interrupted == 0;
      });
      std::fprintf(stderr, "\n");
      std::string werr;
      if (!ff::ffctl::write_recording(record_out, r, werr)) return fail(werr);
      std::fprintf(stderr, "wrote %s, %s%s\n", record_out.c_str(), ff::ffctl::ticks_path_for(record_out).c_str(),
                   r.has_condition ? (" and " + ff::ffctl::condition_path_for(record_out)).c_str() : "");
      if (client.malformed_replies() > 0) {
        std::fprintf(stderr, "%u malformed frames were skipped\n", client.malformed_replies());
      }
      return ok ? 0 : fail(error + " (what arrived was kept)");
    }
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  return 0;
}
