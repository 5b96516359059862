#include "frictionfield/drivers/zforce_frame.hpp"

#include "frictionfield/drivers/ber.hpp"

namespace ff::zforce {
namespace {

FrameError from_ber(ber::Status s) {
  return s == ber::Status::Truncated ? FrameError::Truncated : FrameError::MalformedTag;
}

// Members a response (the Message SEQUENCE) may carry besides the address.
bool is_message_member(uint16_t tag) {
  switch (tag) {
    case kEnable: case kTouchFormat: case kOperationMode: case kFrequency: case kResolution:
    case 0x6A:  // openShort [APPLICATION 10]
    case 0x6C:  // deviceInformation [APPLICATION 12]
    case 0x6D:  // status [APPLICATION 13]
    case 0x6F:  // deviceCount [APPLICATION 15]
    case 0x72:  // signalsLayout [APPLICATION 18]
    case kDeviceConfiguration:
    case kResultCode:
    case 0x75:    // diagnosticsSettings [APPLICATION 21]
    case 0x79:    // storageOperation [APPLICATION 25]
    case 0x7A:    // lighting [APPLICATION 26]
    case 0x7C:    // lowSignal [APPLICATION 28]
    case 0x5F1F:  // errorCounterClear [APPLICATION 31]
    case 0x7F20:  // errorInformation [APPLICATION 32]
    case 0x5F21:  // errorLog [APPLICATION 33]
    case 0x7F22:  // errorThresholds [APPLICATION 34]
    case 0x7F24:  // touchMode [APPLICATION 36]
      return true;
    default:
      return false;
  }
}

// Notification choices this driver does not use but recognises.
bool is_other_notification(uint16_t tag) {
  switch (tag) {
    case 0x6B:  // ledLevels [APPLICATION 11]
    case 0x6E:  // coreSignals [APPLICATION 14]
    case 0x71:  // airSignals [APPLICATION 17]
    case 0xA1:  // airMaximum [1]
    case 0xA2:  // gestureNotifications [2]
    case kStatusNotification:
      return true;
    default:
      return false;
  }
}

FrameError decode_address(const ber::Tlv& t, Message& out) {
  if (t.length != 2) return FrameError::MalformedTag;
  if (t.value[0] > kMaxDeviceType) return FrameError::ImpossibleValue;
  out.has_address = true;
  out.device_type = t.value[0];
  out.device_index = t.value[1];
  return FrameError::None;
}

}  // namespace

const char* to_string(FrameError e) {
  switch (e) {
    case FrameError::None: return "none";
    case FrameError::WrongHeader: return "wrong header";
    case FrameError::LengthOverMax: return "length over max";
    case FrameError::Truncated: return "truncated";
    case FrameError::MalformedTag: return "malformed tag";
    case FrameError::UnknownTag: return "unknown tag";
    case FrameError::ImpossibleValue: return "impossible value";
  }
  return "?";
}

FrameError parse_touch_descriptor(const uint8_t* content, size_t n, TouchFormat& out) {
  if (n < 2) return FrameError::MalformedTag;  // unused-bits octet and at least one data octet
  const uint8_t unused = content[0];
  if (unused > 7) return FrameError::MalformedTag;
  if (n > 5) return FrameError::ImpossibleValue;  // more than 32 fields: sizes unknown
  uint32_t fields = 0;
  const size_t bits = (n - 1) * 8 - unused;
  for (size_t i = 0; i < bits; ++i) {
    const uint8_t octet = content[1 + i / 8];
    if ((octet >> (7 - i % 8)) & 1u) fields |= 1u << i;
  }
  TouchFormat f;
  f.fields = fields;
  if (!f.usable()) return FrameError::ImpossibleValue;
  out = f;
  return FrameError::None;
}

FrameError FrameDecoder::decode(const uint8_t* frame, size_t n, Message& out) const {
  if (frame == nullptr || n < 2) return FrameError::Truncated;
  if (frame[0] != kFrameStart) return FrameError::WrongHeader;
  const size_t length = frame[1];
  if (length > kMaxFramePayload) return FrameError::LengthOverMax;
  if (n - 2 < length) return FrameError::Truncated;
  if (n - 2 > length) return FrameError::MalformedTag;  // trailing bytes
  return decode_payload(frame + 2, length, out);
}

FrameError FrameDecoder::decode_payload(const uint8_t* p, size_t n, Message& out) const {
  out = Message{};
  if (n > kMaxFramePayload) return FrameError::LengthOverMax;
  ber::Tlv top;
  const ber::Status s = ber::read_tlv(p, n, top);
  if (s != ber::Status::Ok) return from_ber(s);
  if (top.size != n) return FrameError::MalformedTag;  // trailing bytes after the message
  if (top.tag == kResponse) return decode_response(top.value, top.length, out);
  if (top.tag == kNotification) return decode_notification(top.value, top.length, out);
  return FrameError::UnknownTag;  // includes a request, which the sensor never sends
}

FrameError FrameDecoder::decode_response(const uint8_t* p, size_t n, Message& out) const {
  out.kind = MessageKind::Response;
  size_t pos = 0;
  bool first = true;
  while (pos < n) {
    ber::Tlv t;
    const ber::Status s = ber::read_tlv(p + pos, n - pos, t);
    if (s != ber::Status::Ok) return from_ber(s);
    pos += t.size;
    if (t.tag == kDeviceAddress) {
      if (!first) return FrameError::MalformedTag;
      const FrameError e = decode_address(t, out);
      if (e != FrameError::None) return e;
    } else if (is_message_member(t.tag)) {
      if (out.response_to == 0) out.response_to = t.tag;
      if (t.tag == kTouchFormat) {
        ber::Tlv d;
        if (t.length > 0) {
          const ber::Status ds = ber::read_tlv(t.value, t.length, d);
          if (ds != ber::Status::Ok) return from_ber(ds);
          if (d.tag != kTouchDescriptor) return FrameError::UnknownTag;
          if (d.size != t.length) return FrameError::MalformedTag;
          const FrameError e = parse_touch_descriptor(d.value, d.length, out.format);
          if (e != FrameError::None) return e;
          out.has_format = true;
        }
      }
    } else {
      return FrameError::UnknownTag;
    }
    first = false;
  }
  if (out.response_to == 0) return FrameError::MalformedTag;  // a response must answer something
  return FrameError::None;
}

FrameError FrameDecoder::decode_notification(const uint8_t* p, size_t n, Message& out) const {
  size_t pos = 0;
  bool first = true;
  bool have_choice = false;
  while (pos < n) {
    ber::Tlv t;
    const ber::Status s = ber::read_tlv(p + pos, n - pos, t);
    if (s != ber::Status::Ok) return from_ber(s);
    pos += t.size;
    if (t.tag == kDeviceAddress) {
      if (!first) return FrameError::MalformedTag;
      const FrameError e = decode_address(t, out);
      if (e != FrameError::None) return e;
    } else if (t.tag == kTimestamp || t.tag == kLatency) {
      if (!have_choice) return FrameError::MalformedTag;  // they follow the notification
      uint32_t v = 0;
      if (!ber::read_unsigned(t, v)) return FrameError::MalformedTag;
      if (t.tag == kTimestamp) {
        if (out.has_timestamp) return FrameError::MalformedTag;  // one per message, either layout
        out.has_timestamp = true;
        out.timestamp = v;
      }
    } else {
      if (have_choice) return FrameError::MalformedTag;  // exactly one notification per message
      have_choice = true;
      if (t.tag == kTouchNotifications) {
        out.kind = MessageKind::Touches;
        size_t q = 0;
        while (q < t.length) {
          ber::Tlv touch;
          const ber::Status ts = ber::read_tlv(t.value + q, t.length - q, touch);
          if (ts != ber::Status::Ok) return from_ber(ts);
          q += touch.size;
          if (touch.tag == kTimestamp || touch.tag == kLatency) {
            // The other layout: the timestamp inside the sequence.
            if (out.has_timestamp) return FrameError::MalformedTag;
            uint32_t v = 0;
            if (!ber::read_unsigned(touch, v)) return FrameError::MalformedTag;
            if (touch.tag == kTimestamp) {
              out.has_timestamp = true;
              out.timestamp_inside = true;
              out.timestamp = v;
            }
            continue;
          }
          if (touch.tag != kTouchNotification) return FrameError::UnknownTag;
          if (out.touch_count >= kMaxTouches) return FrameError::ImpossibleValue;
          const FrameError e = decode_touch(touch.value, touch.length, out.touches[out.touch_count]);
          if (e != FrameError::None) return e;
          ++out.touch_count;
        }
        if (out.touch_count == 0 && out.timestamp_inside) return FrameError::MalformedTag;  // a stamp of nothing
      } else if (t.tag == kTouchNotification) {
        out.kind = MessageKind::Touches;
        const FrameError e = decode_touch(t.value, t.length, out.touches[0]);
        if (e != FrameError::None) return e;
        out.touch_count = 1;
      } else if (t.tag == kBootComplete) {
        out.kind = MessageKind::BootComplete;
      } else if (is_other_notification(t.tag)) {
        out.kind = MessageKind::OtherNotification;
      } else {
        return FrameError::UnknownTag;
      }
    }
    first = false;
  }
  if (!have_choice) return FrameError::MalformedTag;
  for (uint8_t i = 0; i < out.touch_count; ++i) {
    for (uint8_t j = 0; j < i; ++j) {
      if (out.touches[i].id == out.touches[j].id) return FrameError::ImpossibleValue;
    }
  }
  return FrameError::None;
}

FrameError FrameDecoder::decode_touch(const uint8_t* p, size_t n, Touch& out) const {
  if (n != format_.bytes()) return FrameError::ImpossibleValue;
  Touch t;
  uint32_t event = 0;
  size_t pos = 0;
  for (uint8_t f = 0; f < kTouchFieldCount; ++f) {
    if (((format_.fields >> f) & 1u) == 0) continue;
    const uint8_t b = p[pos++];
    switch (static_cast<TouchField>(f)) {
      case TouchField::Id: t.id = b; break;
      case TouchField::Event: event = b; break;
      case TouchField::X1: t.x = b; break;
      case TouchField::X2: case TouchField::X3: t.x = (t.x << 8) | b; break;
      case TouchField::Y1: t.y = b; break;
      case TouchField::Y2: case TouchField::Y3: t.y = (t.y << 8) | b; break;
      default: break;  // z, sizes, orientation, confidence, pressure: not used
    }
  }
  if (event > kMaxTouchEvent) return FrameError::ImpossibleValue;
  t.event = static_cast<TouchEvent>(event);
  const bool located = t.event == TouchEvent::Down || t.event == TouchEvent::Move || t.event == TouchEvent::Up;
  if (located && (t.x > max_x_ || t.y > max_y_)) return FrameError::ImpossibleValue;
  out = t;
  return FrameError::None;
}

}  // namespace ff::zforce
