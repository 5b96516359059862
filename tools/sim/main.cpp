// ff-sim: the Teensy firmware on a laptop. firmware/src/main.cpp, unchanged,
// runs on the Teensyduino model (test/teensy_model) with the emulated zForce,
// AD9834, DAC and load cells, and speaks the real protocol on UDP.
//
// The pipeline hands a new scene over by preparing the slot the tick is not
// reading and publishing it with one store. That is safe on the Teensy only
// because the tick is an interrupt that runs to completion on the one core,
// between two instructions of the main loop. ff-sim keeps exactly that: one
// thread, simulated time, and the tick run to completion inside whichever
// Teensyduino call its time falls in (never a second thread, which would let
// a tick read a slot the loop is rewriting).
#include <CLI/CLI.hpp>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <string>
#include <thread>

#include "frictionfield/host/cli_conventions.hpp"
#include "frictionfield/host/trace_csv.hpp"
#include "live_finger.hpp"
#include "sim_devices.hpp"
#include "socket_network.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

// A finger sliding left and right along the middle path at 300 px/s, pressing 0.3 N.
ff::sim::FingerState scripted_stroke(uint64_t t_us) {
  const double phase = std::fmod(static_cast<double>(t_us) * 1e-6 * 300.0, 1200.0);
  const double x = 100.0 + (phase < 600.0 ? phase : 1200.0 - phase);
  return {true, static_cast<float>(x), 240.0f, 0.3f};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ff-sim: the frictionfield firmware, unchanged, on this computer: the Teensy binding on a model of\n"
      "Teensyduino with an emulated zForce, AD9834, DAC and load cells. It speaks the device's protocol\n"
      "on UDP (docs/protocol.md), so ffctl --udp and the experiment program use it as they use a Teensy.\n\n"
      "The finger comes from a trace file (--trace), a scripted stroke (--stroke), or datagrams on the\n"
      "finger port: 'x y force_N' (down at pixel x,y of the 800x480 screen, y down) or 'up'.\n\n"
      "Examples:\n"
      "  ff-sim                               # wait for finger datagrams on 127.0.0.1:8889\n"
      "  ff-sim --trace test/traces/gen_across_high_px.csv\n"
      "  ffctl --udp 127.0.0.1 status\n\n"
      "Exit codes: 0 stopped by a signal, 2 bad usage or input."};
  uint16_t port = 8888, finger_port = 8889;
  double speed = 1.0;
  std::string trace_path;
  bool stroke = false, quiet = false;
  float trace_force_N = 0.3f;
  app.add_option("--port", port, "UDP port of the device's protocol (127.0.0.1; 0: any free port)")->capture_default_str();
  app.add_option("--finger-port", finger_port, "UDP port for finger datagrams (0: any free port)")->capture_default_str();
  app.add_option("--speed", speed, "simulated time runs this many times faster than the wall clock")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  auto* trace_opt = app.add_option("--trace", trace_path,
                                   "finger trace CSV (t_us,x,y,touch) on its own clock: a report stamped t_us\n"
                                   "arrives t_us after the ready line");
  app.add_flag("--stroke", stroke, "a scripted finger sliding along the middle path")->excludes(trace_opt);
  app.add_option("--trace-force", trace_force_N, "force on the plate while the trace touches, N")->capture_default_str();
  app.add_flag("-q,--quiet", quiet, "no live status line");
  if (const int code = ff::host::parse_command_line(app, argc, argv); code >= 0) return code;

  std::vector<ff::host::TraceRow> rows;
  if (!trace_path.empty()) {
    ff::host::TraceError error;
    if (!ff::host::read_sensor_trace_file(trace_path, rows, error)) {
      std::fprintf(stderr, "ff-sim: %s\n", error.to_string(trace_path).c_str());
      return 2;
    }
  }

  teensy_model::Options options;
  options.keep_dac_history = false;
  teensy_model::reset(options);
  ff::sim::SocketNetwork network;
  std::string error;
  if (!network.open(port, error)) {
    std::fprintf(stderr, "ff-sim: %s\n", error.c_str());
    return 2;
  }
  uint16_t bound_finger_port = 0;
  const int finger_fd = ff::sim::open_udp(finger_port, bound_finger_port, error);
  if (finger_fd < 0) {
    std::fprintf(stderr, "ff-sim: finger port: %s\n", error.c_str());
    return 2;
  }
  teensy_model::SimDevices devices;
  devices.wire(network);

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  // Start-up, setup() and the load cells' tare (5 readings, 30 ms apart, no finger) as fast as the
  // host runs them: ~1.1 s of simulated time in a few milliseconds.
  teensy_model::boot();
  teensy_model::run_until(teensy_model::now_us() + 200000);
  const uint64_t t0 = teensy_model::now_us();
  std::vector<ff::SensorSample> trace;
  if (!rows.empty()) {
    // The trace keeps its own clock: a report stamped t_us arrives t_us after ff-sim is ready
    // (a recorder started at once sees the plate at rest before the finger lands).
    for (const auto& r : rows) trace.push_back({static_cast<uint32_t>(t0 + r.t_us), r.x, r.y, r.touch});
    devices.zforce.load_trace(trace);
  }
  // The trace's finger presses the plate from a touching report to the next lifted one; before
  // its first report and after its last it is away.
  size_t next_report = 0;
  bool trace_touching = false;

  // From here simulated time follows the wall clock (times --speed).
  using clock = std::chrono::steady_clock;
  const auto wall0 = clock::now();
  uint64_t paced_until = t0;
  teensy_model::set_pacer([&](uint64_t now) {
    if (now < paced_until + 1000) return;  // check the wall clock once per simulated millisecond
    paced_until = now;
    const auto due = wall0 + std::chrono::microseconds(static_cast<int64_t>((now - t0) / speed));
    std::this_thread::sleep_until(due);
  });
  std::printf("ff-sim ready port=%u finger-port=%u\n", network.port(), bound_finger_port);
  std::fflush(stdout);

  ff::sim::LiveFinger finger;
  const bool live_line = !quiet && isatty(STDERR_FILENO);
  auto next_line = clock::now();
  while (!g_stop && !teensy_model::rebooted()) {
    char buf[256];
    ssize_t n;
    while ((n = ::recv(finger_fd, buf, sizeof buf - 1, 0)) > 0) {
      ff::sim::FingerState f;
      std::string message;
      if (ff::sim::parse_finger_datagram(std::string(buf, static_cast<size_t>(n)), f, message)) {
        finger.set(f);
      } else if (!quiet) {
        std::fprintf(stderr, "ff-sim: %s\n", message.c_str());
      }
    }
    const uint64_t now = teensy_model::now_us();
    if (stroke) finger.set(scripted_stroke(now - t0));
    if (rows.empty()) {
      finger.step(now, devices.zforce);
      devices.set_force_mN(finger.state().down ? finger.state().force_N * 1000.0f : 0.0f);
    } else {
      for (; next_report < trace.size() && trace[next_report].t_us <= now; ++next_report)
        trace_touching = trace[next_report].touch;
      if (next_report == trace.size()) trace_touching = false;
      devices.set_force_mN(trace_touching ? trace_force_N * 1000.0f : 0.0f);
    }
    teensy_model::run_until(now + 1000);
    if (live_line && clock::now() >= next_line) {
      next_line = clock::now() + std::chrono::milliseconds(200);
      const teensy_model::DacState d = teensy_model::dac_now();
      const ff::sim::FingerState& f = finger.state();
      std::fprintf(stderr, "\r t %8.2f s  finger %-16s dac %4u (amplitude %.2f if linear)  force %.2f N   ",
                   static_cast<double>(now - t0) * 1e-6,
                   f.down ? (std::to_string(static_cast<int>(f.x)) + "," + std::to_string(static_cast<int>(f.y))).c_str()
                          : "up",
                   d.code, d.code / 4095.0, static_cast<double>(f.force_N));
    }
  }
  if (live_line) std::fprintf(stderr, "\n");
  ::close(finger_fd);
  return 0;
}
