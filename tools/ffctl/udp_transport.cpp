#include "udp_transport.hpp"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "frictionfield/protocol/codec.hpp"

namespace ff::ffctl {

bool parse_udp_address(const std::string& text, std::string& host, uint16_t& port, std::string& error) {
  host = text;
  port = kDefaultUdpPort;
  if (std::count(text.begin(), text.end(), ':') > 1 || text.find('[') != std::string::npos) {
    return error = "--udp " + text + ": an IPv6 address; the device's WIZ820io and ff-sim speak IPv4 only", false;
  }
  const size_t colon = text.rfind(':');
  if (colon != std::string::npos) {
    host = text.substr(0, colon);
    const std::string p = text.substr(colon + 1);
    char* end = nullptr;
    const long v = std::strtol(p.c_str(), &end, 10);
    if (p.empty() || *end != '\0' || v < 1 || v > 65535) {
      return error = "--udp " + text + ": the port must be a number 1..65535", false;
    }
    port = static_cast<uint16_t>(v);
  }
  if (host.empty()) return error = "--udp " + text + ": no host (e.g. --udp 192.168.1.177 or --udp 127.0.0.1:8888)", false;
  return true;
}

UdpTransport::UdpTransport(const std::string& host, uint16_t port) {
  addrinfo hints{};
  // IPv4 only: the WIZ820io and ff-sim have no IPv6, and a name such as
  // localhost that also resolves to ::1 would send there, to no one.
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  const int r = getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found);
  if (r != 0) throw std::runtime_error("cannot resolve " + host + ": " + gai_strerror(r));
  std::string why = "no address";
  for (addrinfo* a = found; a; a = a->ai_next) {
    const int s = ::socket(a->ai_family, a->ai_socktype, a->ai_protocol);
    if (s < 0) {
      why = std::strerror(errno);
      continue;
    }
    // connect(): send() needs no address, and datagrams from anyone else are dropped by the kernel.
    if (::connect(s, a->ai_addr, a->ai_addrlen) == 0) {
      socket_ = s;
      break;
    }
    why = std::strerror(errno);
    ::close(s);
  }
  freeaddrinfo(found);
  if (socket_ < 0) throw std::runtime_error("cannot open a UDP socket to " + host + ":" + std::to_string(port) + ": " + why);
}

UdpTransport::~UdpTransport() {
  if (socket_ >= 0) ::close(socket_);
}

bool UdpTransport::send(const uint8_t* frame, size_t size) {
  return ::send(socket_, frame, size, 0) == static_cast<ssize_t>(size);
}

ReceiveResult UdpTransport::receive(std::vector<uint8_t>& frame, int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    const int left = static_cast<int>(
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count());
    if (left <= 0) return ReceiveResult::Timeout;
    pollfd p{socket_, POLLIN, 0};
    const int ready = ::poll(&p, 1, left);
    if (ready < 0 && errno == EINTR) continue;  // Ctrl-C: the caller looks once a frame or the deadline comes
    if (ready <= 0) return ready == 0 ? ReceiveResult::Timeout : ReceiveResult::Disconnected;
    frame.resize(protocol::kMaxFrame + 1);  // one more: an oversized datagram shows as a length error
    const ssize_t n = ::recv(socket_, frame.data(), frame.size(), 0);
    if (n < 0) {
      // ICMP port unreachable on a connected socket: nobody listens there (yet). Keep waiting.
      if (errno == ECONNREFUSED || errno == EINTR || errno == EAGAIN) continue;
      return ReceiveResult::Disconnected;
    }
    frame.resize(static_cast<size_t>(n));
    return ReceiveResult::Frame;
  }
}

}  // namespace ff::ffctl
