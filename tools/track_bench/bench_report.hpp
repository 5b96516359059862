#pragma once
// The benchmark's markdown table, the goal check of issue 3, and writing it
// into a document between markers.
#include <iosfwd>
#include <string>
#include <vector>

#include "tracking_evaluation.hpp"

namespace ff::bench {

struct ReportRow {
  std::string config;  // the first config in the rows is the baseline (thesis pipeline)
  std::string noise;   // "low" | "high"
  Metrics metrics;
};

// The default tracker ("recommended()") against the baseline, per noise level.
struct GoalCheck {
  std::string noise;
  double heightmap_ratio = 0.0;   // default / baseline heightmap RMS: goal <= 0.5
  double lag_ms = 0.0;            // goal <= 2
  double frictionmap_ratio = 0.0; // goal <= 1
  // Why the ratios mean nothing (no ticks while moving, a baseline without
  // error); empty when they do.
  std::string not_judged;
  bool met() const {
    return not_judged.empty() && heightmap_ratio <= 0.5 && lag_ms <= 2.0 && frictionmap_ratio <= 1.0;
  }
};
std::vector<GoalCheck> check_goal(const std::vector<ReportRow>& rows, const std::string& default_config);

// v with that many decimals ("%.*f"): the tables' number format.
std::string fixed(double v, int decimals);

// "6 generated traces of 30 s": what a row of the standard set averages over.
std::string generated_set_description(double duration_s);
void write_report(std::ostream& out, const std::vector<ReportRow>& rows, const std::string& set_description,
                  double moving_speed_px_s);

// Replaces the text between "<!-- MARKER:begin -->" and "<!-- MARKER:end -->"
// in the file (appends both if absent); MARKER is track-bench for the main
// table, track-bench-classes for the per-class one.
bool replace_marked_section(const std::string& path, const std::string& text, std::string& error,
                            const std::string& marker = "track-bench");
std::string replace_marked_text(const std::string& document, const std::string& text,
                                const std::string& marker = "track-bench");

}  // namespace ff::bench
