#include "frictionfield/host/trace_csv.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>

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

bool parse_float(const std::string& text, float& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  const float v = std::strtof(text.c_str(), &end);  // accepts nan, inf, overflow -> inf
  if (end == text.c_str() || end != text.c_str() + text.size()) return false;
  out = v;
  return true;
}

}  // namespace

std::string TraceError::to_string(const std::string& file) const {
  std::ostringstream s;
  s << file;
  if (line > 0) s << ':' << line;
  if (column > 0) s << ':' << column;
  s << ": " << message;
  return s.str();
}

bool read_sensor_trace(std::istream& in, std::vector<TraceRow>& rows, TraceError& error) {
  std::string line;
  size_t line_no = 0;
  if (!std::getline(in, line)) {
    error = {1, 0, "empty file: expected a header row 't_us,x,y,touch'"};
    return false;
  }
  ++line_no;
  const std::vector<std::string> header = split(line);
  int col_t = -1, col_x = -1, col_y = -1, col_touch = -1;
  for (size_t i = 0; i < header.size(); ++i) {
    const std::string name = trim(header[i]);
    const int c = static_cast<int>(i);
    if (name == "t_us") col_t = c;
    else if (name == "x") col_x = c;
    else if (name == "y") col_y = c;
    else if (name == "touch") col_touch = c;
  }
  if (col_t < 0 || col_x < 0 || col_y < 0 || col_touch < 0) {
    error = {1, 0, "header must name the columns t_us, x, y and touch (got '" + trim(line) + "')"};
    return false;
  }
  const size_t needed = static_cast<size_t>(std::max(std::max(col_t, col_x), std::max(col_y, col_touch))) + 1;

  while (std::getline(in, line)) {
    ++line_no;
    if (trim(line).empty()) continue;
    const std::vector<std::string> f = split(line);
    if (f.size() < needed) {
      error = {line_no, f.size() + 1, "expected at least " + std::to_string(needed) + " fields, got " +
                                          std::to_string(f.size())};
      return false;
    }
    TraceRow row;
    if (!parse_u64(trim(f[col_t]), row.t_us)) {
      error = {line_no, static_cast<size_t>(col_t) + 1, "t_us must be a non-negative integer (got '" + trim(f[col_t]) + "')"};
      return false;
    }
    uint64_t touch = 0;
    if (!parse_u64(trim(f[col_touch]), touch) || touch > 1) {
      error = {line_no, static_cast<size_t>(col_touch) + 1, "touch must be 0 or 1 (got '" + trim(f[col_touch]) + "')"};
      return false;
    }
    row.touch = touch == 1;
    // Without a finger x and y are ignored, so they may be empty.
    const std::string xs = trim(f[col_x]), ys = trim(f[col_y]);
    if (!parse_float(xs, row.x) && (row.touch || !xs.empty())) {
      error = {line_no, static_cast<size_t>(col_x) + 1, "x is not a number (got '" + xs + "')"};
      return false;
    }
    if (!parse_float(ys, row.y) && (row.touch || !ys.empty())) {
      error = {line_no, static_cast<size_t>(col_y) + 1, "y is not a number (got '" + ys + "')"};
      return false;
    }
    rows.push_back(row);
  }
  return true;
}

bool read_sensor_trace_file(const std::string& path, std::vector<TraceRow>& rows, TraceError& error) {
  std::ifstream in(path);
  if (!in) {
    error = {0, 0, std::string("cannot open: ") + std::strerror(errno)};
    return false;
  }
  return read_sensor_trace(in, rows, error);
}

void write_replay_header(std::ostream& out) { out << "t_us,x,y,vx,vy,amplitude,dac\n"; }

void write_replay_row(std::ostream& out, uint64_t t_us, const TickOutput& t) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%llu,%.3f,%.3f,%.5f,%.5f,%.6f,%u\n", static_cast<unsigned long long>(t_us),
                static_cast<double>(t.position.x), static_cast<double>(t.position.y),
                static_cast<double>(t.direction.x), static_cast<double>(t.direction.y),
                static_cast<double>(t.amplitude), static_cast<unsigned>(t.dac));
  out << buf;
}

}  // namespace ff::host
