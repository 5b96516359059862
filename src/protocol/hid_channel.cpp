#include "frictionfield/protocol/hid_channel.hpp"

#include <cstring>

namespace ff::protocol {

void fill_report(const uint8_t* frame, size_t size, size_t index, uint8_t* report) {
  const size_t offset = index * kHidChunkBytes;
  const size_t chunk = size - offset < kHidChunkBytes ? size - offset : kHidChunkBytes;
  std::memset(report, 0, kHidReportBytes);
  report[0] = static_cast<uint8_t>((index + 1 == reports_for(size) ? 0x80u : 0u) | index);
  std::memcpy(&report[1], frame + offset, chunk);
}

size_t split_into_reports(const uint8_t* frame, size_t size, uint8_t (*reports)[kHidReportBytes],
                          size_t max_reports) {
  const size_t n = reports_for(size);
  if (frame == nullptr || size == 0 || n > max_reports || n > 0x7F) return 0;
  for (size_t i = 0; i < n; ++i) fill_report(frame, size, i, reports[i]);
  return n;
}

bool HidReassembler::push(const uint8_t* report) {
  const uint8_t index = report[0] & 0x7Fu;
  const bool last = (report[0] & 0x80u) != 0;
  if (index != next_index_) {
    // Out of order or a lost report: drop what we had; a fresh first report starts over.
    ++errors_;
    filled_ = 0;
    next_index_ = 0;
    if (index != 0) return false;
  }
  if (filled_ + kHidChunkBytes > sizeof(buffer_)) {
    ++errors_;
    filled_ = 0;
    next_index_ = 0;
    return false;
  }
  std::memcpy(buffer_ + filled_, report + 1, kHidChunkBytes);
  filled_ += kHidChunkBytes;
  next_index_ = static_cast<uint8_t>(index + 1);
  if (!last) return false;
  next_index_ = 0;
  // The frame's own header says how long it is; the rest is padding.
  const size_t want = kHeaderBytes + (static_cast<size_t>(buffer_[5]) | (static_cast<size_t>(buffer_[6]) << 8)) + kCrcBytes;
  const bool complete = want <= filled_;
  filled_ = 0;
  complete_size_ = complete ? want : 0;
  if (!complete) ++errors_;
  return complete;
}

}  // namespace ff::protocol
