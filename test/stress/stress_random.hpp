#pragma once
// The stress suite's seeds (random numbers: test/support/random.hpp) and the
// environment knobs that reproduce a failure: FF_STRESS_SEED (base seed,
// decimal or 0x-hex) and FF_STRESS_CASES (cases per class).
#include <cstdint>
#include <cstdlib>

#include "support/random.hpp"

namespace ff::stress {

constexpr uint64_t kDefaultSeed = 0x5eed2022u;

using Rng = support::Random;  // one stream per case seed

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
