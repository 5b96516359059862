#pragma once
// The project's one source of test randomness (trace generation, the stress
// suite, the benches): the same numbers for the same seed on every platform.
// std::mt19937_64 is fully specified by the standard, the <random>
// distributions are not, so the few we need are written out here.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>

namespace ff::support {

// Independent streams from one user seed (motion, timing, noise, faults), so
// that changing the noise level leaves the finger's motion untouched. Each
// optional effect of the trace models draws from its own stream, so that
// switching one on leaves the others' draws (and, all off, the trace) unchanged.
enum class Stream : uint64_t {
  Single = 0,
  Motion = 1,
  Timing = 2,
  Noise = 3,
  Faults = 4,
  SlowStrokes = 5,
  Hesitations = 6,
  Reversals = 7,
  Tremor = 8,
  Latency = 9,
  PeriodJitter = 10,
  CorrelatedNoise = 11,
  Drift = 12,
};

inline uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

class Random {
 public:
  explicit Random(uint64_t seed, Stream stream = Stream::Single)
      : engine_(splitmix64(seed ^ splitmix64(static_cast<uint64_t>(stream)))) {}

  uint64_t next() { return engine_(); }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Log-uniform in [lo, hi], lo > 0: as many slow strokes as fast ones per octave.
  double log_uniform(double lo, double hi) { return lo * std::exp(std::log(hi / lo) * uniform()); }
  // Integer in [lo, hi].
  int integer(int lo, int hi) {
    const uint64_t span = static_cast<uint64_t>(static_cast<int64_t>(hi) - lo) + 1u;
    return lo + static_cast<int>(engine_() % span);
  }
  bool chance(double p) { return uniform() < p; }
  // Standard normal (Box-Muller; the second value is kept for the next call).
  double gaussian() {
    if (have_spare_) {
      have_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double a = 2.0 * 3.14159265358979323846 * u2;
    spare_ = r * std::sin(a);
    have_spare_ = true;
    return r * std::cos(a);
  }
  template <typename T, size_t N>
  const T& pick(const T (&items)[N]) {
    return items[engine_() % N];
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool have_spare_ = false;
};

}  // namespace ff::support
