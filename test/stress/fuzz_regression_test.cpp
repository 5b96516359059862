// Every saved fuzz input (the seed corpus and each crash a fuzzer ever found,
// test/stress/corpus/<target>/) replayed through the fuzz targets' own
// checks, plus the bundled traces: a crash found once stays fixed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace ff::fuzz {
int trace_csv_one_input(const uint8_t* data, size_t size);
int scene_file_one_input(const uint8_t* data, size_t size);
}  // namespace ff::fuzz

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> out;
  if (!fs::exists(dir)) return out;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_regular_file()) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

template <typename Fn>
size_t replay_all(const fs::path& dir, Fn target) {
  size_t n = 0;
  for (const fs::path& p : files_in(dir)) {
    SCOPED_TRACE(p.string());
    const std::string b = bytes_of(p);
    EXPECT_EQ(target(reinterpret_cast<const uint8_t*>(b.data()), b.size()), 0);  // aborts on a failed check
    ++n;
  }
  return n;
}

TEST(FuzzRegression, TraceCsvCorpus) {
  EXPECT_GE(replay_all(fs::path(FF_FUZZ_CORPUS_DIR) / "trace_csv", ff::fuzz::trace_csv_one_input), 4u);
}

TEST(FuzzRegression, BundledTracesThroughTheTraceTarget) {
  EXPECT_GE(replay_all(fs::path(FF_TRACE_DIR), ff::fuzz::trace_csv_one_input), 10u);
}

TEST(FuzzRegression, SceneFileCorpus) {
  EXPECT_GE(replay_all(fs::path(FF_FUZZ_CORPUS_DIR) / "scene_file", ff::fuzz::scene_file_one_input), 6u);
}

// Fuzzer finds not fixed yet (scripts/stress-report saves them in
// corpus/<target>_open/; the bug goes to known_core_bugs_test.cpp). Once one
// passes, move its file to corpus/<target>/.
TEST(FuzzRegression, DISABLED_TraceCsvOpenFinds) {
  replay_all(fs::path(FF_FUZZ_CORPUS_DIR) / "trace_csv_open", ff::fuzz::trace_csv_one_input);
}
TEST(FuzzRegression, DISABLED_SceneFileOpenFinds) {
  replay_all(fs::path(FF_FUZZ_CORPUS_DIR) / "scene_file_open", ff::fuzz::scene_file_one_input);
}

TEST(FuzzRegression, EmptyAndBinaryInputs) {
  const uint8_t nothing[1] = {0};
  EXPECT_EQ(ff::fuzz::trace_csv_one_input(nothing, 0), 0);
  EXPECT_EQ(ff::fuzz::scene_file_one_input(nothing, 0), 0);
  std::vector<uint8_t> noise(4096);
  for (size_t i = 0; i < noise.size(); ++i) noise[i] = static_cast<uint8_t>((i * 2654435761u) >> 13);
  EXPECT_EQ(ff::fuzz::trace_csv_one_input(noise.data(), noise.size()), 0);
  EXPECT_EQ(ff::fuzz::scene_file_one_input(noise.data(), noise.size()), 0);
}

}  // namespace
