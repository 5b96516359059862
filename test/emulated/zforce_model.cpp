#include "frictionfield/emulated/zforce_model.hpp"

#include <algorithm>
#include <cmath>

namespace ff::emulated {
namespace {

// Byte values written out here on purpose (not the driver's constants): the
// model is a second reading of the protocol description.
constexpr uint8_t kStart = 0xEE;
constexpr uint8_t kResponseTag = 0xEF;
constexpr uint8_t kNotificationTag = 0xF0;
constexpr uint8_t kAddressTag = 0x40;
constexpr uint8_t kTouchSequenceTag = 0xA0;
constexpr uint8_t kTouchTag = 0x42;
constexpr uint8_t kTimestampTag = 0x58;

void put_length(std::vector<uint8_t>& out, size_t n) {
  if (n < 0x80) {
    out.push_back(static_cast<uint8_t>(n));
  } else {
    out.push_back(0x81);
    out.push_back(static_cast<uint8_t>(n));
  }
}

void put_item(std::vector<uint8_t>& out, uint8_t tag, const std::vector<uint8_t>& content) {
  out.push_back(tag);
  put_length(out, content.size());
  out.insert(out.end(), content.begin(), content.end());
}

std::vector<uint8_t> unsigned_content(uint32_t v) {
  std::vector<uint8_t> c;
  bool started = false;
  for (int shift = 24; shift >= 0; shift -= 8) {
    const uint8_t b = static_cast<uint8_t>(v >> shift);
    if (!started && b == 0 && shift != 0) continue;
    if (!started && (b & 0x80)) c.push_back(0);
    started = true;
    c.push_back(b);
  }
  return c;
}

std::vector<uint8_t> frame_of(const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> f{kStart, static_cast<uint8_t>(payload.size())};
  f.insert(f.end(), payload.begin(), payload.end());
  return f;
}

bool read_uint(const uint8_t* p, size_t n, uint32_t& out) {
  if (n == 0 || n > 3) return false;
  out = 0;
  for (size_t i = 0; i < n; ++i) out = (out << 8) | p[i];
  return true;
}

}  // namespace

ZforceModel::ZforceModel(const Options& options) : options_(options) {
  if (options_.boot_complete) {
    // notification { address platform, bootCompleteNotification { asicStatus 0, resetSource '80'H (power up) } }
    std::vector<uint8_t> p{kNotificationTag, 0, kAddressTag, 2, 0x00, 0x00, 0x63, 0x07,
                           0x80, 0x01, 0x00, 0x81, 0x02, 0x07, 0x80};
    p[1] = static_cast<uint8_t>(p.size() - 2);
    schedule({0, frame_of(p), p.size() + 2, false});
  }
}

void ZforceModel::to_sensor(float x_px, float y_px, uint32_t& x, uint32_t& y) const {
  const ScreenCalibration& c = calibration_;
  double u = (static_cast<double>(x_px) - static_cast<double>(c.offset_x)) / static_cast<double>(c.scale_x);
  double v = (static_cast<double>(y_px) - static_cast<double>(c.offset_y)) / static_cast<double>(c.scale_y);
  if (c.flip_x) u = static_cast<double>(c.range_x) - u;
  if (c.flip_y) v = static_cast<double>(c.range_y) - v;
  const double rx = c.swap_xy ? v : u;
  const double ry = c.swap_xy ? u : v;
  const double max_x = c.swap_xy ? c.range_y : c.range_x;
  const double max_y = c.swap_xy ? c.range_x : c.range_y;
  x = static_cast<uint32_t>(std::lround(std::clamp(rx, 0.0, max_x)));
  y = static_cast<uint32_t>(std::lround(std::clamp(ry, 0.0, max_y)));
}

namespace {
uint32_t sensor_ticks(uint32_t t_us) {  // the sensor's 32768 Hz clock, 16 bits
  return static_cast<uint32_t>((static_cast<uint64_t>(t_us) * 32768u / 1000000u) & 0xFFFFu);
}
}  // namespace

std::vector<uint8_t> ZforceModel::notification(const std::vector<uint8_t>& body, bool with_timestamp,
                                               uint32_t t_us) const {
  std::vector<uint8_t> content{kAddressTag, 2, 0x02, 0x00};  // zForce Air device 0
  content.insert(content.end(), body.begin(), body.end());
  if (with_timestamp) {
    put_item(content, kTimestampTag, unsigned_content(sensor_ticks(t_us)));
  }
  std::vector<uint8_t> payload;
  put_item(payload, kNotificationTag, content);
  return frame_of(payload);
}

std::vector<uint8_t> ZforceModel::touch_frame(const uint8_t* ids, const uint8_t* events, const uint32_t* xs,
                                              const uint32_t* ys, int count, uint32_t t_us) const {
  const uint32_t f = options_.format.fields;
  auto bytes_of = [f](int first, int n) {
    int k = 0;
    for (int i = first; i < first + n; ++i) k += (f >> i) & 1u;
    return k;
  };
  const int nx = bytes_of(2, 3), ny = bytes_of(5, 3), nsize = bytes_of(11, 3);
  std::vector<uint8_t> touches;
  for (int t = 0; t < count; ++t) {
    std::vector<uint8_t> b;
    int kx = 0, ky = 0, ks = 0;
    for (int field = 0; field < 23; ++field) {
      if (((f >> field) & 1u) == 0) continue;
      if (field == 0) {
        b.push_back(ids[t]);
      } else if (field == 1) {
        b.push_back(events[t]);
      } else if (field >= 2 && field <= 4) {
        b.push_back(static_cast<uint8_t>(xs[t] >> (8 * (nx - 1 - kx++))));
      } else if (field >= 5 && field <= 7) {
        b.push_back(static_cast<uint8_t>(ys[t] >> (8 * (ny - 1 - ky++))));
      } else if (field >= 11 && field <= 13) {
        b.push_back(static_cast<uint8_t>(48u >> (8 * (nsize - 1 - ks++))));  // a finger ~12 px wide
      } else if (field == 21) {
        b.push_back(100);  // confidence
      } else {
        b.push_back(0);
      }
    }
    put_item(touches, kTouchTag, b);
  }
  const bool inside = options_.timestamps && options_.timestamp_inside;
  if (inside) put_item(touches, kTimestampTag, unsigned_content(sensor_ticks(t_us)));
  std::vector<uint8_t> body;
  put_item(body, kTouchSequenceTag, touches);
  return notification(body, options_.timestamps && !inside, t_us);
}

void ZforceModel::schedule(Frame f) {
  auto it = std::upper_bound(queue_.begin() + (current_ ? 1 : 0), queue_.end(), f.due_us,
                             [](uint32_t due, const Frame& g) { return static_cast<int32_t>(due - g.due_us) < 0; });
  queue_.insert(it, std::move(f));
}

void ZforceModel::schedule_raw(uint32_t t_us, std::vector<uint8_t> frame) {
  const size_t n = frame.size();
  schedule({t_us, std::move(frame), n, false});
}

void ZforceModel::load_trace(const std::vector<SensorSample>& trace, const SecondFinger* second) {
  bool down = false;
  uint32_t last_x = 0, last_y = 0;
  int second_state = 0;  // 0 not yet down, 1 down, 2 up
  for (const SensorSample& p : trace) {
    uint8_t ids[2], events[2];
    uint32_t xs[2], ys[2];
    int n = 0;
    int main_index = -1;
    if (p.touch) {
      to_sensor(p.x, p.y, last_x, last_y);
      main_index = n;
      ids[n] = 0;
      events[n] = down ? 1 : 0;
      xs[n] = last_x;
      ys[n++] = last_y;
      down = true;
    } else if (down) {
      main_index = n;
      ids[n] = 0;
      events[n] = 2;
      xs[n] = last_x;
      ys[n++] = last_y;
      down = false;
    }
    if (second != nullptr) {
      const bool inside = static_cast<int32_t>(p.t_us - second->from_us) >= 0 &&
                          static_cast<int32_t>(second->to_us - p.t_us) >= 0;
      uint8_t ev = 0xFF;
      if (inside) {
        ev = second_state == 0 ? 0 : 1;
        second_state = 1;
      } else if (second_state == 1) {
        ev = 2;
        second_state = 2;
      }
      if (ev != 0xFF) {
        ids[n] = 1;
        events[n] = ev;
        to_sensor(second->x, second->y, xs[n], ys[n]);
        ++n;
        if (second->listed_first && main_index == 0) {
          std::swap(ids[0], ids[1]);
          std::swap(events[0], events[1]);
          std::swap(xs[0], xs[1]);
          std::swap(ys[0], ys[1]);
        }
      }
    }
    if (n == 0) continue;
    std::vector<uint8_t> bytes = touch_frame(ids, events, xs, ys, n, p.t_us);
    const size_t size = bytes.size();
    schedule({p.t_us, std::move(bytes), size, true});
  }
}

namespace {

// A frame that would move the tracked finger (id 0) to (40, 40) sensor units
// if it got through.
std::vector<uint8_t> decoy(const ZforceModel& m, uint32_t t_us, uint8_t event = 1, uint32_t x = 40) {
  const uint8_t id = 0;
  const uint32_t y = 40;
  return m.touch_frame(&id, &event, &x, &y, 1, t_us);
}

}  // namespace

void ZforceModel::inject(uint32_t t_us, Fault f) {
  std::vector<uint8_t> bytes;
  switch (f) {
    case Fault::ImpossibleEvent: bytes = decoy(*this, t_us, 7); break;
    case Fault::OutOfRange: {
      const uint32_t limit = std::max<uint32_t>(resolution_x_, calibration_.range_x);
      bytes = decoy(*this, t_us, 1, limit + 100);
      break;
    }
    default: bytes = decoy(*this, t_us); break;
  }
  const size_t n = bytes.size();
  schedule({t_us, std::move(bytes), n, false});
  if (f != Fault::ImpossibleEvent && f != Fault::OutOfRange) corrupt_frame_at(t_us, f);
}

bool ZforceModel::corrupt_frame_at(uint32_t t_us, Fault f) {
  for (size_t i = current_ ? 1 : 0; i < queue_.size(); ++i) {
    Frame& fr = queue_[i];
    if (fr.due_us != t_us || fr.bytes.size() < 14 || fr.bytes[2] != kNotificationTag) continue;
    std::vector<uint8_t>& b = fr.bytes;
    switch (f) {
      case Fault::BadHeader: b[0] = 0x00; break;
      case Fault::Truncated:
        b.resize(b.size() - 3);
        b[1] = static_cast<uint8_t>(b.size() - 2);
        break;
      case Fault::CutShort: b[1] = static_cast<uint8_t>(b[1] + 6); break;
      case Fault::LengthOverMax:
        b.resize(2 + 200, 0x00);
        b[1] = 200;
        break;
      case Fault::UnknownTag: b[8] = 0xA5; break;         // [5] instead of touchNotifications [0]
      case Fault::MalformedLength: b[9] = 0x85; break;    // five length octets
      case Fault::ImpossibleEvent: b[13] = 7; break;      // first touch: id at 12, event at 13
      case Fault::OutOfRange: {
        // Rewrite the first touch's x (fields after id and event) beyond any resolution.
        if (options_.format.has(zforce::TouchField::X1)) b[14] = 0xFF;
        break;
      }
    }
    fr.declared = b.size();  // CutShort: the length byte promises more than this
    return true;
  }
  return false;
}

void ZforceModel::become_current() {
  while (!current_ && !queue_.empty() && static_cast<int32_t>(now_ - queue_.front().due_us) >= 0) {
    if (queue_.front().touch && !enabled_) {
      ++dropped_disabled_;  // the sensor does not report touches until enabled
      queue_.pop_front();
      continue;
    }
    current_ = true;
    read_pos_ = 0;
    const uint32_t due = queue_.front().due_us;
    edge_us_ = static_cast<int32_t>(due - free_since_) >= 0 ? due : free_since_;
    ++edges_;
  }
}

void ZforceModel::advance_to(uint32_t now_us) {
  now_ = now_us;
  become_current();
}

bool ZforceModel::asserted() const { return current_; }

bool ZforceModel::take_edge(uint32_t& t_us, uint32_t& edges) {
  if (edges_ == edges_taken_) return false;
  edges = edges_ - edges_taken_;
  edges_taken_ = edges_;
  t_us = edge_us_;
  return true;
}

BusStatus ZforceModel::on_read(uint8_t* data, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    if (!current_) {
      data[i] = 0xFF;
      ++overread_;
      continue;
    }
    Frame& f = queue_.front();
    data[i] = read_pos_ < f.bytes.size() ? f.bytes[read_pos_] : 0xFF;
    ++read_pos_;
    if (read_pos_ >= f.declared) {
      queue_.pop_front();
      current_ = false;
      free_since_ = now_;
      ++delivered_;
      // The rest of this read gets idle bytes; the next message raises DR anew.
      for (size_t j = i + 1; j < n; ++j) {
        data[j] = 0xFF;
        ++overread_;
      }
      become_current();
      return BusStatus::Ok;
    }
  }
  return BusStatus::Ok;
}

void ZforceModel::respond(const std::vector<uint8_t>& content) {
  std::vector<uint8_t> payload;
  put_item(payload, kResponseTag, content);
  std::vector<uint8_t> bytes = frame_of(payload);
  const size_t n = bytes.size();
  schedule({now_, std::move(bytes), n, false});
  become_current();
}

BusStatus ZforceModel::on_write(const uint8_t* d, size_t n) {
  ++requests_;
  auto reject = [this](const char* why) {
    ++rejected_;
    last_rejection_ = why;
    return BusStatus::Ok;  // the bytes were acknowledged; the sensor just ignores them
  };
  if (current_) return reject("request written while DR was high");
  if (n < 10 || d[0] != kStart || d[1] != n - 2) return reject("bad frame header or length");
  const uint8_t* p = d + 2;
  const size_t len = n - 2;
  if (p[0] != 0xEE || p[1] != len - 2) return reject("not a request");
  if (p[2] != kAddressTag || p[3] != 2) return reject("no device address");
  const uint8_t device_type = p[4];
  const uint8_t command = p[6];
  const size_t clen = p[7];
  if (clen != len - 8) return reject("command length");
  const uint8_t* c = p + 8;

  // The command's items as (tag, value) pairs.
  struct Item {
    uint8_t tag;
    uint32_t value;
  };
  std::vector<Item> items;
  for (size_t i = 0; i < clen;) {
    if (i + 2 > clen || i + 2 + c[i + 1] > clen) return reject("item overruns the command");
    uint32_t v = 0;
    if (c[i + 1] > 0 && !read_uint(c + i + 2, c[i + 1], v)) return reject("bad integer");
    items.push_back({c[i], v});
    i += 2u + c[i + 1];
  }

  std::vector<uint8_t> echo(c, c + clen);
  switch (command) {
    case 0x66: {  // touchFormat
      if (device_type != 0x02 || clen != 0) return reject("touchFormat");
      std::vector<uint8_t> bits{1, 0, 0, 0};  // 23 bits: 1 unused
      for (int i = 0; i < 23; ++i) {
        if ((options_.format.fields >> i) & 1u) bits[1 + i / 8] |= static_cast<uint8_t>(0x80u >> (i % 8));
      }
      echo.clear();
      put_item(echo, 0x41, bits);
      break;
    }
    case 0x65:  // enable
      if (device_type != 0x02 || items.size() != 1) return reject("enable");
      if (items[0].tag == 0x81) {
        enabled_ = true;
      } else if (items[0].tag == 0x80) {
        enabled_ = false;
      } else {
        return reject("enable item");
      }
      break;
    case 0x67:  // operationMode
      for (const Item& it : items) {
        if (it.tag == 0x80) detection_ = it.value != 0;
      }
      break;
    case 0x68:  // frequency, platform device
      if (device_type != 0x00) return reject("frequency addressed to a non-platform device");
      for (const Item& it : items) {
        if (it.tag == 0x80) finger_hz_ = static_cast<uint16_t>(it.value);
        if (it.tag == 0x82) idle_hz_ = static_cast<uint16_t>(it.value);
      }
      break;
    case 0x69:  // resolution
      for (const Item& it : items) {
        if (it.tag == 0x80) resolution_x_ = static_cast<uint16_t>(it.value);
        if (it.tag == 0x81) resolution_y_ = static_cast<uint16_t>(it.value);
      }
      break;
    case 0x73:  // deviceConfiguration
      for (const Item& it : items) {
        if (it.tag == 0x86) reported_touches_ = static_cast<uint8_t>(it.value);
      }
      break;
    default:
      return reject("unknown command");
  }
  if (!options_.answer_requests) return BusStatus::Ok;
  std::vector<uint8_t> content{kAddressTag, 2, device_type, p[5]};
  put_item(content, command, echo);
  respond(content);
  return BusStatus::Ok;
}

}  // namespace ff::emulated
