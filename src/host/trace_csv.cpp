#include "frictionfield/host/trace_csv.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>

#include "frictionfield/host/input_file.hpp"

namespace ff::host {

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream s(line);
  while (std::getline(s, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::string trim(std::string s) {
  const char* ws = " \t\r\n";
  s.erase(0, s.find_first_not_of(ws));
  s.erase(s.find_last_not_of(ws) + 1);
  return s;
}

bool parse_u64(const std::string& text, uint64_t& out) {
  if (text.empty() || text[0] == '-' || text[0] == '+') return false;
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (errno != 0 || end == text.c_str() || end != text.c_str() + text.size()) return false;
  out = v;
  return true;
}

bool parse_float(const std::string& text, float& out) {  // "" parses nothing: end stays at the start
  char* end = nullptr;
  const float v = std::strtof(text.c_str(), &end);  // accepts nan, inf, overflow -> inf
  if (end == text.c_str() || end != text.c_str() + text.size()) return false;
  out = v;
  return true;
}

// Metadata before the header that a reader keeps: every tool writes fewer.
constexpr size_t kMaxLeadingComments = 64;

}  // namespace

std::string TraceError::to_string(const std::string& file) const {
  std::ostringstream s;
  s << file;
  if (line > 0) s << ':' << line;
  if (column > 0) s << ':' << column;
  s << ": " << message;
  return s.str();
}

bool SensorTraceReader::next_data_line(std::string& line) {
  while (std::getline(in_, line)) {
    ++line_no_;
    if (line_no_ == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);  // UTF-8 BOM
    const std::string t = trim(line);
    if (!t.empty() && t[0] == '#' && names_.empty() && leading_comments_.size() < kMaxLeadingComments) {
      leading_comments_.push_back(t);
    }
    if (t.empty() || t[0] == '#') continue;  // blank lines and metadata
    return true;
  }
  return false;
}

bool SensorTraceReader::read_header(TraceError& error) {
  std::string line;
  if (!next_data_line(line)) {
    error = {line_no_ + (line_no_ == 0 ? 1 : 0), 0, "empty file: expected a header row 't_us,x,y,touch'"};
    return false;
  }
  names_ = split(line);
  for (size_t i = 0; i < names_.size(); ++i) {
    const std::string& name = names_[i] = trim(names_[i]);
    // Named twice, the last would win silently: a file merged by hand.
    if (!name.empty() && std::find(names_.begin(), names_.begin() + static_cast<long>(i), name) !=
                             names_.begin() + static_cast<long>(i)) {
      error = {line_no_, i + 1, "column '" + name + "' is named twice in the header"};
      return false;
    }
    const int c = static_cast<int>(i);
    if (name == "t_us") col_t_ = c;
    else if (name == "x") col_x_ = c;
    else if (name == "y") col_y_ = c;
    else if (name == "touch") col_touch_ = c;
    else if (name == "x_true") col_x_true_ = c;
    else if (name == "y_true") col_y_true_ = c;
    else if (name == "taken_us") col_taken_ = c;
  }
  if (col_t_ < 0 || col_x_ < 0 || col_y_ < 0 || col_touch_ < 0) {
    error = {line_no_, 0, "header must name the columns t_us, x, y and touch (got '" + trim(line) + "')"};
    return false;
  }
  needed_ = static_cast<size_t>(std::max(std::max(col_t_, col_x_), std::max(col_y_, col_touch_))) + 1;
  return true;
}

bool SensorTraceReader::next(TraceRow& row, TraceError& error, TruthPoint* truth) {
  error = {};
  std::string line;
  if (!next_data_line(line)) return false;
  if (parse_row(line, row, error, truth)) return true;
  // getline stopped at the end of the file, not at a newline: a write cut short.
  if (in_.eof())
    error.message +=
        " (the last line, without its end: a recording cut short? delete it to read the rest)";
  return false;
}

bool SensorTraceReader::parse_row(const std::string& line, TraceRow& row, TraceError& error, TruthPoint* truth) {
  const std::vector<std::string> f = split(line);
  if (f.size() < needed_) {
    error = {line_no_, f.size() + 1,
             "expected at least " + std::to_string(needed_) + " fields, got " + std::to_string(f.size())};
    return false;
  }
  if (f.size() > names_.size()) {  // misaligned: a column the header does not name
    error = {line_no_, names_.size() + 1,
             "more fields than the header names (" + std::to_string(names_.size()) + "), got " +
                 std::to_string(f.size())};
    return false;
  }
  row = TraceRow{};
  row.line = line_no_;
  const std::string ts = trim(f[col_t_]), touchs = trim(f[col_touch_]);
  if (!parse_u64(ts, row.t_us)) {
    error = {line_no_, static_cast<size_t>(col_t_) + 1, "t_us must be a non-negative integer (got '" + ts + "')"};
    return false;
  }
  if (row.t_us > kMaxTraceTimeUs) {
    error = {line_no_, static_cast<size_t>(col_t_) + 1,
             "t_us must be at most 2^53 = " + std::to_string(kMaxTraceTimeUs) + " (got '" + ts + "')"};
    return false;
  }
  uint64_t touch = 0;
  if (!parse_u64(touchs, touch) || touch > 1) {
    error = {line_no_, static_cast<size_t>(col_touch_) + 1, "touch must be 0 or 1 (got '" + touchs + "')"};
    return false;
  }
  row.touch = touch == 1;
  // Without a finger x and y are ignored, so they may be empty.
  const std::string xs = trim(f[col_x_]), ys = trim(f[col_y_]);
  if (!parse_float(xs, row.x) && (row.touch || !xs.empty())) {
    error = {line_no_, static_cast<size_t>(col_x_) + 1, "x is not a number (got '" + xs + "')"};
    return false;
  }
  if (!parse_float(ys, row.y) && (row.touch || !ys.empty())) {
    error = {line_no_, static_cast<size_t>(col_y_) + 1, "y is not a number (got '" + ys + "')"};
    return false;
  }
  if (col_taken_ >= 0) {
    const std::string taken = static_cast<size_t>(col_taken_) < f.size() ? trim(f[col_taken_]) : std::string();
    uint64_t v = 0;
    if (taken == "-1") {
      row.taken_us = -1;
    } else if (parse_u64(taken, v) && v <= kMaxTraceTimeUs) {
      row.taken_us = static_cast<int64_t>(v);
    } else {
      error = {line_no_, static_cast<size_t>(col_taken_) + 1,
               "taken_us must be a time in us or -1 (got '" + taken + "')"};
      return false;
    }
  }
  if (truth != nullptr) {
    *truth = TruthPoint{};
    float tx = 0.0f, ty = 0.0f;
    if (has_truth() && f.size() > static_cast<size_t>(std::max(col_x_true_, col_y_true_)) &&
        parse_float(trim(f[col_x_true_]), tx) && parse_float(trim(f[col_y_true_]), ty)) {
      truth->x = static_cast<double>(tx);
      truth->y = static_cast<double>(ty);
    }
  }
  return true;
}

std::string SensorTraceReader::metadata(const std::string& key) const {
  for (const std::string& c : leading_comments_) {
    const std::string text = trim(c.substr(1));
    if (text.compare(0, key.size(), key) != 0 || text.size() == key.size()) continue;
    const char after = text[key.size()];
    if (after == ' ' || after == ':') return trim(text.substr(key.size() + 1));
  }
  return "";
}

int SensorTraceReader::column(const std::string& name) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  return it == names_.end() ? -1 : static_cast<int>(it - names_.begin());
}

bool read_sensor_trace(std::istream& in, std::vector<TraceRow>& rows, TraceError& error) {
  SensorTraceReader reader(in);
  if (!reader.read_header(error)) return false;
  TraceRow row;
  while (reader.next(row, error)) rows.push_back(row);
  return error.message.empty();
}

bool read_sensor_trace_file(const std::string& path, std::vector<TraceRow>& rows, TraceError& error) {
  std::ifstream in;
  std::string why;
  if (!open_input_file(path, in, why)) {
    error = {0, 0, why};
    return false;
  }
  return read_sensor_trace(in, rows, error);
}

void write_replay_header(std::ostream& out) { out << "t_us,x,y,vx,vy,amplitude,dac,present\n"; }

void write_replay_row(std::ostream& out, uint64_t t_us, const TickOutput& t) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%llu,%.3f,%.3f,%.5f,%.5f,%.6f,%u,%d\n", static_cast<unsigned long long>(t_us),
                static_cast<double>(t.position.x), static_cast<double>(t.position.y),
                static_cast<double>(t.direction.x), static_cast<double>(t.direction.y),
                static_cast<double>(t.amplitude), static_cast<unsigned>(t.dac), t.present ? 1 : 0);
  out << buf;
}

void write_metadata(std::ostream& out, const Metadata& metadata) {
  for (const auto& [key, value] : metadata) {
    std::string v = value;
    for (char& c : v) if (c == '\n' || c == '\r') c = ' ';
    out << "# " << key << ": " << v << "\n";
  }
}

}  // namespace ff::host

