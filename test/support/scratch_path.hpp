// A file name in the test's temporary directory that no other process uses:
// the native and the sanitizer test runs, or a deletion sweep beside a
// developer's build, may run the same test at the same moment.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

namespace ff::support {

inline std::string scratch_path(const std::string& name) {
  return ::testing::TempDir() + "ff_" + std::to_string(::getpid()) + "_" + name;
}

}  // namespace ff::support
