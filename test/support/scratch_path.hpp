// A file name in this test process's own scratch folder: the native and the
// sanitizer test runs, or a deletion sweep beside a developer's build, may run
// the same test at the same moment. The folder is emptied when the process
// first asks for it (a reused pid must not find an earlier run's files) and
// removed at exit when every test passed (kept for a look when one failed).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace ff::support {

class ScratchFolder {
 public:
  ScratchFolder() : path_(::testing::TempDir() + "ff_" + std::to_string(::getpid())) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchFolder() {
    // gtest's UnitTest lives on the heap and is never destroyed, so it can be
    // asked here, during static destruction.
    if (::testing::UnitTest::GetInstance()->Passed()) {
      std::error_code ignored;
      std::filesystem::remove_all(path_, ignored);
    }
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

inline std::string scratch_path(const std::string& name) {
  static const ScratchFolder folder;
  return folder.path() + "/" + name;
}

}  // namespace ff::support
