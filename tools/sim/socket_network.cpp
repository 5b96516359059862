#include "socket_network.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace ff::sim {

int open_udp(uint16_t port, uint16_t& bound_port, std::string& error) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) {
    error = std::string("socket: ") + std::strerror(errno);
    return -1;
  }
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    error = "cannot listen on 127.0.0.1:" + std::to_string(port) + ": " + std::strerror(errno);
    ::close(fd);
    return -1;
  }
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  bound_port = ntohs(a.sin_port);
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
  return fd;
}

SocketNetwork::~SocketNetwork() {
  if (fd_ >= 0) ::close(fd_);
}

bool SocketNetwork::open(uint16_t port, std::string& error) {
  fd_ = open_udp(port, port_, error);
  return fd_ >= 0;
}

bool SocketNetwork::receive(std::vector<uint8_t>& payload, uint32_t& ip, uint16_t& port) {
  uint8_t buf[2048];
  sockaddr_in from{};
  socklen_t len = sizeof from;
  const ssize_t n = ::recvfrom(fd_, buf, sizeof buf, 0, reinterpret_cast<sockaddr*>(&from), &len);
  if (n < 0) return false;
  payload.assign(buf, buf + n);
  ip = from.sin_addr.s_addr;  // network order: the first octet in the lowest byte, as IPAddress keeps it
  port = ntohs(from.sin_port);
  return true;
}

bool SocketNetwork::deliver(uint32_t ip, uint16_t port, const std::vector<uint8_t>& payload) {
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = ip;
  // A full socket buffer on loopback loses the datagram, as a busy network would; ARP always answers here.
  ::sendto(fd_, payload.data(), payload.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
  return true;
}

}  // namespace ff::sim
