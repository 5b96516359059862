// Fault counters: counted per kind, saturating, and read whole by snapshot().
#include "frictionfield/core/fault_counters.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace ff {
namespace {

TEST(FaultCounters, CountEachKindAndSaturateInsteadOfWrapping) {
  FaultCounters f;
  f.add(Fault::TouchDown);
  f.add(Fault::TouchDown);
  f.add(Fault::LiftOff);
  EXPECT_EQ(f[Fault::TouchDown], 2u);
  EXPECT_EQ(f[Fault::LiftOff], 1u);
  EXPECT_EQ(f[Fault::OffScreen], 0u);
  EXPECT_EQ(f.total(), 3u);
  f.count[static_cast<int>(Fault::OffScreen)] = UINT32_MAX - 1;
  f.add(Fault::OffScreen);
  f.add(Fault::OffScreen);
  EXPECT_EQ(f[Fault::OffScreen], UINT32_MAX);
}

TEST(FaultCounters, ASnapshotHoldsEveryCounter) {
  FaultCounters f;
  for (int i = 0; i < static_cast<int>(Fault::kCount); ++i)
    for (int n = 0; n <= i; ++n) f.add(static_cast<Fault>(i));
  const FaultCounters s = f.snapshot();
  for (int i = 0; i < static_cast<int>(Fault::kCount); ++i) EXPECT_EQ(s.count[i], static_cast<uint32_t>(i + 1)) << i;
  f.add(Fault::TouchDown);  // a copy, not a view
  EXPECT_EQ(s[Fault::TouchDown], f[Fault::TouchDown] - 1);
}

}  // namespace
}  // namespace ff
