#pragma once
// Frames on their way to the USB host channel, whole and in order.
// Teensyduino queues at most 6 SEREMU IN packets (usb_seremu.c
// TX_PACKET_LIMIT) and a write beyond waits up to 30 ms for the host, but a
// frame may need more reports than that: Samples with their taken times 7, a
// Condition carrying a full scene 22. So a frame is taken whole or not at
// all, and its reports go out as the queue has room, over as many loop
// passes as that takes; the host reassembles them in order.
#include <cstddef>
#include <cstdint>

#include "firmware/app/board.hpp"
#include "frictionfield/protocol/hid_channel.hpp"

namespace ff::firmware {

class HidOutbox {
 public:
  // False, and nothing taken, if the frame does not fit beside those waiting.
  bool push(const uint8_t* frame, size_t size);
  // Hands the board as many reports as it takes now (Board::hid_tx_room).
  void drain(Board& board);
  bool empty() const { return head_ == tail_; }

  static constexpr size_t kLengthBytes = 2;  // before each waiting frame
  static constexpr size_t kCapacity = protocol::kMaxHidReports * protocol::kHidReportBytes;
  static_assert(kCapacity >= kLengthBytes + protocol::kMaxFrame, "the largest frame fits on its own");

 private:
  uint8_t bytes_[kCapacity] = {};
  size_t head_ = 0;  // the first waiting frame's length
  size_t tail_ = 0;
  size_t sent_ = 0;  // reports of the first frame already handed over
};

}  // namespace ff::firmware
