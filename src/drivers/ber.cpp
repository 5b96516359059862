#include "frictionfield/drivers/ber.hpp"

#include <cstring>

namespace ff::ber {

Status read_tlv(const uint8_t* data, size_t available, Tlv& out) {
  if (data == nullptr || available < 2) return Status::Truncated;
  size_t pos = 0;
  const uint8_t first = data[pos++];
  uint16_t tag = first;
  if ((first & 0x1Fu) == 0x1Fu) {
    // High-tag form: one subsequent octet, tag number 31..127.
    const uint8_t second = data[pos++];
    if ((second & 0x80u) != 0 || second < 0x1Fu) return Status::Malformed;
    tag = static_cast<uint16_t>((first << 8) | second);
  }
  if (pos >= available) return Status::Truncated;
  const uint8_t l0 = data[pos++];
  size_t length = 0;
  if (l0 < 0x80u) {
    length = l0;
  } else {
    const uint8_t count = l0 & 0x7Fu;
    if (count == 0 || count > 2) return Status::Malformed;  // indefinite, or longer than any zForce item
    if (available - pos < count) return Status::Truncated;
    for (uint8_t i = 0; i < count; ++i) length = (length << 8) | data[pos++];
  }
  if (available - pos < length) return Status::Truncated;
  out.tag = tag;
  out.constructed = (first & kConstructed) != 0;
  out.value = data + pos;
  out.length = length;
  out.size = pos + length;
  return Status::Ok;
}

bool read_unsigned(const Tlv& tlv, uint32_t& out) {
  if (tlv.constructed || tlv.length == 0 || tlv.length > 5) return false;
  if (tlv.length == 5 && tlv.value[0] != 0) return false;
  uint32_t v = 0;
  for (size_t i = 0; i < tlv.length; ++i) v = (v << 8) | tlv.value[i];
  out = v;
  return true;
}

void Writer::put(uint8_t b) {
  if (!ok_) return;
  if (pos_ >= cap_) {
    ok_ = false;
    return;
  }
  buf_[pos_++] = b;
}

void Writer::put_tag(uint16_t tag) {
  if (tag > 0xFF) put(static_cast<uint8_t>(tag >> 8));
  put(static_cast<uint8_t>(tag & 0xFF));
}

void Writer::put_header(uint16_t tag, size_t length) {
  put_tag(tag);
  if (length < 0x80) {
    put(static_cast<uint8_t>(length));
  } else if (length <= 0xFF) {
    put(0x81);
    put(static_cast<uint8_t>(length));
  } else {
    put(0x82);
    put(static_cast<uint8_t>(length >> 8));
    put(static_cast<uint8_t>(length & 0xFF));
  }
}

void Writer::begin(uint16_t tag) {
  if (depth_ >= kMaxDepth) {
    ok_ = false;
    return;
  }
  put_tag(tag);
  open_[depth_++] = pos_;
  put(0);  // short-form placeholder, widened in end() if needed
}

void Writer::end() {
  if (!ok_ || depth_ == 0) {
    ok_ = false;
    return;
  }
  const size_t at = open_[--depth_];
  const size_t length = pos_ - at - 1;
  if (length < 0x80) {
    buf_[at] = static_cast<uint8_t>(length);
    return;
  }
  const size_t extra = length <= 0xFF ? 1 : 2;
  if (length > 0xFFFF || pos_ + extra > cap_) {
    ok_ = false;
    return;
  }
  std::memmove(buf_ + at + 1 + extra, buf_ + at + 1, length);
  pos_ += extra;
  if (extra == 1) {
    buf_[at] = 0x81;
    buf_[at + 1] = static_cast<uint8_t>(length);
  } else {
    buf_[at] = 0x82;
    buf_[at + 1] = static_cast<uint8_t>(length >> 8);
    buf_[at + 2] = static_cast<uint8_t>(length & 0xFF);
  }
}

void Writer::unsigned_integer(uint16_t tag, uint32_t value) {
  uint8_t bytes[5];
  int n = 0;
  for (int shift = 24; shift >= 0; shift -= 8) {
    const uint8_t b = static_cast<uint8_t>(value >> shift);
    if (n == 0 && b == 0 && shift != 0) continue;  // minimal: skip leading zero octets
    if (n == 0 && (b & 0x80u) != 0) bytes[n++] = 0;  // keep it non-negative
    bytes[n++] = b;
  }
  put_header(tag, static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) put(bytes[i]);
}

void Writer::boolean(uint16_t tag, bool value) {
  put_header(tag, 1);
  put(value ? 0xFF : 0x00);
}

void Writer::null(uint16_t tag) { put_header(tag, 0); }

void Writer::octets(uint16_t tag, const uint8_t* data, size_t n) {
  put_header(tag, n);
  for (size_t i = 0; i < n; ++i) put(data[i]);
}

}  // namespace ff::ber
