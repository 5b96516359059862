// ff-sim as a user runs it: started as a program, spoken to over UDP on
// 127.0.0.1 with the real protocol, a finger sent as datagrams.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "frictionfield/protocol/codec.hpp"
#include "support/scratch_path.hpp"

namespace {

using ff::protocol::Message;
using ff::protocol::MessageType;

struct Sim {
  // `args` may end in a redirection of stderr; -q (no live line, no datagram complaints) unless
  // `quiet` is false.
  explicit Sim(const std::string& args, bool quiet = true) {
    int out[2];
    EXPECT_EQ(pipe(out), 0);
    started = std::chrono::steady_clock::now();
    pid = fork();
    if (pid == 0) {
      dup2(out[1], STDOUT_FILENO);
      close(out[0]);
      const std::string cmd = std::string(FF_SIM_BINARY) + " --port 0 --finger-port 0 " + (quiet ? "-q " : "") + args;
      execl("/bin/sh", "sh", "-c", ("exec " + cmd).c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    close(out[1]);
    FILE* f = fdopen(out[0], "r");
    char line[200] = {};
    if (fgets(line, sizeof line, f) != nullptr) {
      ready_after = std::chrono::steady_clock::now() - started;
      std::sscanf(line, "ff-sim ready port=%hu finger-port=%hu", &port, &finger_port);
    }
    fclose(f);
    fd = socket(AF_INET, SOCK_DGRAM, 0);
    timeval tv{0, 200000};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  }
  ~Sim() {
    if (pid > 0) stop(SIGTERM);
    close(fd);
  }
  // Sends `signal` and waits: the exit code, or -1 if the signal killed it.
  int stop(int signal) {
    kill(pid, signal);
    int status = 0;
    waitpid(pid, &status, 0);
    pid = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  void send_to(uint16_t p, const void* data, size_t n) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(p);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    sendto(fd, data, n, 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
  }
  void send(const Message& m) {
    uint8_t frame[ff::protocol::kMaxFrame];
    send_to(port, frame, ff::protocol::encode(m, frame, sizeof frame));
  }
  void finger(const std::string& text) { send_to(finger_port, text.data(), text.size()); }
  // Replies of one type within a deadline (others are collected on the way).
  bool wait_for(MessageType type, Message& out, int ms = 2000) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
    while (std::chrono::steady_clock::now() < end) {
      uint8_t buf[2048];
      const ssize_t n = recv(fd, buf, sizeof buf, 0);
      if (n <= 0) continue;
      Message m;
      if (ff::protocol::decode(buf, static_cast<size_t>(n), m) != ff::protocol::DecodeStatus::Ok) continue;
      seen.push_back(m);
      if (m.type == type) {
        out = m;
        return true;
      }
    }
    return false;
  }
  Message status() {
    Message q, st;
    q.type = MessageType::QueryStatus;
    send(q);
    EXPECT_TRUE(wait_for(MessageType::Status, st));
    return st;
  }

  pid_t pid = -1;
  int fd = -1;
  uint16_t port = 0, finger_port = 0;
  std::chrono::steady_clock::time_point started;
  std::chrono::steady_clock::duration ready_after{};
  std::vector<Message> seen;
};

TEST(FfSim, StartsInUnderASecondAndAnswersStatus) {
  Sim sim("");
  ASSERT_NE(sim.port, 0) << "no ready line";
  EXPECT_LT(std::chrono::duration<double>(sim.ready_after).count(), 1.0);
  const Message st = sim.status();
  EXPECT_EQ(st.status.firmware_version, 0x0101);  // 1.1, the firmware unchanged
  EXPECT_FALSE(st.status.finger_present);
  EXPECT_EQ(st.status.sensor_state, ff::protocol::SensorState::Running);  // the emulated zForce configured
}

// The local address Linux lists for a UDP port (/proc/net/udp: hex, 0100007F is 127.0.0.1).
std::string udp_local_address(uint16_t port) {
  FILE* f = std::fopen("/proc/net/udp", "r");
  if (f == nullptr) return "";
  char line[512];
  char suffix[8];
  std::snprintf(suffix, sizeof suffix, ":%04X", port);
  std::string found;
  while (std::fgets(line, sizeof line, f) != nullptr) {
    char local[64] = {};
    if (std::sscanf(line, " %*[0-9]: %63s", local) == 1 && std::string(local).size() > 5 &&
        std::string(local).compare(std::string(local).size() - 5, 5, suffix) == 0)
      found = local;
  }
  std::fclose(f);
  return found;
}

TEST(FfSim, ListensOnLoopbackOnly) {
  // A laboratory's laptop on a network: only this computer may set the device's condition.
  Sim sim("");
  ASSERT_NE(sim.port, 0);
  char expected[16];
  std::snprintf(expected, sizeof expected, "0100007F:%04X", sim.port);
  EXPECT_EQ(udp_local_address(sim.port), expected);
  std::snprintf(expected, sizeof expected, "0100007F:%04X", sim.finger_port);
  EXPECT_EQ(udp_local_address(sim.finger_port), expected);
}

TEST(FfSim, CtrlCOrSigtermStopsItWithExitCode0) {
  for (const int signal : {SIGINT, SIGTERM}) {
    Sim sim("");
    ASSERT_NE(sim.port, 0);
    sim.status();  // running, not still starting
    EXPECT_EQ(sim.stop(signal), 0) << "signal " << signal;
  }
}

TEST(FfSim, AFingerFromDatagramsRendersTheSceneAndPressesTheLoadCells) {
  Sim sim("");
  ASSERT_NE(sim.port, 0);
  Message set, ack;
  set.type = MessageType::SetCondition;
  set.sequence = 3;
  set.condition.kind = ff::protocol::ConditionKind::Heightmap;
  sim.send(set);
  ASSERT_TRUE(sim.wait_for(MessageType::Ack, ack));
  EXPECT_EQ(ack.sequence, 3);
  EXPECT_EQ(ack.ack.status, ff::protocol::AckStatus::Ok);
  Message start;
  start.type = MessageType::StartStream;
  start.stream.tick_decimation = 10;
  sim.send(start);
  // Slide right along the middle path, pressing 0.4 N, for 0.6 s.
  for (int i = 0; i < 60; ++i) {
    sim.finger(std::to_string(200 + 5 * i) + " 240 0.4");
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  Message ticks, force;
  ASSERT_TRUE(sim.wait_for(MessageType::Ticks, ticks));
  ASSERT_TRUE(sim.wait_for(MessageType::Force, force));
  const Message st = sim.status();
  EXPECT_TRUE(st.status.finger_present);
  // Whole ADC counts per cell: 400 mN / (4 x 10.508) = 9.5 -> 10 counts each: 420.3 mN.
  EXPECT_NEAR(st.status.force_mN, 420.34f, 0.5f);
  bool rendered = false;
  for (const Message& m : sim.seen) {
    if (m.type != MessageType::Ticks) continue;
    for (int i = 0; i < m.ticks.count; ++i) rendered = rendered || (m.ticks.ticks[i].present && m.ticks.ticks[i].dac > 0);
  }
  EXPECT_TRUE(rendered) << "streamed ticks over UDP with the finger down";
  sim.finger("up");
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(sim.status().status.finger_present);
}

TEST(FfSim, AScriptedStrokeTouchesAndPresses) {
  Sim sim("--stroke");
  ASSERT_NE(sim.port, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(400));  // the 5-reading force average settled
  const Message st = sim.status();
  EXPECT_TRUE(st.status.finger_present);
  // 0.3 N in whole ADC counts per cell: 300 mN / (4 x 10.508) = 7.14 -> 7 counts each: 294.2 mN.
  EXPECT_NEAR(st.status.force_mN, 294.22f, 0.5f);
}

TEST(FfSim, ABadFingerDatagramIsNamedOnStderrUnlessQuiet) {
  for (const bool quiet : {false, true}) {
    const std::string log = ff::support::scratch_path("sim_datagram.log");
    std::remove(log.c_str());
    {
      Sim sim("2>" + log, quiet);
      ASSERT_NE(sim.port, 0);
      sim.finger("12 abc");
      sim.status();  // the datagram has been read by then: one pass of the loop reads both ports
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    std::string text;
    if (FILE* f = std::fopen(log.c_str(), "r")) {
      char buf[256];
      while (std::fgets(buf, sizeof buf, f) != nullptr) text += buf;
      std::fclose(f);
    }
    const std::string message = "ff-sim: finger datagram '12 abc': expected 'x y force_N' or 'up'\n";
    if (quiet)
      EXPECT_EQ(text, "");
    else
      EXPECT_NE(text.find(message), std::string::npos) << text;
    std::remove(log.c_str());
  }
}

TEST(FfSim, ATracesFingerPressesTheLoadCellsOnlyWhileItTouches) {
  // Half-second phases: away (no reports yet), down sliding right, lifted, down again to the
  // trace's last report, then nothing. The sensor has frames to deliver from the start to 2 s, but
  // the plate is pressed only while the trace touches, and not after its last report. The firmware averages 5 load-cell readings 30 ms apart
  // (150 ms to settle), so each check comes 350 ms after a change and 150 ms before the next:
  // ff-sim may fall 200 ms behind the wall clock on a loaded machine and still pass.
  const std::string path = ff::support::scratch_path("sim_force_trace.csv");
  {
    FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fprintf(f, "t_us,x,y,touch\n");
    for (int t_ms = 500; t_ms < 2000; t_ms += 5) {
      const bool down = t_ms < 1000 || t_ms >= 1500;
      std::fprintf(f, "%d,%d,240,%d\n", t_ms * 1000, 200 + (t_ms - 500) / 10, down ? 1 : 0);
    }
    std::fclose(f);
  }
  Sim sim("--trace " + path + " --trace-force 0.5");
  ASSERT_NE(sim.port, 0);
  auto at_ms = [&sim](int ms) { std::this_thread::sleep_until(sim.started + sim.ready_after + std::chrono::milliseconds(ms)); };
  // --trace-force 0.5 in whole ADC counts per cell: 500 mN / (4 x 10.508) = 11.9 -> 12 counts
  // each: 504.4 mN.
  const float pressed_mN = 504.38f;
  at_ms(350);
  EXPECT_LT(sim.status().status.force_mN, 50.0f) << "before the trace's first report";
  at_ms(850);
  const Message down = sim.status();
  EXPECT_TRUE(down.status.finger_present);
  EXPECT_NEAR(down.status.force_mN, pressed_mN, 0.5f);
  at_ms(1350);
  const Message lifted = sim.status();
  EXPECT_FALSE(lifted.status.finger_present);
  EXPECT_LT(lifted.status.force_mN, 50.0f) << "lifted between two strokes";
  at_ms(1850);
  EXPECT_NEAR(sim.status().status.force_mN, pressed_mN, 0.5f) << "down again";
  at_ms(2350);
  EXPECT_LT(sim.status().status.force_mN, 50.0f) << "after the trace's last report";
  std::remove(path.c_str());
}

// What `ff-sim ARGS` prints on stderr, and its exit code.
int run_sim(const std::string& args, std::string& stderr_text) {
  FILE* p = popen((std::string(FF_SIM_BINARY) + " " + args + " 2>&1 >/dev/null").c_str(), "r");
  if (p == nullptr) return -1;
  char buf[512];
  stderr_text.clear();
  while (std::fgets(buf, sizeof buf, p) != nullptr) stderr_text += buf;
  const int rc = pclose(p);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

TEST(FfSim, RefusesABadTraceWithExitCode2) {
  std::string err;
  EXPECT_EQ(run_sim("--trace /nonexistent.csv -q", err), 2);
  EXPECT_EQ(err.rfind("ff-sim: /nonexistent.csv: cannot open: No such file or directory", 0), 0u) << err;
  EXPECT_EQ(run_sim("--trace / -q", err), 2);  // a folder: not "an empty file"
  EXPECT_EQ(err.rfind("ff-sim: /: is a folder, not a file", 0), 0u) << err;
}

TEST(FfSim, BadUsageExitsWith2AndHelpWith0) {
  std::string err;
  EXPECT_EQ(run_sim("--bogus", err), 2);
  EXPECT_EQ(run_sim("--speed 0", err), 2);  // outside 0.01-1000
  EXPECT_NE(err.find("--speed"), std::string::npos) << err;
  EXPECT_EQ(run_sim("--stroke --trace /dev/null", err), 2);  // one finger at a time
  EXPECT_NE(err.find("excludes"), std::string::npos) << err;
  EXPECT_EQ(run_sim("--help", err), 0);
}

TEST(FfSim, APortInUseIsNamedWithExitCode2) {
  // A socket of this test holds a port; ff-sim asked for it, as either port, says so.
  const int held = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(bind(held, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  socklen_t len = sizeof a;
  ASSERT_EQ(getsockname(held, reinterpret_cast<sockaddr*>(&a), &len), 0);
  const std::string port = std::to_string(ntohs(a.sin_port));
  std::string err;
  EXPECT_EQ(run_sim("--port " + port + " --finger-port 0 -q", err), 2);
  EXPECT_EQ(err.rfind("ff-sim: cannot listen on 127.0.0.1:" + port + ": ", 0), 0u) << err;
  EXPECT_EQ(run_sim("--port 0 --finger-port " + port + " -q", err), 2);
  EXPECT_EQ(err.rfind("ff-sim: finger port: cannot listen on 127.0.0.1:" + port + ": ", 0), 0u) << err;
  close(held);
}

}  // namespace
