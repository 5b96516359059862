#include "trace_writer.hpp"

#include <cmath>
#include <cstdio>
#include <ostream>

namespace ff::tracegen {

namespace {
constexpr uint64_t kTickUs = 500;
}

std::string format_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0.0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  std::string s(buf);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

void write_trace(std::ostream& out, const GeneratedTrace& trace, bool with_events) {
  const bool tremor = trace.tremor.enabled();
  out << "t_us,x,y,touch,x_true,y_true" << (tremor ? ",x_tremor,y_tremor" : "") << (with_events ? ",event" : "") << '\n';
  for (const TraceSample& s : trace.samples) {
    out << s.t_us << ',' << format_number(s.x) << ',' << format_number(s.y) << ',' << (s.touch ? 1 : 0) << ','
        << format_number(s.x_true) << ',' << format_number(s.y_true);
    if (tremor) {
      const Point shake = trace.tremor_at(s.t_us);
      out << ',' << format_number(shake.x) << ',' << format_number(shake.y);
    }
    if (with_events) out << ',' << to_string(s.event);
    out << '\n';
  }
}

uint64_t write_truth_ticks(std::ostream& out, const GeneratedTrace& trace, const Progress& progress) {
  const bool tremor = trace.tremor.enabled();
  out << "t_us,x_true,y_true,vx_true,vy_true,touch" << (tremor ? ",x_tremor,y_tremor" : "") << '\n';
  if (trace.samples.empty()) return 0;
  const uint64_t t0 = trace.samples.front().t_us;
  const uint64_t span = trace.end_us() > t0 ? trace.end_us() - t0 : 0;
  const uint64_t last = (span + kTickUs - 1) / kTickUs;
  const uint64_t report_every = last / 100 + 1;
  for (uint64_t k = 0; k <= last; ++k) {
    const uint64_t t = t0 + k * kTickUs;
    const TrueState s = trace.truth_at(t);
    const double nan = std::nan("");
    out << t << ',' << format_number(s.touching ? s.position.x : nan) << ','
        << format_number(s.touching ? s.position.y : nan) << ',' << format_number(s.velocity.x) << ','
        << format_number(s.velocity.y) << ',' << (s.touching ? 1 : 0);
    if (tremor) {
      const Point shake = trace.tremor_at(t);
      out << ',' << format_number(shake.x) << ',' << format_number(shake.y);
    }
    out << '\n';
    if (progress && k % report_every == 0) progress(static_cast<double>(k) / static_cast<double>(last + 1));
  }
  if (progress) progress(1.0);
  return last + 1;
}

}  // namespace ff::tracegen
