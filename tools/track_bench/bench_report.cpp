#include "bench_report.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <ostream>
#include <sstream>

#include "frictionfield/host/output_file.hpp"

namespace ff::bench {

namespace {
std::string begin_marker(const std::string& marker) { return "<!-- " + marker + ":begin -->"; }
std::string end_marker(const std::string& marker) { return "<!-- " + marker + ":end -->"; }
}  // namespace

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::vector<GoalCheck> check_goal(const std::vector<ReportRow>& rows, const std::string& default_config) {
  std::vector<GoalCheck> checks;
  if (rows.empty()) return checks;
  const std::string& baseline = rows.front().config;
  for (const ReportRow& base : rows) {
    if (base.config != baseline) continue;
    for (const ReportRow& r : rows) {
      if (r.config != default_config || r.noise != base.noise) continue;
      GoalCheck g;
      g.noise = r.noise;
      g.heightmap_ratio = r.metrics.heightmap_rms / base.metrics.heightmap_rms;
      g.lag_ms = r.metrics.lag_ms;
      g.frictionmap_ratio = r.metrics.frictionmap_rms / base.metrics.frictionmap_rms;
      if (base.metrics.moving_ticks == 0 || r.metrics.moving_ticks == 0)
        g.not_judged = "no ticks while the finger moves";
      else if (!(base.metrics.heightmap_rms > 0.0 && base.metrics.frictionmap_rms > 0.0))
        g.not_judged = "the baseline's amplitude error is 0";
      checks.push_back(g);
    }
  }
  return checks;
}

std::string generated_set_description(double duration_s) {
  return "6 generated traces of " + fixed(duration_s, 0) + " s";
}

void write_report(std::ostream& out, const std::vector<ReportRow>& rows, const std::string& set_description,
                  double moving_speed_px_s) {
  out << "| tracker | noise | pos RMSE px | pos p95 px | lag ms | dir err mean ° | dir err p95 ° "
         "| HM amp RMS | HM amp p95 | FM amp RMS | FM amp p95 | HM at rest RMS | ns/tick |\n";
  out << "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const ReportRow& r : rows) {
    const Metrics& m = r.metrics;
    out << "| " << r.config << " | " << r.noise << " | " << fixed(m.position_rmse_px, 2) << " | "
        << fixed(m.position_p95_px, 2) << " | " << fixed(m.lag_ms, 2) << " | " << fixed(m.direction_mean_deg, 1) << " | "
        << fixed(m.direction_p95_deg, 1) << " | " << fixed(m.heightmap_rms, 3) << " | " << fixed(m.heightmap_p95, 3)
        << " | " << fixed(m.frictionmap_rms, 3) << " | " << fixed(m.frictionmap_p95, 3) << " | "
        << fixed(m.heightmap_rest_rms, 3) << " | " << fixed(m.ns_per_tick, 0) << " |\n";
  }
  out << "\n";
  if (!rows.empty()) {
    const Metrics& m = rows.front().metrics;
    out << "Each row: " << set_description << " (" << m.moving_ticks << " ticks while moving above "
        << fixed(moving_speed_px_s * 0.2, 0) << " mm/s, " << m.rest_ticks << " at rest); "
        << (rows.front().noise == "recorded" ? "noise: what the files hold"
                                             : "noise low = 1 px, high = 2.5 px (1 sigma per axis)")
        << "; amplitudes on the raw 0..1 scale (strength 1).\n\n";
  }
  // The goal for the default and for the proposals.
  std::vector<std::string> candidates;
  for (const ReportRow& r : rows) {
    const bool proposal = r.config == "recommended()" || r.config.rfind("kalman tuned", 0) == 0 ||
                          r.config.rfind("candidate", 0) == 0;
    if (proposal && std::find(candidates.begin(), candidates.end(), r.config) == candidates.end())
      candidates.push_back(r.config);
  }
  for (const std::string& name : candidates) {
    for (const GoalCheck& g : check_goal(rows, name)) {
      if (!g.not_judged.empty()) {
        out << "Goal (" << g.noise << " noise): " << name << ": not judged: " << g.not_judged << ".\n";
        continue;
      }
      out << "Goal (" << g.noise << " noise): " << name << ": heightmap error " << fixed(100.0 * g.heightmap_ratio, 0)
          << " % of the thesis pipeline's (<= 50 %), lag " << fixed(g.lag_ms, 2) << " ms (<= 2), frictionmap error "
          << fixed(100.0 * g.frictionmap_ratio, 0) << " % of the thesis pipeline's (<= 100 %): "
          << (g.met() ? "met" : "NOT met") << ".\n";
    }
  }
}

std::string replace_marked_text(const std::string& document, const std::string& text, const std::string& marker) {
  const std::string kBegin = begin_marker(marker), kEnd = end_marker(marker);
  const std::string block = kBegin + "\n" + text + kEnd;
  const size_t begin = document.find(kBegin);
  const size_t end = begin == std::string::npos ? std::string::npos : document.find(kEnd, begin);
  if (begin == std::string::npos || end == std::string::npos) {
    std::string out = document;
    if (!out.empty() && out.back() != '\n') out += '\n';
    return out + block + "\n";
  }
  return document.substr(0, begin) + block + document.substr(end + kEnd.size());
}

bool replace_marked_section(const std::string& path, const std::string& text, std::string& error,
                            const std::string& marker) {
  std::string document;
  {
    std::ifstream in(path);
    if (in) {
      std::ostringstream s;
      s << in.rdbuf();
      document = s.str();
    }
  }
  // Atomically: a killed or failed run leaves the document as it was.
  return host::write_file_atomically(path, replace_marked_text(document, text, marker), error);
}

}  // namespace ff::bench
