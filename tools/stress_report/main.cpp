// ff-stress-report: runs every stress class (test/stress/stress_classes.hpp)
// with more cases than the unit tests, the three-hour long runs and the
// float32-vs-double measurements, and prints the results as Markdown tables
// for docs/stress.md (scripts/stress-report puts them there).
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <string>

#include "frictionfield/host/cli_conventions.hpp"
#include "stress_classes.hpp"
#include "stress_long_run.hpp"
#include "stress_precision.hpp"
#include "stress_random.hpp"

namespace {

std::string with_commas(unsigned long long v) {
  std::string s = std::to_string(v);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(static_cast<size_t>(i), ",");
  return s;
}

// Markdown table cells: pipes escaped, one line.
std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += "\\|";
    else out += c == '\n' ? ' ' : c;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Runs the stress suite at scale and prints the report tables (Markdown)."};
  int cases = 100;
  uint64_t seed = ff::stress::base_seed();
  uint64_t long_seconds = 10800;
  std::string only;
  app.add_option("--cases", cases, "cases per input class")->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "base seed (case i of a class runs with seed + i)");
  app.add_option("--long-run-seconds", long_seconds, "simulated length of each long run (rounded up to whole minutes)");
  app.add_option("--class", only, "run only this class");
  if (const int code = ff::host::parse_command_line(app, argc, argv); code >= 0) return code;

  using clock = std::chrono::steady_clock;
  const auto started = clock::now();
  std::printf("Seed %llu, %d cases per class (long rests: %d). Reproduce a failing case with the "
              "`FF_STRESS_SEED=... FF_STRESS_CASES=1` printed for it.\n\n",
              static_cast<unsigned long long>(seed), cases, (cases + 5) / 6);
  std::printf("| input class | what | cases | ticks | failures | worst \\|A_f32 - A_f64\\| | worst recovery (ticks) | class measure |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---|\n");
  int total_failures = 0;   // failing cases and long runs
  int failing_classes = 0;  // input classes with a failing case, and failing long runs
  std::string failures_text;
  for (const ff::stress::StressClass& c : ff::stress::stress_classes()) {
    if (!only.empty() && only != c.name) continue;
    const int n = std::string(c.name) == "long_rest_then_move" ? (cases + 5) / 6 : cases;
    const ff::stress::ClassResult r = c.run(seed, n);
    total_failures += r.failures;
    failing_classes += r.failures > 0 ? 1 : 0;
    std::string measure = r.note;
    if (r.worst_table > 0.0) {
      char buf[80];
      std::snprintf(buf, sizeof buf, "%stable scenes vs closed form: %.3g", measure.empty() ? "" : "; ", r.worst_table);
      measure += buf;
    }
    if (r.worst_max_gradient_error > 1e-6 && std::string(c.name) != "max_gradient_search") {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%smax|G| rel. error %.2g", measure.empty() ? "" : "; ", r.worst_max_gradient_error);
      measure += buf;
    }
    std::printf("| `%s` | %s | %d | %s | %d | %.2g | %lld | %s |\n", c.name, escape(c.what).c_str(), r.cases,
                with_commas(r.ticks).c_str(), r.failures, r.worst_rendering, static_cast<long long>(r.worst_recovery),
                escape(measure).c_str());
    std::fflush(stdout);
    if (r.failures > 0) failures_text += "- " + escape(r.first_failure) + "\n";
  }
  if (!only.empty()) return total_failures == 0 ? 0 : 1;

  std::printf("\n| long run (%s s simulated, 2 kHz, finger down throughout, the 32-bit clock wraps at 30 s, 71.6 and 143.2 min) "
              "| ticks | bad ticks | worst rest offset (px) | stroke error max, first / worst minute (px) | mean, first / worst (px) | "
              "ns per tick |\n|---|---:|---:|---:|---:|---:|---:|\n", with_commas(long_seconds).c_str());
  const struct {
    const char* name;
    ff::TrackerConfig config;
  } trackers[] = {{"recommended tracker", ff::TrackerConfig::recommended()}, {"thesis tracker", ff::TrackerConfig::thesis()}};
  for (const auto& t : trackers) {
    const ff::stress::LongRunResult r = ff::stress::long_run(t.config, long_seconds, seed);
    const bool ok = r.bad_ticks == 0 && r.worst_rest_offset <= 0.1 && r.worst_max_error <= r.first_max_error + 1e-3 &&
                    r.worst_mean_error <= r.first_mean_error + 1e-3;
    total_failures += ok ? 0 : 1;
    failing_classes += ok ? 0 : 1;
    std::printf("| %s | %s | %llu | %.2g | %.3f / %.3f | %.3f / %.3f | %.0f |\n", t.name, with_commas(r.ticks).c_str(),
                static_cast<unsigned long long>(r.bad_ticks), r.worst_rest_offset, r.first_max_error, r.worst_max_error,
                r.first_mean_error, r.worst_mean_error, r.wall_seconds * 1e9 / static_cast<double>(r.ticks));
    std::fflush(stdout);
  }

  const ff::stress::RenderingPrecision rp = ff::stress::rendering_precision(seed, cases * 10);
  const ff::stress::ChainPrecision cp = ff::stress::thesis_chain_precision(seed, cases);
  std::printf("\n| float32 against the double reference | samples | worst deviation |\n|---|---:|---|\n");
  std::printf("| closed-form rendering, %d random scenes (same position, direction and max\\|G\\|) | %s points | amplitude %.2g |\n",
              rp.scenes, with_commas(rp.evaluations).c_str(), rp.worst_amplitude);
  std::printf("| max\\|G\\| search: the thesis' scenes / random general scenes | %d scenes | relative %.2g / %.2g |\n", rp.scenes,
              rp.worst_max_builtin, rp.worst_max_general);
  std::printf("| thesis chain end to end (spec.md#thesis-tracker + heightmap), %d traces | %s ticks (%s moving >= 50 px/s) | "
              "position %.2g px, amplitude %.2g (moving) |\n", cp.traces, with_commas(cp.ticks).c_str(),
              with_commas(cp.moving_ticks).c_str(), cp.worst_position, cp.worst_amplitude);

  const double wall = std::chrono::duration<double>(clock::now() - started).count();
  // Cases and classes apart: "3 failing classes" once meant three cases of one class.
  std::printf("\n%d failing case%s in %d class%s; report computed in %.0f s.\n", total_failures,
              total_failures == 1 ? "" : "s", failing_classes, failing_classes == 1 ? "" : "es", wall);
  if (!failures_text.empty()) std::printf("\nFirst failure of each failing class:\n\n%s", failures_text.c_str());
  return total_failures == 0 ? 0 : 1;
}
