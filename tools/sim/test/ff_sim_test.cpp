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

namespace {

using ff::protocol::Message;
using ff::protocol::MessageType;

struct Sim {
  explicit Sim(const std::string& args) {
    int out[2];
    EXPECT_EQ(pipe(out), 0);
    started = std::chrono::steady_clock::now();
    pid = fork();
    if (pid == 0) {
      dup2(out[1], STDOUT_FILENO);
      close(out[0]);
      const std::string cmd = std::string(FF_SIM_BINARY) + " --port 0 --finger-port 0 -q " + args;
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
    kill(pid, SIGTERM);
    int status = 0;
    waitpid(pid, &status, 0);
    close(fd);
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

TEST(FfSim, ATracesFingerPressesTheLoadCellsOnlyWhileItTouches) {
  // Half-second phases: away (no reports yet), down sliding right, lifted, down again, lifted
  // reports to the end. The sensor has frames to deliver from the start to 2 s, but the plate is
  // pressed only while the trace touches. The firmware averages 5 load-cell readings 30 ms apart
  // (150 ms to settle), so each check comes 350 ms after a change and 150 ms before the next:
  // ff-sim may fall 200 ms behind the wall clock on a loaded machine and still pass.
  const std::string path = ::testing::TempDir() + "ff_sim_force_trace.csv";
  {
    FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fprintf(f, "t_us,x,y,touch\n");
    for (int t_ms = 500; t_ms <= 2500; t_ms += 5) {
      const bool down = (t_ms < 1000) || (t_ms >= 1500 && t_ms < 2000);
      std::fprintf(f, "%d,%d,240,%d\n", t_ms * 1000, 200 + (t_ms - 500) / 10, down ? 1 : 0);
    }
    std::fclose(f);
  }
  Sim sim("--trace " + path);
  ASSERT_NE(sim.port, 0);
  auto at_ms = [&sim](int ms) { std::this_thread::sleep_until(sim.started + sim.ready_after + std::chrono::milliseconds(ms)); };
  // Whole ADC counts per cell: 300 mN / (4 x 10.508) = 7.14 -> 7 counts each: 294.2 mN.
  const float pressed_mN = 294.22f;
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
  EXPECT_LT(sim.status().status.force_mN, 50.0f) << "lifted reports still arriving";
  std::remove(path.c_str());
}

TEST(FfSim, RefusesABadTraceWithExitCode2) {
  const int rc = std::system((std::string(FF_SIM_BINARY) + " --trace /nonexistent.csv -q 2>/dev/null").c_str());
  ASSERT_TRUE(WIFEXITED(rc));
  EXPECT_EQ(WEXITSTATUS(rc), 2);
}

}  // namespace
