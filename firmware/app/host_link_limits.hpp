#pragma once
// How long the host links may make the main loop wait, and the rules that
// keep those waits away. Facts from Teensyduino and the Ethernet library:
// - usb_seremu.c and usb_mouse.c queue at most TX_PACKET_LIMIT packets per
//   endpoint (6 and 3); a write beyond waits TX_TIMEOUT_MSEC = 30 ms for a
//   host that does not poll. Writing only while the queue has room never waits.
// - The W5200 retries an unanswered ARP or send RCR times every RTR
//   (defaults 200 ms x 8 retries: ~1.8 s of busy-waiting in
//   EthernetUDP::endPacket, socket.cpp socketSendUDP); Ethernet.cpp's
//   setRetransmissionTimeout(ms) writes RTR = ms x 10 (100 us units).
#include <cstddef>
#include <cstdint>

namespace ff::firmware {

constexpr uint32_t kSeremuTxPacketLimit = 6;  // usb_seremu.c TX_PACKET_LIMIT
constexpr uint32_t kMouseTxPacketLimit = 3;   // usb_mouse.c TX_PACKET_LIMIT

// 64-byte reports the SEREMU transmit queue takes now without waiting.
constexpr size_t seremu_tx_room(bool usb_configured, uint32_t queued_packets) {
  return usb_configured && queued_packets < kSeremuTxPacketLimit ? kSeremuTxPacketLimit - queued_packets : 0;
}
// Whether Mouse.moveTo() would queue its report without waiting.
constexpr bool mouse_can_send(bool usb_configured, uint32_t queued_packets) {
  return usb_configured && queued_packets < kMouseTxPacketLimit;
}

// An unanswered send costs at most kW5200RetransmissionMs x (kW5200Retries + 1)
// = 10 ms, well inside the loop watchdog (kWatchdogUs); after one, the
// firmware stays quiet towards that address until it speaks again (UdpPeer).
constexpr uint16_t kW5200RetransmissionMs = 5;
constexpr uint8_t kW5200Retries = 1;

}  // namespace ff::firmware
