#pragma once
// The subset of ASN.1 BER/DER the zForce protocol uses: tag-length-value
// items with one- or two-octet identifiers and short or long (1-2 octet)
// lengths; unsigned INTEGER, BOOLEAN, NULL, OCTET STRING, SEQUENCE. Reads
// never go past the bytes given; writes never past the buffer given.
#include <cstddef>
#include <cstdint>

namespace ff::ber {

enum class Status : uint8_t { Ok, Truncated, Malformed };

constexpr uint8_t kConstructed = 0x20;

struct Tlv {
  uint16_t tag = 0;             // first identifier octet, or (first << 8) | second in the high-tag form
  bool constructed = false;
  const uint8_t* value = nullptr;
  size_t length = 0;            // content octets
  size_t size = 0;              // identifier + length octets + content
};

// One item at the start of `data`. Truncated: the bytes end before the item
// does. Malformed: indefinite length, more than 2 length octets, or a tag
// number that needs more than one subsequent identifier octet.
Status read_tlv(const uint8_t* data, size_t available, Tlv& out);

// Unsigned big-endian INTEGER content, 1 to 5 octets (5 only with a leading
// 0x00). False otherwise.
bool read_unsigned(const Tlv& tlv, uint32_t& out);

// Builds nested items into a fixed buffer. Any overflow makes ok() false and
// freezes the writer.
class Writer {
 public:
  Writer(uint8_t* buffer, size_t capacity) : buf_(buffer), cap_(capacity) {}

  void begin(uint16_t tag);  // a constructed item; up to kMaxDepth open at once
  void end();
  void unsigned_integer(uint16_t tag, uint32_t value);  // minimal, 0x00 prefix if the top bit is set
  void boolean(uint16_t tag, bool value);                 // 0xFF / 0x00
  void null(uint16_t tag);
  void octets(uint16_t tag, const uint8_t* data, size_t n);

  bool ok() const { return ok_ && depth_ == 0; }
  size_t size() const { return pos_; }

 private:
  static constexpr int kMaxDepth = 4;
  void put(uint8_t b);
  void put_tag(uint16_t tag);
  void put_header(uint16_t tag, size_t length);

  uint8_t* buf_;
  size_t cap_;
  size_t pos_ = 0;
  size_t open_[kMaxDepth] = {};  // position of each open item's length octet
  int depth_ = 0;
  bool ok_ = true;
};

}  // namespace ff::ber
