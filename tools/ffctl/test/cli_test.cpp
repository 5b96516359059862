// ffctl as a user runs it: the binary in a subprocess, files on disk, exit
// codes; over UDP against the firmware app (firmware/app on emulated
// devices) behind a real socket on 127.0.0.1 in this process.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <memory>
#include <regex>
#include <sstream>
#include <thread>

#include "device_client.hpp"
#include "hex_record.hpp"
#include "emulated_firmware.hpp"
#include "intel_hex.hpp"
#include "udp_transport.hpp"
#include "support/file_contents.hpp"
#include "support/scratch_path.hpp"

namespace ff::ffctl {
namespace {

// The firmware app behind a UDP socket on 127.0.0.1 (an ephemeral port). One
// thread owns the app: it takes the datagrams that arrived, then runs the
// loop every 100 us and the tick every 500 us of simulated time, paced to
// about real time (never faster), so the tick never runs beside the loop.
class UdpDevice final : public firmware::Board {
 public:
  // finger(t_us): where the finger is at device time t (touch false: lifted).
  explicit UdpDevice(const std::function<SensorSample(uint32_t)>& finger) {
    std::vector<SensorSample> trace;
    for (uint32_t t = 0; t <= 120000000; t += 5000) trace.push_back(finger(t));
    fw_.zforce.load_trace(trace);
    fw_.start(*this);
    socket_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    EXPECT_EQ(::bind(socket_, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
    socklen_t len = sizeof a;
    ::getsockname(socket_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
    thread_ = std::thread([this] { run(); });
  }
  ~UdpDevice() {
    stop_ = true;
    thread_.join();
    ::close(socket_);
  }
  uint16_t port() const { return port_; }

  // Board.
  bool mouse_move_to(int, int) override { return true; }
  bool udp_receive(uint8_t* buffer, size_t capacity, size_t& size, firmware::UdpEndpoint& from) override {
    if (inbox_.empty()) return false;
    const Datagram& d = inbox_.front();
    size = std::min(capacity, d.bytes.size());
    std::copy(d.bytes.begin(), d.bytes.begin() + static_cast<long>(size), buffer);
    from = d.from;
    inbox_.pop_front();
    return true;
  }
  bool udp_send(const firmware::UdpEndpoint& to, const uint8_t* data, size_t size) override {
    if (to.port == 0) return true;  // nobody asked yet
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = to.ip;
    a.sin_port = htons(to.port);
    ::sendto(socket_, data, size, 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
    return true;
  }
  bool hid_receive(uint8_t*) override { return false; }
  void hid_send(const uint8_t*) override {}
  uint32_t cycles() override { return cycles_ += 700; }
  void reboot_to_bootloader() override { ++reboots_; }
  int reboots() const { return reboots_; }

 private:
  struct Datagram {
    std::vector<uint8_t> bytes;
    firmware::UdpEndpoint from;
  };

  void run() {
    const auto start = std::chrono::steady_clock::now();
    while (!stop_) {
      for (;;) {  // whatever arrived
        pollfd p{socket_, POLLIN, 0};
        if (::poll(&p, 1, 0) <= 0) break;
        Datagram d;
        d.bytes.resize(2048);
        sockaddr_in a{};
        socklen_t len = sizeof a;
        const ssize_t n = ::recvfrom(socket_, d.bytes.data(), d.bytes.size(), 0, reinterpret_cast<sockaddr*>(&a), &len);
        if (n < 0) break;
        d.bytes.resize(static_cast<size_t>(n));
        d.from = {a.sin_addr.s_addr, ntohs(a.sin_port)};
        inbox_.push_back(std::move(d));
      }
      for (int i = 0; i < 10; ++i) fw_.step();  // 1 ms of device time
      const auto device = start + std::chrono::microseconds(fw_.now);
      if (device > std::chrono::steady_clock::now()) std::this_thread::sleep_until(device);
    }
  }

  EmulatedFirmware fw_;
  std::deque<Datagram> inbox_;
  int socket_ = -1;
  uint16_t port_ = 0;
  uint32_t cycles_ = 0;
  std::atomic<int> reboots_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Strokes along the middle path: 0.6 s down, 0.2 s lifted, again and again.
SensorSample strokes(uint32_t t) {
  const uint32_t phase = t % 800000;
  return {t, 100.0f + 600.0f * static_cast<float>(phase) / 600000.0f, 240.0f + 40.0f * std::sin(static_cast<float>(t) * 1e-6f),
          phase < 600000};
}

// A finger that never lifts: circles round the middle of the screen.
SensorSample circling(uint32_t t) {
  const float a = static_cast<float>(t) * 1e-6f * 2.0f;
  return {t, 400.0f + 200.0f * std::cos(a), 240.0f + 150.0f * std::sin(a), true};
}

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

// ffctl with these arguments, as a shell runs it.
CliRun ffctl(const std::string& args) {
  static int n = 0;
  const std::string base = support::scratch_path("ffctl_cli_" + std::to_string(n++));
  const std::string cmd = std::string(FFCTL_BINARY) + " " + args + " >" + base + ".out 2>" + base + ".err </dev/null";
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = support::file_contents(base + ".out");
  r.err = support::file_contents(base + ".err");
  return r;
}

std::string udp(const UdpDevice& d) { return "--udp 127.0.0.1:" + std::to_string(d.port()) + " "; }

size_t lines_in(const std::string& path) {
  const std::string text = support::file_contents(path);
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

// ffctl "--udp 127.0.0.1:PORT" + args, run until `ready()` (polled every 20 ms;
// a loaded machine only makes it wait longer, at most 30 s), then sent
// `signal`; stdout to `stdout_path` (not a terminal). Returns the wait status.
template <typename Ready>
int run_then_signal(const UdpDevice& device, std::vector<std::string> args, Ready ready, int signal,
                    const std::string& stdout_path = "/dev/null") {
  args.insert(args.begin(), {FFCTL_BINARY, "--udp", "127.0.0.1:" + std::to_string(device.port())});
  // Everything allocated before fork(): the device's thread may hold the heap's lock.
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const int out = ::open(stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int null = ::open("/dev/null", O_WRONLY);
  const pid_t child = fork();
  if (child == 0) {
    ::dup2(out, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    ::execv(FFCTL_BINARY, argv.data());
    _exit(127);
  }
  ::close(out);
  ::close(null);
  if (child < 0) return -1;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!ready() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ::kill(child, signal);
  int status = 0;
  ::waitpid(child, &status, 0);
  return status;
}

TEST(FfctlCli, BadUsageIsExitTwoBeforeAnyDeviceIsTouched) {
  // No device at all: each of these must be refused by its arguments alone.
  CliRun r = ffctl("--udp 127.0.0.1:9 record -o /nonexistent/dir/x.csv --seconds 1");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("/nonexistent/dir does not exist"), std::string::npos) << r.err;
  r = ffctl("--udp 127.0.0.1:9 record -o " + ::testing::TempDir() + "x.csv --seconds -5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--seconds -5: must be more than 0"), std::string::npos) << r.err;
  r = ffctl("--udp 127.0.0.1:9 record -o " + ::testing::TempDir());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("is a folder"), std::string::npos) << r.err;
  r = ffctl("--udp 127.0.0.1:9 scene");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("which scene?"), std::string::npos) << r.err;
  r = ffctl("--udp 127.0.0.1:9 scene --strength 0.5");  // a strength is not a scene
  EXPECT_EQ(r.exit_code, 2);
  r = ffctl("--udp 127.0.0.1:9 scene --scene no-such-scene");
  EXPECT_EQ(r.exit_code, 2);
  r = ffctl("status --no-such-option");  // CLI11's own parse errors
  EXPECT_EQ(r.exit_code, 2);
  r = ffctl("--udp 127.0.0.1:70000 status");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("1..65535"), std::string::npos) << r.err;
  r = ffctl("verify " + support::scratch_path("no_such_recording.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no_such_recording.csv: cannot open: No such file or directory"), std::string::npos) << r.err;
  // A folder reads as an empty file on Linux: it was "expected a header row" and "no Intel HEX records".
  r = ffctl("verify " + ::testing::TempDir());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(": is a folder, not a file"), std::string::npos) << r.err;
  r = ffctl("flash " + ::testing::TempDir());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(": is a folder, not a file"), std::string::npos) << r.err;
  r = ffctl("flash " + support::scratch_path("no_such_firmware.hex"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no_such_firmware.hex: cannot open: No such file or directory"), std::string::npos) << r.err;
  r = ffctl("--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out.rfind("ffctl ", 0), 0u) << r.out;
  r = ffctl("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("Exit codes: 0 ok; 1 a failed check"), std::string::npos);
  r = ffctl("");  // which command?
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("A subcommand is required"), std::string::npos) << r.err;
  for (const char* bad : {"carrier 0", "carrier -34900", "carrier nan", "carrier inf", "sweep 0 40000 1000",
                          "sweep 30000 -1 1000", "sweep 30000 40000 0", "sweep nan 40000 1000", "sweep 30000 40000"}) {
    r = ffctl(std::string("--udp 127.0.0.1:9 ") + bad);  // nobody on port 9: refused before asking
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_EQ(r.err.find("no reply"), std::string::npos) << bad << ": " << r.err;
  }
  // Scenes the parser takes but the core's preparation refuses: the device
  // would refuse them too, so they are refused before it is asked.
  const std::string vortex_in_heights = support::scratch_path("ffctl_vortex_height_table.scene");
  std::ofstream(vortex_in_heights) << "evaluation table 8 float height\nelement vortex centre 400 240\n";
  const std::string table_too_large = support::scratch_path("ffctl_table_too_large.scene");
  std::ofstream(table_too_large) << "evaluation table 1 float gradient\nelement vortex centre 400 240\n";
  for (const std::string& file : {vortex_in_heights, table_too_large}) {
    r = ffctl("--udp 127.0.0.1:9 scene --scene-file " + file);
    EXPECT_EQ(r.exit_code, 2) << file << ": " << r.err;
    EXPECT_NE(r.err.find("cannot prepare the scene: "), std::string::npos) << file << ": " << r.err;
    EXPECT_EQ(r.err.find("no reply"), std::string::npos) << file << ": " << r.err;
  }
  // The USB commands without a device: list says so (or lists what is there), --serial is an option.
  r = ffctl("--serial 0123456 list");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(r.out.empty());
  r = ffctl("--serial no-such-serial status");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("no frictionfield device with serial number no-such-serial"), std::string::npos) << r.err;
  // Nobody answers on this port: a failed operation, not bad usage.
  r = ffctl("--udp 127.0.0.1:9 status");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no reply"), std::string::npos) << r.err;
}

std::string write_hex(const std::string& name, uint32_t sp, uint32_t reset) {
  // The vector table's first two words as one data record at 0, then EOF.
  std::vector<uint8_t> words;
  for (uint32_t w : {sp, reset}) {
    for (int i = 0; i < 4; ++i) words.push_back(static_cast<uint8_t>(w >> (8 * i)));
  }
  const std::string path = support::scratch_path(name);
  std::ofstream(path) << hex_record(0, 0x00, words) << hex_record(0, 0x01, {});
  return path;
}

TEST(FfctlCli, FlashRefusesAnImageThatIsNotForTheMk66) {
  // A Teensy 3.2 (MK20DX256: RAM 0x1FFF8000..0x20008000) image: its stack
  // starts at 0x20008000, inside the MK66's RAM too, so the reset vector
  // decides: an even one is ARM, not Thumb.
  CliRun r = ffctl("flash " + write_hex("even_reset.hex", 0x20030000u, 0x00000400u));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("reset vector 0x00000400 is not an odd"), std::string::npos) << r.err;
  // A Teensy LC / 4.x style stack pointer (0x20001800 fits; 0x20070000 does not).
  r = ffctl("flash " + write_hex("far_stack.hex", 0x20070000u, 0x000001C1u));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("outside the MK66's RAM"), std::string::npos) << r.err;
  // Code at 0x60000000 (Teensy 4's FlexSPI flash): outside the image.
  r = ffctl("flash " + write_hex("imxrt.hex", 0x20030000u, 0x60001001u));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("reset vector 0x60001001"), std::string::npos) << r.err;
  // --wait changes only how the bootloader is found: the image is checked first all the same.
  r = ffctl("flash --wait " + write_hex("even_reset_wait.hex", 0x20030000u, 0x00000400u));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("reset vector 0x00000400 is not an odd"), std::string::npos) << r.err;
}

TEST(Mk66Image, VectorTableChecksByHand) {
  FlashImage image;
  std::string error;
  const auto put = [&](uint32_t sp, uint32_t reset, size_t highest) {
    for (int i = 0; i < 4; ++i) {
      image.bytes[static_cast<size_t>(i)] = static_cast<uint8_t>(sp >> (8 * i));
      image.bytes[static_cast<size_t>(4 + i)] = static_cast<uint8_t>(reset >> (8 * i));
    }
    image.highest = highest;
  };
  put(0x20030000u, 0x000001BDu, 0x4000);  // Teensyduino 3.6: stack at the top of SRAM_U, ResetHandler in flash
  EXPECT_TRUE(check_mk66_image(image, error)) << error;
  put(0x20030000u, 0x000001BDu, kMk66FlashBytes);  // the whole flash
  EXPECT_TRUE(check_mk66_image(image, error)) << error;
  const auto refused = [&](const char* why) {
    error.clear();
    EXPECT_FALSE(check_mk66_image(image, error));
    EXPECT_NE(error.find(why), std::string::npos) << error;
  };
  put(0x1FFF0000u, 0x000001BDu, 0x4000);  // a stack with no room at all
  refused("initial stack pointer 0x1FFF0000 is outside");
  put(0x20030004u, 0x000001BDu, 0x4000);  // one word past the RAM
  refused("initial stack pointer 0x20030004 is outside");
  put(0x20030000u, 0x000041BDu, 0x4000);  // into flash nobody wrote
  refused("reset vector 0x000041BD is not an odd (Thumb) address inside the image");
  put(0x20030000u, 0x000001BCu, 0x4000);  // even: not Thumb code
  refused("reset vector 0x000001BC is not an odd");
  put(0x20030000u, 0x000001BDu, 4);  // no whole vector table
  refused("no vector table");
  put(0x20030000u, 0x000001BDu, kMk66FlashBytes + 1);  // what no parsed file has, but a caller could
  refused("larger than the MK66's 1 MiB flash");
}

TEST(UdpAddress, HostAndPort) {
  std::string host, error;
  uint16_t port = 0;
  ASSERT_TRUE(parse_udp_address("192.168.1.177", host, port, error));
  EXPECT_EQ(host, "192.168.1.177");
  EXPECT_EQ(port, 8888);
  ASSERT_TRUE(parse_udp_address("localhost:9000", host, port, error));
  EXPECT_EQ(host, "localhost");
  EXPECT_EQ(port, 9000);
  EXPECT_FALSE(parse_udp_address(":9000", host, port, error));
  EXPECT_FALSE(parse_udp_address("h:0", host, port, error));
  EXPECT_FALSE(parse_udp_address("h:x", host, port, error));
  // The device and ff-sim speak IPv4 only: an IPv6 address is refused as one,
  // not read as a host "fe80:" on port 1.
  EXPECT_FALSE(parse_udp_address("fe80::1", host, port, error));
  EXPECT_NE(error.find("IPv4 only"), std::string::npos) << error;
  EXPECT_FALSE(parse_udp_address("[::1]:8888", host, port, error));
  EXPECT_NE(error.find("IPv4 only"), std::string::npos) << error;
}

TEST(FfctlCli, StatusSceneRecordVerifyOverUdp) {
  UdpDevice device(strokes);
  CliRun r = ffctl(udp(device) + "status");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("firmware 1."), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("interrupt (whole, DWT)"), std::string::npos) << r.out;
  // The fault counters and the sensor's: nonzero ones only, each list a line of its own.
  EXPECT_TRUE(std::regex_search(r.out, std::regex("\nfaults: (none|[a-z_]+ [1-9][0-9]*(, [a-z_]+ [1-9][0-9]*)*)\n")))
      << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("\ntouch sensor: running, frames read [1-9][0-9]*(, [a-z ]+ [1-9][0-9]*)*\n")))
      << r.out;
  r = ffctl(udp(device) + "scene --scene frictionmap --target bottom --strength 0.33");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("condition set: frictionmap, target bottom, strength 0.33"), std::string::npos) << r.out;
  r = ffctl(udp(device) + "status");
  EXPECT_NE(r.out.find("condition: frictionmap, target bottom, strength 0.33"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("device: conditions_set 1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("touch sensor: running, frames read "), std::string::npos) << r.out;
  r = ffctl(udp(device) + "carrier 35000");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("carrier set to 35000.0 Hz"), std::string::npos) << r.out;
  r = ffctl(udp(device) + "status");
  const size_t at = r.out.find("carrier ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_NEAR(std::atof(r.out.c_str() + at + 8), 35000.0, 1.0) << r.out;  // the AD9834's 28-bit tuning word
  r = ffctl(udp(device) + "carrier 5000000");  // beyond the AD9834's range: the device refuses
  EXPECT_EQ(r.exit_code, 1) << r.out;

  const std::string path = support::scratch_path("udp_rec.csv");
  r = ffctl(udp(device) + "record -o " + path + " --seconds 2 --scene heightmap --target top --strength 0.66");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Recording rec;
  std::string error;
  ASSERT_TRUE(read_recording(path, rec, error)) << error;
  EXPECT_NEAR(static_cast<double>(rec.ticks.size()), 4000.0, 100.0);
  EXPECT_GT(rec.samples.size(), 200u);
  // Metadata: readers skip it; the tool, the words, the firmware and the date are there.
  const std::string trace = support::file_contents(path);
  EXPECT_EQ(trace.rfind("# ffctl ", 0), 0u);
  EXPECT_NE(trace.find("record -o " + path + " --seconds 2 --scene heightmap"), std::string::npos);
  EXPECT_NE(trace.find("# firmware 1."), std::string::npos);
  const size_t condition_line = trace.find("# condition heightmap, target top, strength 0.66,");
  ASSERT_NE(condition_line, std::string::npos);
  EXPECT_EQ(trace.find("(set by this recording)\n", condition_line), trace.find('\n', condition_line) - 23);
  EXPECT_NE(r.err.find("condition set: heightmap, target top, strength 0.66,"), std::string::npos) << r.err;
  EXPECT_NE(trace.find("# date 20"), std::string::npos);
  // By now the finger has come and gone: both counted, on the faults line.
  r = ffctl(udp(device) + "status");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::smatch faults;
  ASSERT_TRUE(std::regex_search(r.out, faults, std::regex("\nfaults: ([a-z_]+ [1-9][0-9]*(, [a-z_]+ [1-9][0-9]*)*)\n")))
      << r.out;
  EXPECT_NE(faults[1].str().find("touch_down "), std::string::npos) << r.out;
  EXPECT_NE(faults[1].str().find("lift_off "), std::string::npos) << r.out;
  // Force every 30 ms: ~66 in 2 s.
  const std::string force = support::file_contents(force_path_for(path));
  EXPECT_NE(force.find("t_us,force_mN,over_force\n"), std::string::npos);
  EXPECT_GT(std::count(force.begin(), force.end(), '\n'), 50);

  // The stream may start in the middle of a 0.6 s stroke: up to 0.6 s of the
  // 2 s are warm-up, not compared, so the coverage is at least ~70 %.
  r = ffctl("verify " + path + " --min-coverage 60");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("PASS"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("of " + std::to_string(rec.ticks.size()) + " recorded ticks (coverage "), std::string::npos) << r.out;
  r = ffctl("verify " + path + " --min-coverage 60 --scene heightmap --target top --strength 0.66");
  EXPECT_EQ(r.exit_code, 0) << r.out;  // the same condition given as words
  EXPECT_NE(r.out.find("PASS"), std::string::npos) << r.out;
  // Without its sensor-profile file verify takes the default profile, the one this device used, and says so.
  ASSERT_EQ(std::remove(sensor_profile_path_for(path).c_str()), 0);
  r = ffctl("verify " + path + " --min-coverage 60");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("sensor profile: the default (no " + sensor_profile_path_for(path) + ")"), std::string::npos)
      << r.out;
  r = ffctl("verify " + path + " --scene heightmap --target bottom --strength 0.66");
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("FAIL"), std::string::npos) << r.out;
}

TEST(FfctlCli, SweepAndRebootOverUdp) {
  UdpDevice device(strokes);
  CliRun r = ffctl(udp(device) + "sweep 30000 40000 2000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("sweeping 30000.0 .. 40000.0 Hz over 2000 ms"), std::string::npos) << r.out;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  r = ffctl(udp(device) + "status");
  const size_t at = r.out.find("carrier ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const double hz = std::atof(r.out.c_str() + at + 8);
  EXPECT_GT(hz, 30000.0) << r.out;  // under way: past its start, short of its end
  EXPECT_LT(hz, 40000.0) << r.out;
  r = ffctl(udp(device) + "sweep 30000 5000000 1000");  // beyond the AD9834's range
  EXPECT_EQ(r.exit_code, 1) << r.out;
  // Over UDP the device's acknowledgement is all there is to wait for (this one stays up).
  r = ffctl(udp(device) + "reboot");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("the device acknowledged: it rests the plate"), std::string::npos) << r.out;
  for (int i = 0; i < 100 && device.reboots() == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(device.reboots(), 1);  // asked once (it replies first, then restarts)
}

TEST(FfctlCli, TheRecordersLiveLineOnlyWhereItIsWanted) {
  UdpDevice device(strokes);
  const std::string path = support::scratch_path("udp_progress.csv");
  // stderr is a file here: no live line unless --progress asks for it.
  CliRun r = ffctl(udp(device) + "record -o " + path + " --seconds 0.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("wrote " + path), std::string::npos) << r.err;
  r = ffctl(udp(device) + "record -o " + path + " --seconds 0.5 --progress");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("\r"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" ticks, "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" lost\033[K\nwrote " + path), std::string::npos) << r.err;  // the summary on a line of its own
}

TEST(FfctlCli, SensorProfileIsSentReadBackShownAndKeptByARecording) {
  UdpDevice device(strokes);
  const std::string flags =
      "--white-noise-px 1.5 --correlated-noise-px 0.5 --correlation-time-ms 250 --tremor-px 0.25 "
      "--tremor-hz 9.5 --report-rate-hz 180 --jitter-us 400 --latency-us 3000";
  const std::string words = "white noise 1.5 px, wander 0.5 px over 250 ms, tremor 0.25 px at 9.5 Hz, 180 reports/s "
                            "+- 400 us, latency 3000 us";
  CliRun r = ffctl(udp(device) + "sensor-profile --show");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("white noise 1 px, wander 0 px over 0 ms, tremor 0 px, 200 reports/s +- 150 us, latency 0 us"),
            std::string::npos) << r.out;  // the default profile since power-on
  r = ffctl(udp(device) + "sensor-profile " + flags);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("the device's tracker uses: " + words), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ffctl sensor-profile " + flags), std::string::npos) << r.out;  // what --calibrate prints
  r = ffctl(udp(device) + "status");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("sensor profile: " + words), std::string::npos) << r.out;

  // Bad usage, before the device is touched: the profile stays.
  for (const char* bad : {"sensor-profile", "sensor-profile --show --default", "sensor-profile --show --tremor-px 1",
                          "sensor-profile --correlated-noise-px 2", "sensor-profile --report-rate-hz 5",
                          "sensor-profile --latency-us 50001", "sensor-profile --white-noise-px nan",
                          "sensor-profile --tremor-hz 2", "sensor-profile --tremor-hz 25"}) {
    r = ffctl(udp(device) + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.out << r.err;
  }
  r = ffctl(udp(device) + "sensor-profile --show");
  EXPECT_NE(r.out.find(words), std::string::npos) << r.out;

  // A recording keeps it; verify replays with it.
  const std::string path = support::scratch_path("udp_profile_rec.csv");
  r = ffctl(udp(device) + "record -o " + path + " --seconds 1 --scene heightmap --target top --strength 0.66");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(support::file_contents(path).find("# sensor-profile " + flags + "\n"), std::string::npos);
  Recording rec;
  std::string error;
  ASSERT_TRUE(read_recording(path, rec, error)) << error;
  ASSERT_TRUE(rec.has_sensor_profile);
  EXPECT_EQ(rec.sensor_profile.report_rate_hz, 180.0f);
  EXPECT_EQ(rec.sensor_profile.latency_us, 3000u);
  EXPECT_EQ(tracker_config_of(rec).sensor.jitter_us, 400.0f);
  r = ffctl("verify " + path + " --min-coverage 0");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("sensor profile (" + sensor_profile_path_for(path) + "): " + words), std::string::npos) << r.out;

  r = ffctl(udp(device) + "sensor-profile --default");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("white noise 1 px, wander 0 px over 0 ms"), std::string::npos) << r.out;
}

TEST(FfctlCli, VerifyFailsAnotherSceneWhenTheFingerNeverLifts) {
  UdpDevice device(circling);
  const std::string path = support::scratch_path("udp_never_lifts.csv");
  CliRun r = ffctl(udp(device) + "record -o " + path + " --seconds 1.5 --scene heightmap --target top --strength 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* other : {"--scene heightmap --target bottom --strength 1", "--scene frictionmap --target top",
                            "--scene heightmap --target top --strength 0.33"}) {
    r = ffctl("verify " + path + " " + other);
    EXPECT_EQ(r.exit_code, 1) << other << "\n" << r.out;
    EXPECT_NE(r.out.find("FAIL"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\n  the finger never left the plate: compared from the first tick"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\n    first at "), std::string::npos) << r.out;  // where each run starts
  }
}

TEST(FfctlCli, MonitorPrintsALinePerChangeAndCtrlCEndsItWithZero) {
  UdpDevice device(strokes);
  const std::string out = support::scratch_path("monitor.out");
  // The finger comes and goes every 0.8 s: stopped after the first line and two changes.
  // Each line reaches the file as it comes (flushed), whole: not a buffer's worth at a time.
  std::string first_seen;
  const auto two_changes = [&] {
    const std::string text = support::file_contents(out);
    if (std::count(text.begin(), text.end(), '\n') < 3) return false;
    first_seen = text;
    return true;
  };
  const int status = run_then_signal(device, {"monitor", "--interval", "0.05"}, two_changes, SIGINT, out);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  ASSERT_FALSE(first_seen.empty());
  EXPECT_EQ(first_seen.back(), '\n') << first_seen;
  EXPECT_LE(std::count(first_seen.begin(), first_seen.end(), '\n'), 6) << first_seen;  // ~0.4 s apart, polled every 20 ms
  const std::string text = support::file_contents(out);
  const auto lines = std::count(text.begin(), text.end(), '\n');
  EXPECT_GE(lines, 3) << text;
  EXPECT_LT(lines, 30) << text;  // not every 50 ms query: only changes
  // Each line differs from the one before in what counts as a change (from "finger" on).
  std::istringstream in(text);
  std::string line, previous;
  while (std::getline(in, line)) {
    const size_t at = line.find("finger ");
    ASSERT_NE(at, std::string::npos) << line;
    EXPECT_NE(line.substr(at), previous) << text;
    previous = line.substr(at);
    // Counters that are not 0 only; "none" when no fault was counted.
    // Any of the sensor's states (a loaded machine may catch it configuring), and an over-force when there is one.
    EXPECT_TRUE(std::regex_search(previous, std::regex("^finger (up|down)(, OVER-FORCE)?, protocol errors [0-9]+, "
                                                       "watchdog trips [0-9]+, stream overruns [0-9]+, faults "
                                                       "(none|[a-z_]+=[1-9][0-9]*( [a-z_]+=[1-9][0-9]*)*), "
                                                       "sensor (booting|configuring|running|failed)( [a-z_ ]+=[1-9][0-9]*)*$")))
        << line;
  }
  EXPECT_NE(text.find("finger down"), std::string::npos) << text;
  EXPECT_NE(text.find("finger up"), std::string::npos) << text;
  EXPECT_NE(text.find(", sensor running"), std::string::npos) << text;
  EXPECT_EQ(text.find("frames read"), std::string::npos) << text;  // what moves all the time is no change
  EXPECT_EQ(text.find('\r'), std::string::npos);  // no refreshing line into a file
}

TEST(FfctlCli, CtrlCEndsARecordingCleanly) {
  UdpDevice device(strokes);
  const std::string path = support::scratch_path("udp_ctrl_c.csv");  // a fresh folder: no stale ticks file
  const auto half_a_second = [&] { return lines_in(ticks_path_for(path)) > 1100; };  // 2 kHz ticks
  const int status = run_then_signal(device, {"record", "-o", path}, half_a_second, SIGINT);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  Recording rec;
  std::string error;
  ASSERT_TRUE(read_recording(path, rec, error)) << error;
  EXPECT_GT(rec.ticks.size(), 500u);
  EXPECT_FALSE(rec.has_condition);  // no scene words: none set, none claimed
  EXPECT_NE(support::file_contents(path).find("# condition not set by this recording"), std::string::npos);
}

TEST(FfctlCli, AKilledRecorderLeavesValidFiles) {
  UdpDevice device(strokes);
  const std::string path = support::scratch_path("udp_killed.csv");
  const auto a_second = [&] { return lines_in(ticks_path_for(path)) > 2100; };  // 2 kHz ticks, as flushed
  const int status = run_then_signal(device, {"record", "-o", path, "--scene", "heightmap"}, a_second, SIGKILL);
  EXPECT_TRUE(WIFSIGNALED(status));
  // Every line whole, every file readable: about the second before the kill is there.
  for (const std::string& p : {path, ticks_path_for(path), force_path_for(path)}) {
    const std::string text = support::file_contents(p);
    ASSERT_FALSE(text.empty()) << p;
    EXPECT_EQ(text.back(), '\n') << p;
  }
  Recording rec;
  std::string error;
  ASSERT_TRUE(read_recording(path, rec, error)) << error;
  EXPECT_GT(rec.ticks.size(), 1000u);  // > 0.5 s of 2 kHz (the kill came after a second was on disk)
  EXPECT_GT(rec.samples.size(), 10u);
  EXPECT_TRUE(rec.has_condition);  // written when it was set, not at the end
}

}  // namespace
}  // namespace ff::ffctl
