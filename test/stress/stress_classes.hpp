#pragma once
// The stress set: one class per kind of input the plate must survive. The
// gtest suites and ff-stress-report run the same classes, so the report's
// numbers are the tests' numbers with more cases.
#include <cstdint>
#include <string>
#include <vector>

namespace ff::stress {

// Float32 rendering against the double reference at the same position and
// direction, closed-form scenes (see docs/stress.md for the measured worst).
constexpr double kRenderingBound = 2e-3;
// Ticks (500 us) after the last bad input until the output agrees again with
// a run that never saw it (same presence, position within 0.5 px, amplitude
// within kRecoveryAmplitudeTolerance) for good.
constexpr int64_t kRecoveryBoundTicks = 600;
constexpr double kRecoveryAmplitudeTolerance = 0.05;
// The core's max|G| search (coarse scan + compass search) against a double
// 4 px scan with refinement, relative: it may miss a corner peak slightly.
constexpr double kMaxGradientBound = 2e-2;

struct ClassResult {
  std::string name;
  int cases = 0;
  uint64_t ticks = 0;
  int failures = 0;
  double worst_rendering = 0.0;  // max |A_float - A_double|, closed-form scenes
  double worst_table = 0.0;      // the same for table scenes (tabulation error; not a failure)
  int64_t worst_recovery = 0;    // ticks
  double worst_max_gradient_error = 0.0;  // relative, the core's max|G| search against the double scan
  std::string first_failure;     // with the seed that reproduces it
  std::string note;              // class-specific measurement
};

struct StressClass {
  const char* name;
  const char* what;
  bool known_bug;  // fails until the core is fixed: a DISABLED_ test, a report row with failures
  ClassResult (*run)(uint64_t base_seed, int cases);
};

const std::vector<StressClass>& stress_classes();
const StressClass* find_class(const std::string& name);

// The reproduction hint printed with every failure.
std::string reproduce_hint(uint64_t seed, const char* class_name);

}  // namespace ff::stress
