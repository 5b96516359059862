#include "firmware/app/hid_outbox.hpp"

#include <cstring>

namespace ff::firmware {

bool HidOutbox::push(const uint8_t* frame, size_t size) {
  if (frame == nullptr || size == 0 || size > protocol::kMaxFrame) return false;
  const size_t need = kLengthBytes + size;
  if (kCapacity - tail_ < need && head_ > 0) {  // the room is at the front: move the waiting frames there
    std::memmove(bytes_, bytes_ + head_, tail_ - head_);
    tail_ -= head_;
    head_ = 0;
  }
  if (kCapacity - tail_ < need) return false;
  bytes_[tail_] = static_cast<uint8_t>(size & 0xFF);
  bytes_[tail_ + 1] = static_cast<uint8_t>(size >> 8);
  std::memcpy(bytes_ + tail_ + kLengthBytes, frame, size);
  tail_ += need;
  return true;
}

void HidOutbox::drain(Board& board) {
  for (size_t room = board.hid_tx_room(); room > 0 && !empty(); --room) {
    const size_t size = bytes_[head_] | static_cast<size_t>(bytes_[head_ + 1]) << 8;
    uint8_t report[protocol::kHidReportBytes];
    protocol::fill_report(bytes_ + head_ + kLengthBytes, size, sent_, report);
    board.hid_send(report);
    if (++sent_ < protocol::reports_for(size)) continue;
    head_ += kLengthBytes + size;
    sent_ = 0;
    if (head_ == tail_) head_ = tail_ = 0;
  }
}

}  // namespace ff::firmware
