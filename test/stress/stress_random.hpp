#pragma once
// Seeded, platform-independent random numbers for the stress suite, and the
// environment knobs that reproduce a failure: FF_STRESS_SEED (base seed,
// decimal or 0x-hex) and FF_STRESS_CASES (cases per class).
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace ff::stress {

constexpr uint64_t kDefaultSeed = 0x5eed2022u;

inline uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// xoshiro-free and tiny: splitmix64 as a counter-based generator is plenty
// for test inputs and is identical on every platform.
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(splitmix64(seed)) {}
  uint64_t next() { return splitmix64(state_++); }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  double log_uniform(double lo, double hi) { return lo * std::exp(std::log(hi / lo) * uniform()); }
  int integer(int lo, int hi) {  // [lo, hi]
    const uint64_t span = static_cast<uint64_t>(static_cast<int64_t>(hi) - lo) + 1u;
    return lo + static_cast<int>(next() % span);
  }
  bool chance(double p) { return uniform() < p; }
  double gaussian() {  // Box-Muller, one value per call
    const double u1 = 1.0 - uniform();
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
  }
  template <typename T, size_t N>
  const T& pick(const T (&items)[N]) { return items[next() % N]; }

 private:
  uint64_t state_;
};

// Base seed: FF_STRESS_SEED if set, else kDefaultSeed. Case i of a class runs
// with seed base + i, so a failing case is rerun alone with
// FF_STRESS_SEED=<its seed> FF_STRESS_CASES=1.
inline uint64_t base_seed() {
  const char* s = std::getenv("FF_STRESS_SEED");
  return s != nullptr && *s != '\0' ? std::strtoull(s, nullptr, 0) : kDefaultSeed;
}

inline int cases_or(int fallback) {
  const char* s = std::getenv("FF_STRESS_CASES");
  if (s == nullptr || *s == '\0') return fallback;
  const long n = std::strtol(s, nullptr, 0);
  return n > 0 ? static_cast<int>(n) : fallback;
}

}  // namespace ff::stress
