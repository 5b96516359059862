// open_input_file: a file opens; a missing one and a folder are refused with
// the reason (a folder would otherwise open, and read as an empty file).
#include "frictionfield/host/input_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/scratch_path.hpp"

namespace ff::host {
namespace {

TEST(InputFile, OpensAFileAndSaysWhyNotForAMissingOneOrAFolder) {
  const std::string path = support::scratch_path("input_file.csv");
  std::ofstream(path) << "t_us,x,y,touch\n";
  std::ifstream in;
  std::string why;
  ASSERT_TRUE(open_input_file(path, in, why)) << why;
  std::string line;
  EXPECT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "t_us,x,y,touch");
  std::ifstream missing;
  EXPECT_FALSE(open_input_file(support::scratch_path("no_such_file.csv"), missing, why));
  EXPECT_EQ(why, "cannot open: No such file or directory");
  const std::string folder = support::scratch_path("a_folder.csv");
  std::filesystem::create_directories(folder);
  std::ifstream as_folder;
  EXPECT_FALSE(open_input_file(folder, as_folder, why));
  EXPECT_EQ(why, "is a folder, not a file");
  EXPECT_FALSE(as_folder.is_open());
}

}  // namespace
}  // namespace ff::host
