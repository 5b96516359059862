// UdpTransport against real sockets on 127.0.0.1: what it resolves, opens,
// sends to and closes, and how it waits.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

#include "frictionfield/protocol/codec.hpp"
#include "udp_transport.hpp"

namespace ff::ffctl {
namespace {

// The lowest free file descriptor: what the next socket() would get.
int next_descriptor() {
  const int fd = ::open("/dev/null", O_RDONLY);
  ::close(fd);
  return fd;
}

// A socket of `type` bound to 127.0.0.1:`port` (0: any free port); -1 if the port is taken.
int bound(int type, uint16_t port) {
  const int s = ::socket(AF_INET, type, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || (type == SOCK_STREAM && ::listen(s, 1) != 0)) {
    ::close(s);
    return -1;
  }
  return s;
}

uint16_t port_of(int s) {
  sockaddr_in a{};
  socklen_t n = sizeof a;
  ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &n);
  return ntohs(a.sin_port);
}

TEST(UdpTransport, ResolvesIPv4AddressesOnly) {
  // A name that resolves to ::1 as well as 127.0.0.1 (localhost, on most
  // machines) must reach ff-sim's 127.0.0.1, so IPv6 is never asked for.
  try {
    UdpTransport to_v6("::1", kDefaultUdpPort);
    ADD_FAILURE() << "an IPv6 address was opened";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("cannot resolve ::1: ", 0), 0u) << e.what();
  }
  EXPECT_NO_THROW(UdpTransport("127.0.0.1", kDefaultUdpPort));
}

TEST(UdpTransport, SendsDatagramsEvenWhereATcpServerHasThePort) {
  // getaddrinfo lists a stream address first unless asked for datagrams: a
  // TCP server on the device's port must not be what the frames go to.
  int udp = -1, tcp = -1;
  for (int attempt = 0; attempt < 20 && tcp < 0; ++attempt) {
    if (udp >= 0) ::close(udp);
    udp = bound(SOCK_DGRAM, 0);
    tcp = bound(SOCK_STREAM, port_of(udp));
  }
  ASSERT_GE(tcp, 0) << "no port free for both";
  UdpTransport transport("127.0.0.1", port_of(udp));
  const uint8_t frame[] = {0xF5, 0x01, 0x02};
  ASSERT_TRUE(transport.send(frame, sizeof frame));
  pollfd p{udp, POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 2000), 1) << "no datagram arrived";
  uint8_t got[8] = {};
  EXPECT_EQ(::recv(udp, got, sizeof got, 0), 3);
  EXPECT_EQ(got[0], 0xF5);
  EXPECT_EQ(got[2], 0x02);
  ::close(tcp);
  ::close(udp);
}

TEST(UdpTransport, AnAddressItCannotConnectToIsRefusedWithTheReasonAndNothingLeftOpen) {
  // A datagram socket connects to a broadcast address only with SO_BROADCAST (EACCES).
  const int before = next_descriptor();
  try {
    UdpTransport broadcast("255.255.255.255", kDefaultUdpPort);
    ADD_FAILURE() << "a broadcast address was connected to";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "cannot open a UDP socket to 255.255.255.255:8888: Permission denied");
  }
  EXPECT_EQ(next_descriptor(), before);
}

TEST(UdpTransport, ItsSocketIsClosedWithIt) {
  const int before = next_descriptor();
  {
    UdpTransport transport("127.0.0.1", kDefaultUdpPort);
    EXPECT_NE(next_descriptor(), before);
  }
  EXPECT_EQ(next_descriptor(), before);
}

TEST(UdpTransport, ADeadlineAlreadyPastIsATimeoutNotAWaitForever) {
  const int device = bound(SOCK_DGRAM, 0);
  UdpTransport transport("127.0.0.1", port_of(device));
  std::vector<uint8_t> frame;
  EXPECT_EQ(transport.receive(frame, -5), ReceiveResult::Timeout);  // poll() with a negative timeout would block
  ::close(device);
}

TEST(UdpTransport, NobodyListeningIsWaitedOutNotADisconnection) {
  // The ICMP port unreachable a send to a closed port brings back shows up
  // as ECONNREFUSED on the next recv: ff-sim may not have started yet.
  const int device = bound(SOCK_DGRAM, 0);
  const uint16_t port = port_of(device);
  ::close(device);
  UdpTransport transport("127.0.0.1", port);
  const uint8_t frame[] = {1};
  ASSERT_TRUE(transport.send(frame, sizeof frame));
  std::vector<uint8_t> reply;
  EXPECT_EQ(transport.receive(reply, 200), ReceiveResult::Timeout);
}

TEST(UdpTransport, NoSocketToBeHadIsRefusedWithTheReason) {
#if defined(__SANITIZE_ADDRESS__)
  // UBSan's vptr check probes memory through a pipe: with no descriptor left
  // it reports the object under construction as invalid.
  GTEST_SKIP() << "the sanitizer runtime needs descriptors of its own";
#endif
  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_NOFILE, &saved), 0);
  rlimit none = saved;
  none.rlim_cur = static_cast<rlim_t>(next_descriptor());  // every descriptor below it is taken
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &none), 0);
  std::string what;
  try {
    UdpTransport transport("127.0.0.1", kDefaultUdpPort);
  } catch (const std::runtime_error& e) {
    what = e.what();
  }
  ASSERT_EQ(::setrlimit(RLIMIT_NOFILE, &saved), 0);
  EXPECT_EQ(what, "cannot open a UDP socket to 127.0.0.1:8888: Too many open files");
}

TEST(UdpTransport, ASignalWhileWaitingIsNotADisconnection) {
  // Ctrl-C interrupts poll() (EINTR); the wait goes on to its deadline, and
  // the caller looks at what the signal asked for when receive() returns.
  struct sigaction quiet {}, saved{};
  quiet.sa_handler = [](int) {};
  ASSERT_EQ(::sigaction(SIGALRM, &quiet, &saved), 0);  // no SA_RESTART: poll() returns EINTR
  const int device = bound(SOCK_DGRAM, 0);
  UdpTransport transport("127.0.0.1", port_of(device));
  itimerval in_50_ms{};
  in_50_ms.it_value.tv_usec = 50000;
  ASSERT_EQ(::setitimer(ITIMER_REAL, &in_50_ms, nullptr), 0);
  std::vector<uint8_t> frame;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(transport.receive(frame, 300), ReceiveResult::Timeout);
  EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(290));
  ::sigaction(SIGALRM, &saved, nullptr);
  ::close(device);
}

// What the transport receives when the device (a socket on 127.0.0.1)
// answers its first datagram with `reply`, as the device answers its sender.
std::vector<uint8_t> received_reply(const std::vector<uint8_t>& reply) {
  const int device = bound(SOCK_DGRAM, 0);
  UdpTransport transport("127.0.0.1", port_of(device));
  const uint8_t hello[] = {0};
  EXPECT_TRUE(transport.send(hello, sizeof hello));
  sockaddr_in from{};
  socklen_t n = sizeof from;
  uint8_t got[4];
  EXPECT_EQ(::recvfrom(device, got, sizeof got, 0, reinterpret_cast<sockaddr*>(&from), &n), 1);
  EXPECT_EQ(::sendto(device, reply.data(), reply.size(), 0, reinterpret_cast<sockaddr*>(&from), n),
            static_cast<ssize_t>(reply.size()));
  std::vector<uint8_t> frame;
  EXPECT_EQ(transport.receive(frame, 2000), ReceiveResult::Frame);
  ::close(device);
  return frame;
}

TEST(UdpTransport, ADatagramIsOneFrameOfItsOwnLength) {
  EXPECT_EQ(received_reply({9, 8, 7, 6, 5}), std::vector<uint8_t>({9, 8, 7, 6, 5}));
}

TEST(UdpTransport, AnOversizedDatagramArrivesLongerThanAnyFrame) {
  // Longer than any frame, so the decoder refuses its length instead of a cut frame.
  EXPECT_GT(received_reply(std::vector<uint8_t>(4000, 0x55)).size(), protocol::kMaxFrame);
}

}  // namespace
}  // namespace ff::ffctl
