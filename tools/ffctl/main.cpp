// ffctl: see what a frictionfield device does, record it, prove it, flash it.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <thread>

#include "device_client.hpp"
#include "frictionfield/drivers/zforce_sensor.hpp"
#include "frictionfield/host/cli_conventions.hpp"
#include "frictionfield/host/input_file.hpp"
#include "frictionfield/host/scene_spec.hpp"
#include "frictionfield/host/sensor_profile_options.hpp"
#include "halfkay.hpp"
#include "hid_transport.hpp"
#include "scene_command.hpp"
#include "udp_transport.hpp"

namespace {

using ff::protocol::Message;
using ff::protocol::MessageType;

// One exit-code convention for every frictionfield tool (cli_conventions.hpp): 1 is a failed
// check (verify mismatch, the device refused or did not answer), 2 bad usage or input
// (options, files, images).
using ff::host::kExitBadUsage;
using ff::host::kExitCheckFailed;
using ff::host::kExitOk;

volatile std::sig_atomic_t g_interrupted = 0;
void on_interrupt(int) { g_interrupted = 1; }

int fail(const std::string& what) {
  std::cerr << "ffctl: " << what << "\n";
  return kExitCheckFailed;
}
int usage(const std::string& what) {
  std::cerr << "ffctl: " << what << "\n";
  return kExitBadUsage;
}

// Whether any of the shared scene words (--scene, --target, --strength, ...) was given.
bool scene_words_given(const CLI::App& cmd) {
  for (const CLI::Option* o : cmd.get_options()) {
    const std::string name = o->get_name();
    if (name == "--help" || name == "--output" || name == "--seconds" || name == "trace" || name == "--progress" ||
        name == "--min-coverage") {
      continue;
    }
    if (o->count() > 0) return true;
  }
  return false;
}

// The words as typed after the subcommand, for the recording's metadata.
std::string words_after(int argc, char** argv, const std::string& subcommand) {
  std::string out;
  bool after = false;
  for (int i = 1; i < argc; ++i) {
    if (after) out += (out.empty() ? "" : " ") + std::string(argv[i]);
    if (argv[i] == subcommand) after = true;
  }
  return out;
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

bool wait_for_bootloader(int seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    if (ff::ffctl::halfkay_present()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  return false;
}

// 500 us at 180 MHz: 90,000 cycles per tick.
constexpr double kTickCycles = 90000.0;
constexpr double kTickUs = 500.0;

// What only silicon can tell: the whole interrupt (DWT cycles, entry to
// exit), the last scene preparation, the longest main-loop pass, and which
// zForce notification layout the sensor sends.
void print_silicon(const ff::protocol::StatusMessage& s) {
  const auto pct = [](double cycles) { return 100.0 * cycles / kTickCycles; };
  std::printf("interrupt (whole, DWT): mean %u, p99 %u, max %u cycles (%.1f%% / %.1f%% / %.1f%% of a 500 us tick)\n",
              s.isr_cycles_mean, s.isr_cycles_p99, s.isr_cycles_max, pct(s.isr_cycles_mean), pct(s.isr_cycles_p99),
              pct(s.isr_cycles_max));
  std::printf("last scene preparation %u us (%.1f ticks), longest main-loop pass %u us (%.1f%% of a tick)\n",
              s.prepare_us_last, s.prepare_us_last / kTickUs, s.loop_pass_max_us, 100.0 * s.loop_pass_max_us / kTickUs);
  std::printf("zForce touch notifications: %u with the timestamp beside the touches, %u inside them\n",
              s.zforce_layout_beside, s.zforce_layout_inside);
}

// What the firmware and the zForce driver count, nonzero ones only: the
// device's (refused conditions, restarts, lost frames...) and the sensor's
// errors; frames read and samples show that it reports at all.
void print_device_and_sensor(const ff::protocol::StatusMessage& s) {
  using ff::protocol::DeviceCount;
  bool any = false;
  for (int i = 0; i < static_cast<int>(DeviceCount::kCount); ++i) {
    if (s.device.count[i] == 0) continue;
    std::printf("%s%s %u", any ? ", " : "device: ", ff::protocol::to_string(static_cast<DeviceCount>(i)),
                s.device.count[i]);
    any = true;
  }
  if (any) std::printf("\n");
  std::printf("touch sensor: %s", ff::protocol::to_string(s.sensor_state));
  for (int i = 0; i < s.sensor_count_n; ++i) {
    if (s.sensor_counts[i] == 0) continue;
    const char* name = i < static_cast<int>(ff::ZforceCount::kCount) ? ff::to_string(static_cast<ff::ZforceCount>(i)) : "other";
    std::printf(", %s %u", name, s.sensor_counts[i]);
  }
  std::printf("\n");
}

void print_status(const ff::protocol::StatusMessage& s) {
  static const char* kinds[] = {"heightmap", "frictionmap", "neutral", "general scene"};
  static const char* targets[] = {"top", "middle", "bottom"};
  std::printf("firmware %u.%u (protocol %u), %u ticks, finger %s\n", s.firmware_version >> 8, s.firmware_version & 0xFF,
              ff::protocol::kVersion, s.ticks, s.finger_present ? "down" : "up");
  std::printf("condition: %s, target %s, strength %.3g\n", kinds[static_cast<int>(s.kind)],
              targets[static_cast<int>(s.target)], static_cast<double>(s.strength));
  std::printf("tick cost: mean %u, max %u cycles (%.1f%% / %.1f%% of the 90000 a 500 us tick has at 180 MHz)\n",
              s.tick_cycles_mean, s.tick_cycles_max, 100.0 * s.tick_cycles_mean / kTickCycles,
              100.0 * s.tick_cycles_max / kTickCycles);
  print_silicon(s);
  std::printf("carrier %.1f Hz, force %.1f mN%s, protocol errors %u, watchdog trips %u, stream overruns %u\n",
              static_cast<double>(s.carrier_hz), static_cast<double>(s.force_mN), s.over_force ? " (OVER the limit)" : "",
              s.protocol_errors, s.watchdog_trips, s.stream_overruns);
  bool any = false;
  for (int i = 0; i < static_cast<int>(ff::Fault::kCount); ++i) {
    if (s.faults.count[i] == 0) continue;
    std::printf("%s%s %u", any ? ", " : "faults: ", ff::to_string(static_cast<ff::Fault>(i)), s.faults.count[i]);
    any = true;
  }
  std::printf(any ? "\n" : "faults: none\n");
  print_device_and_sensor(s);
}

// The monitor's line: `changing` holds what counts as a change (counters,
// finger, over-force), `line` adds what moves all the time (ticks, force).
void monitor_line(const ff::protocol::StatusMessage& s, std::string& line, std::string& changing) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "finger %s%s, protocol errors %u, watchdog trips %u, stream overruns %u, faults ",
                s.finger_present ? "down" : "up", s.over_force ? ", OVER-FORCE" : "", s.protocol_errors,
                s.watchdog_trips, s.stream_overruns);
  changing = buf;
  bool any = false;
  for (int i = 0; i < static_cast<int>(ff::Fault::kCount); ++i) {
    if (s.faults.count[i] == 0) continue;
    changing += (any ? " " : "") + std::string(ff::to_string(static_cast<ff::Fault>(i))) + "=" +
                std::to_string(s.faults.count[i]);
    any = true;
  }
  if (!any) changing += "none";
  // The sensor's state and what went wrong with it or the device (not what
  // moves all the time: frames read, samples, timestamp layouts).
  changing += std::string(", sensor ") + ff::protocol::to_string(s.sensor_state);
  for (int i = 0; i < static_cast<int>(ff::protocol::DeviceCount::kCount); ++i) {
    if (s.device.count[i] == 0) continue;
    changing += std::string(" ") + ff::protocol::to_string(static_cast<ff::protocol::DeviceCount>(i)) + "=" +
                std::to_string(s.device.count[i]);
  }
  for (int i = 0; i < s.sensor_count_n && i < static_cast<int>(ff::ZforceCount::kCount); ++i) {
    const auto c = static_cast<ff::ZforceCount>(i);
    if (s.sensor_counts[i] == 0 || c == ff::ZforceCount::FramesRead || c == ff::ZforceCount::Samples ||
        c == ff::ZforceCount::TimestampBeside || c == ff::ZforceCount::TimestampInside) {
      continue;
    }
    changing += std::string(" ") + ff::to_string(c) + "=" + std::to_string(s.sensor_counts[i]);
  }
  std::snprintf(buf, sizeof buf, "ticks %u, tick max %.1f%%, force %.0f mN, ", s.ticks,
                100.0 * s.tick_cycles_max / kTickCycles, static_cast<double>(s.force_mN));
  line = buf + changing;
}

void print_verify(const ff::ffctl::VerifyResult& v) {
  std::printf("compared %zu of %zu recorded ticks (coverage %.1f%%): max |d amplitude| %.6f, max |d dac| %d; "
              "%zu beyond one DAC code (%zu with a finger on one side only) in %zu runs\n",
              v.compared, v.recorded, 100.0 * v.coverage(), static_cast<double>(v.max_amplitude_difference),
              v.max_dac_difference, v.beyond_one_code, v.presence_mismatches, v.run_count);
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

// false with `error` "PATH: why".
bool read_file(const std::string& path, std::string& text, std::string& error) {
  std::ifstream in;
  std::string why;
  if (!ff::host::open_input_file(path, in, why)) return error = path + ": " + why, false;
  std::stringstream s;
  s << in.rdbuf();
  text = s.str();
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string version = ff::host::project_version();
  CLI::App app{"ffctl " + version + ": talk to a frictionfield device (Teensy 3.6) over USB (USB type USB_HID) or UDP.\n"
               "  ffctl list | status | monitor | scene --scene heightmap --target top --strength 0.66\n"
               "  ffctl sensor-profile --white-noise-px 1.2 ... (ff-track-bench --calibrate prints them) | --show\n"
               "  ffctl record -o trace.csv [--seconds 30] [scene words] | verify trace.csv\n"
               "  ffctl carrier 34900 | sweep 25000 70000 30000 | reboot | reset | flash [--wait] firmware.hex"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "ffctl " + version + " (protocol " + std::to_string(ff::protocol::kVersion) + ")");
  app.footer(
      "A session:\n"
      "  ffctl list                          is the device on USB?\n"
      "  ffctl status                        what it renders, how long a tick takes, what went wrong\n"
      "  ffctl record -o run1.csv --seconds 30 --scene heightmap --target top --strength 0.66\n"
      "  ffctl verify run1.csv               does the firmware render what the native core computes?\n"
      "  ffctl flash --wait firmware.hex     new firmware (a running device is restarted into its bootloader)\n"
      "  ffctl --udp 192.168.1.177 status    the same over Ethernet (or --udp 127.0.0.1 with ff-sim)\n"
      "Exit codes: 0 ok; 1 a failed check (verify mismatch or coverage too low, the device refused or did not\n"
      "answer); 2 bad usage or input (options, files, a firmware image not for the MK66).\n"
      "Permission denied? Install udev/49-frictionfield.rules (docs/ffctl.md).");
  std::string serial, udp;
  app.add_option("--serial", serial, "the USB device's serial number (default: the first device)");
  app.add_option("--udp", udp, "talk over UDP to HOST[:PORT] (IPv4, default port 8888) instead of USB");

  auto* list = app.add_subcommand("list", "frictionfield devices on USB");
  auto* status = app.add_subcommand(
      "status", "firmware version, condition, tick and interrupt cost (CPU cycles of the 90,000 a 500 us tick has), "
                "preparation and loop times, fault counters, force");
  auto* monitor = app.add_subcommand("monitor", "status and fault counters live, until Ctrl-C (one line refreshed on a "
                                                "terminal, one line per change otherwise)");
  double monitor_interval_s = 0.2;
  monitor->add_option("--interval", monitor_interval_s, "seconds between queries")
      ->check(CLI::Range(0.02, 60.0))
      ->capture_default_str();
  ff::host::SceneSpec scene_spec;
  auto* scene = app.add_subcommand("scene", "set the rendered condition: the same scene words as ff-replay");
  ff::host::add_scene_options(*scene, scene_spec);
  ff::SensorProfile profile;
  bool profile_show = false, profile_default = false;
  auto* sensor_profile = app.add_subcommand(
      "sensor-profile", "tell the device's tracker what its touch sensor is like (noise, report rate, latency) and "
                        "print what it uses now; kept until the device is reset or powered off");
  ff::host::add_sensor_profile_options(*sensor_profile, profile);
  auto* show_flag = sensor_profile->add_flag("--show", profile_show, "only print the profile the device uses");
  auto* default_flag = sensor_profile->add_flag("--default", profile_default, "send the default profile (as at power-on)");
  sensor_profile->footer(
      "ff-track-bench --calibrate measures a sensor and prints the flags for it (docs/tracking.md#calibration);\n"
      "flags left out take the default profile's values. The tracker starts afresh with the new profile: a finger\n"
      "on the screen is found again at its next report. Exit 1 if the device refuses the profile.");
  std::string record_out;
  double seconds = 0.0;
  bool progress_line = false;
  ff::host::SceneSpec record_spec;
  auto* rec = app.add_subcommand("record", "stream the raw sensor reports (ff-replay reads them), every rendered tick "
                                           "and the load cells to files, row by row as they arrive");
  rec->add_option("-o,--output", record_out, "trace CSV (ticks go to NAME.ticks.csv, force to NAME.force.csv)")->required();
  auto* seconds_option = rec->add_option("--seconds", seconds, "how long to record (default: until Ctrl-C)");
  rec->add_flag("--progress", progress_line, "the live line on stderr even when it is not a terminal");
  ff::host::add_scene_options(*rec, record_spec);
  rec->footer("With scene words the condition is set first and kept in NAME.condition for `ffctl verify`;\n"
              "the tracker's sensor profile (ffctl sensor-profile) is kept in NAME.sensor-profile.");
  std::string verify_in;
  double min_coverage_pct = 100.0 * ff::ffctl::kDefaultMinCoverage;
  ff::host::SceneSpec verify_spec;
  auto* ver = app.add_subcommand("verify", "replay a recording through the native core and compare it tick by tick "
                                           "with the device; exit 1 if a tick differs by more than one DAC code or "
                                           "too few ticks could be compared");
  ver->add_option("trace", verify_in, "trace CSV written by ffctl record")->required();
  ver->add_option("--min-coverage", min_coverage_pct, "percent of the recorded ticks that must be compared")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  ff::host::add_scene_options(*ver, verify_spec);
  ver->footer("Without scene words: the condition `ffctl record` kept in NAME.condition. The native tracker\n"
              "uses the sensor profile kept in NAME.sensor-profile (without one: the default profile).");
  double carrier_hz = 0.0;
  auto* carrier = app.add_subcommand("carrier", "set the AD9834 carrier frequency");
  carrier->add_option("hz", carrier_hz, "frequency in Hz (34900: the plate's mode (0;12))")->required();
  double sweep_start = 0.0, sweep_end = 0.0;
  uint32_t sweep_ms = 0;
  auto* sweep = app.add_subcommand("sweep", "sweep the carrier from START to END Hz over MS milliseconds (resonance search)");
  sweep->add_option("start", sweep_start, "start frequency, Hz")->required();
  sweep->add_option("end", sweep_end, "end frequency, Hz")->required();
  sweep->add_option("ms", sweep_ms, "duration, ms")->required();
  auto* reboot = app.add_subcommand("reboot", "restart the device into its bootloader (HalfKay), ready for flash");
  auto* reset = app.add_subcommand("reset", "leave the bootloader and run the firmware that is on the Teensy (HalfKay's boot command)");
  std::string hex;
  bool flash_wait = false;
  auto* flash = app.add_subcommand("flash", "write a firmware image (Intel HEX for the MK66FX1M0) through the Teensy bootloader");
  flash->add_option("firmware", hex, "firmware.hex from `pio run -e teensy36`")->required();
  flash->add_flag("-w,--wait", flash_wait, "wait (until Ctrl-C) for the bootloader: press the Teensy's button");
  if (const int code = ff::host::parse_command_line(app, argc, argv); code >= 0) return code;

  // Usage and input, checked before any device is touched.
  std::string udp_host;
  uint16_t udp_port = 0;
  {
    std::string error;
    if (!udp.empty() && !ff::ffctl::parse_udp_address(udp, udp_host, udp_port, error)) return usage(error);
    if (!udp.empty() && (*list || *flash || *reset)) {
      return usage(std::string("--udp: `") + app.get_subcommands()[0]->get_name() + "` is a USB command");
    }
    if (*rec) {
      if (seconds_option->count() > 0 && !(seconds > 0.0 && std::isfinite(seconds))) {
        return usage("record --seconds " + CLI::detail::to_string(seconds) + ": must be more than 0 (leave it out to record until Ctrl-C)");
      }
      if (!ff::ffctl::check_output_path(record_out, error)) return usage(error);
    }
    if (*scene && scene->count("--scene") == 0 && scene->count("--scene-file") == 0) {
      return usage("scene: which scene? e.g. `ffctl scene --scene heightmap --target top --strength 0.66` (ffctl scene --help)");
    }
    if (*scene || (*rec && scene_words_given(*rec)) || (*ver && scene_words_given(*ver))) {
      ff::protocol::ConditionMessage unused;
      if (!ff::ffctl::condition_message(*scene ? scene_spec : *rec ? record_spec : verify_spec, unused, error)) {
        return usage(error);
      }
    }
    if (*sensor_profile) {
      size_t values = 0;
      for (const CLI::Option* o : sensor_profile->get_options()) {
        if (o != show_flag && o != default_flag && o->get_name() != "--help") values += o->count();
      }
      if (profile_show + profile_default + (values > 0) > 1) {
        return usage("sensor-profile: give the profile's flags, --default or --show, one of them");
      }
      if (!profile_show && !profile_default && values == 0) {
        return usage("sensor-profile: which profile? the flags ff-track-bench --calibrate prints, --default, or "
                     "--show to see the device's (ffctl sensor-profile --help)");
      }
      if (!ff::is_valid(profile)) {  // each flag was checked against its range, but not against the others
        if (profile.correlated_noise_px > 0.0f && profile.correlation_time_ms == 0.0f) {
          return usage("sensor-profile: --correlated-noise-px " + CLI::detail::to_string(profile.correlated_noise_px) +
                       " needs a --correlation-time-ms above 0");
        }
        return usage("sensor-profile: not a profile the tracker can use (a value is not a number, or out of range)");
      }
    }
    if (*carrier && !(carrier_hz > 0.0 && std::isfinite(carrier_hz))) return usage("carrier: the frequency must be more than 0 Hz");
    if (*sweep && !(sweep_start > 0.0 && sweep_end > 0.0 && std::isfinite(sweep_start) && std::isfinite(sweep_end) && sweep_ms > 0)) {
      return usage("sweep: START and END must be more than 0 Hz and MS more than 0");
    }
  }

  try {
    if (*list) {
      const auto devices = ff::ffctl::list_devices();
      if (devices.empty()) std::cout << "no frictionfield devices (16c0:0482, serial-emulation interface)\n";
      for (const auto& d : devices) std::cout << d.serial << "  " << d.product << "  " << d.path << "\n";
      if (ff::ffctl::halfkay_present()) std::cout << "a Teensy in its bootloader (16c0:0478): `ffctl flash firmware.hex`\n";
      return kExitOk;
    }
    if (*ver) {
      ff::ffctl::Recording r;
      std::string error;
      if (!ff::ffctl::read_recording(verify_in, r, error)) return usage(error);
      ff::Condition c;
      if (scene_words_given(*ver)) {
        if (!ff::host::make_condition(verify_spec, c, error)) return usage(error);
      } else if (r.has_condition) {
        c = r.condition.to_condition();
        std::printf("condition (%s): %s\n", ff::ffctl::condition_path_for(verify_in).c_str(),
                    ff::ffctl::describe(r.condition).c_str());
      } else {
        return usage("no " + ff::ffctl::condition_path_for(verify_in) +
                     ": give the condition the device rendered, e.g. --scene heightmap --target top --strength 0.66");
      }
      if (r.has_sensor_profile) {
        std::printf("sensor profile (%s): %s\n", ff::ffctl::sensor_profile_path_for(verify_in).c_str(),
                    ff::ffctl::describe(r.sensor_profile).c_str());
      } else {
        std::printf("sensor profile: the default (no %s)\n", ff::ffctl::sensor_profile_path_for(verify_in).c_str());
      }
      const auto v = ff::ffctl::verify(r, c, ff::ffctl::tracker_config_of(r));
      if (!v.prepared) return usage("the condition does not prepare natively");
      print_verify(v);
      const double min_coverage = min_coverage_pct / 100.0;
      if (ff::ffctl::verify_passed(v, min_coverage)) {
        std::printf("PASS\n");
        return kExitOk;
      }
      if (v.beyond_one_code > 0) {
        std::printf("FAIL: %zu ticks differ by more than one DAC code\n", v.beyond_one_code);
      } else {
        std::printf("FAIL: coverage %.1f%% is below the minimum %.1f%% (--min-coverage): too few ticks compared to "
                    "prove anything\n",
                    100.0 * v.coverage(), min_coverage_pct);
      }
      return kExitCheckFailed;
    }
    if (*flash) {
      std::string text, error;
      if (!read_file(hex, text, error)) return usage(error);
      ff::ffctl::FlashImage image;
      // Checked before anything touches USB.
      if (!ff::ffctl::parse_intel_hex(text, image, error)) return usage(hex + ": " + error);
      if (!ff::ffctl::check_mk66_image(image, error)) return usage(hex + ": " + error);
      const auto writes = ff::ffctl::halfkay_writes(image);
      std::fprintf(stderr, "%s: %zu bytes (%.1f%% of the flash), %zu blocks to write\n", hex.c_str(), image.highest,
                   100.0 * static_cast<double>(image.highest) / static_cast<double>(ff::ffctl::kMk66FlashBytes),
                   writes.size() - 1);
      int wait_s = 10;
      if (!ff::ffctl::halfkay_present() && !ff::ffctl::list_devices().empty()) {
        ff::ffctl::HidTransport transport(serial);
        bool by_feature = false;
        if (!ff::ffctl::reboot_device(transport, error, by_feature)) {
          return fail("could not restart the device into its bootloader: " + error);
        }
        std::fprintf(stderr, "asked the device to restart into its bootloader%s\n",
                     by_feature ? " (SEREMU feature report: the firmware did not answer)" : "");
        if (flash_wait) wait_s = 0;  // a restart that does not come: the button, as --wait says
      } else if (!ff::ffctl::halfkay_present()) {
        if (!flash_wait) {
          return fail("no frictionfield device and no Teensy bootloader on USB: press the Teensy's button, or "
                      "use `ffctl flash --wait` to wait for it");
        }
        std::fprintf(stderr, "waiting for the Teensy bootloader (press the button; Ctrl-C gives up)\n");
        wait_s = 0;  // until it comes
      }
      const bool ok = ff::ffctl::halfkay_flash(writes, [](size_t done, size_t total) {
        const int bar = static_cast<int>(40 * done / total);
        std::fprintf(stderr, "\r[%.*s%*s] %zu/%zu", bar, "########################################", 40 - bar, "",
                     done, total);
      }, error, wait_s);
      std::fprintf(stderr, "\n");
      if (!ok) return fail(error);
      std::fprintf(stderr, "written; the new firmware is starting\n");
      return kExitOk;
    }
    if (*reset) {
      std::string error;
      if (!ff::ffctl::halfkay_boot(error)) return fail(error);
      std::printf("the Teensy left its bootloader: the firmware is starting\n");
      return kExitOk;
    }

    std::unique_ptr<ff::ffctl::Transport> transport;
    if (!udp.empty()) {
      transport = std::make_unique<ff::ffctl::UdpTransport>(udp_host, udp_port);
    } else {
      transport = std::make_unique<ff::ffctl::HidTransport>(serial);
    }
    ff::ffctl::DeviceClient client(*transport);
    Message reply;
    std::string error;
    if (*reboot) {
      bool by_feature = false;
      if (!ff::ffctl::reboot_device(*transport, error, by_feature)) return fail(error);
      if (by_feature) std::fprintf(stderr, "the firmware did not answer: restarted by the SEREMU feature report\n");
      if (!udp.empty()) {
        std::printf("the device acknowledged: it rests the plate and restarts into its bootloader\n");
        return kExitOk;
      }
      transport.reset();  // the device leaves the bus
      if (!wait_for_bootloader(5)) return fail("the device did not come back as the bootloader (16c0:0478) within 5 s");
      std::printf("the bootloader is up: `ffctl flash firmware.hex` next\n");
      return kExitOk;
    }
    if (*status) {
      Message q;
      q.type = MessageType::QueryStatus;
      if (!client.request(q, reply, error)) return fail(error);
      print_status(reply.status);
      ff::SensorProfile active;
      if (ff::ffctl::query_sensor_profile(client, active, error)) {
        std::printf("sensor profile: %s\n", ff::ffctl::describe(active).c_str());
      } else {
        std::printf("sensor profile: unknown (%s)\n", error.c_str());
      }
      return kExitOk;
    }
    if (*sensor_profile) {
      bool refused = false;
      if (!profile_show) {
        Message m;
        m.type = MessageType::SetSensorProfile;
        m.sensor_profile = profile;
        if (!client.request(m, reply, error)) return fail(error);
        refused = reply.ack.status != ff::protocol::AckStatus::Ok;
      }
      ff::SensorProfile active;
      if (!ff::ffctl::query_sensor_profile(client, active, error)) return fail(error);
      if (refused) std::printf("the device refused the profile (outside its limits); it keeps the one it had\n");
      std::printf("the device's tracker uses: %s\n", ff::ffctl::describe(active).c_str());
      std::printf("  ffctl sensor-profile %s\n", ff::host::sensor_profile_flags(active).c_str());
      return refused ? kExitCheckFailed : kExitOk;
    }
    if (*monitor) {
      std::signal(SIGINT, on_interrupt);
      const bool tty = ::isatty(STDOUT_FILENO) != 0;
      std::string last_changing;
      while (g_interrupted == 0) {
        Message q;
        q.type = MessageType::QueryStatus;
        if (!client.request(q, reply, error)) {
          if (g_interrupted) break;
          if (tty) std::printf("\n");
          return fail(error);
        }
        std::string line, changing;
        monitor_line(reply.status, line, changing);
        if (tty) {
          std::printf("\r%s\033[K", line.c_str());
        } else if (changing != last_changing) {
          std::printf("%s %s\n", ff::host::utc_timestamp().c_str(), line.c_str());
        }
        std::fflush(stdout);
        last_changing = changing;
        std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<int>(monitor_interval_s * 1000)));
      }
      if (tty) std::printf("\n");
      return kExitOk;
    }
    if (*scene) {
      ff::protocol::ConditionMessage sent;
      if (!set_condition(client, scene_spec, sent, error)) return fail(error);
      std::printf("condition set: %s\n", ff::ffctl::describe(sent).c_str());
      return kExitOk;
    }
    if (*carrier) {
      Message m;
      m.type = MessageType::SetCarrier;
      m.carrier.frequency_hz = static_cast<float>(carrier_hz);
      if (!ff::ffctl::command(client, m, error)) return fail(error);
      std::printf("carrier set to %.1f Hz\n", carrier_hz);
      return kExitOk;
    }
    if (*sweep) {
      Message m;
      m.type = MessageType::StartSweep;
      m.sweep = {static_cast<float>(sweep_start), static_cast<float>(sweep_end), sweep_ms};
      if (!ff::ffctl::command(client, m, error)) return fail(error);
      std::printf("sweeping %.1f .. %.1f Hz over %u ms\n", sweep_start, sweep_end, sweep_ms);
      return kExitOk;
    }
    if (*rec) {
      ff::ffctl::Recording r;
      std::vector<std::string> metadata = {"ffctl " + version + " record " + words_after(argc, argv, "record"),
                                           "date " + ff::host::utc_timestamp(),
                                           "device " + (udp.empty() ? "usb" + (serial.empty() ? "" : " serial " + serial)
                                                                    : "udp " + udp_host + ":" + std::to_string(udp_port))};
      if (scene_words_given(*rec)) {
        if (!set_condition(client, record_spec, r.condition, error)) return fail(error);
        r.has_condition = true;
        std::fprintf(stderr, "condition set: %s\n", ff::ffctl::describe(r.condition).c_str());
        metadata.push_back("condition " + ff::ffctl::describe(r.condition) + " (set by this recording)");
      } else {
        metadata.push_back("condition not set by this recording (whatever the device rendered)");
      }
      Message q;
      q.type = MessageType::QueryStatus;
      if (!client.request(q, reply, error)) return fail(error);
      char fw[64];
      std::snprintf(fw, sizeof fw, "firmware %u.%u protocol %u", reply.status.firmware_version >> 8,
                    reply.status.firmware_version & 0xFF, ff::protocol::kVersion);
      metadata.push_back(fw);
      if (ff::ffctl::query_sensor_profile(client, r.sensor_profile, error)) {
        r.has_sensor_profile = true;
        metadata.push_back("sensor-profile " + ff::host::sensor_profile_flags(r.sensor_profile));
      } else {
        metadata.push_back("sensor-profile unknown (" + error + "): verify assumes the default");
      }
      ff::ffctl::RecordingWriter writer;
      if (!writer.open(record_out, metadata, r, error)) return usage(error);
      const bool live = progress_line || ::isatty(STDERR_FILENO) != 0;
      std::signal(SIGINT, on_interrupt);
      const bool ok = ff::ffctl::record(client, seconds, writer, error, [&](const ff::ffctl::RecordProgress& p) {
        if (live) {
          char force[32] = "-";
          if (p.have_force) std::snprintf(force, sizeof force, "%.0f mN%s", static_cast<double>(p.last_force.force_mN),
                                          p.last_force.over_force ? " OVER" : "");
          std::fprintf(stderr, "\r%6.1f s%s: finger %s, amplitude %.3f (dac %u), force %s, %zu reports, %zu ticks, "
                               "%zu lost\033[K",
                       p.done_s, seconds > 0.0 ? "" : " (Ctrl-C ends)",
                       p.last_tick.present ? "down" : "up", static_cast<double>(p.last_tick.amplitude),
                       static_cast<unsigned>(p.last_tick.dac), force, p.samples, p.ticks, p.lost_ticks);
        }
        return g_interrupted == 0;
      });
      if (live) std::fprintf(stderr, "\n");
      std::string werr;
      if (!writer.close(werr)) return usage(werr + " (what arrived before was kept)");  // an output: exit 2
      std::fprintf(stderr, "wrote %s, %s, %s%s%s\n", record_out.c_str(), ff::ffctl::ticks_path_for(record_out).c_str(),
                   ff::ffctl::force_path_for(record_out).c_str(),
                   r.has_condition ? (", " + ff::ffctl::condition_path_for(record_out)).c_str() : "",
                   r.has_sensor_profile ? (", " + ff::ffctl::sensor_profile_path_for(record_out)).c_str() : "");
      if (client.malformed_replies() > 0) {
        std::fprintf(stderr, "%u malformed frames were skipped\n", client.malformed_replies());
      }
      return ok ? kExitOk : fail(error + " (what arrived was kept)");
    }
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  return kExitOk;
}
