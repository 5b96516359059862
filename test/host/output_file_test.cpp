// OutputFile: nothing under the real name until commit; an uncommitted or
// failed file leaves nothing at all. ToolOutput: the same for a file, and
// standard output or a device as they are.
#include "frictionfield/host/output_file.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace ff::host {
namespace {

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(OutputFile, AppearsUnderItsNameOnlyWhenCommitted) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "ff_output_file_test";
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / "out.csv", partial = dir / "out.csv.partial";
  std::filesystem::remove(path);
  {
    OutputFile f(path.string());
    ASSERT_TRUE(f.open());
    f.stream() << "a,b\n";
    EXPECT_TRUE(std::filesystem::exists(partial));
    EXPECT_FALSE(std::filesystem::exists(path));
    ASSERT_TRUE(f.commit());
    EXPECT_EQ(read(path), "a,b\n");  // whole at the commit, not when the object goes
  }
  EXPECT_EQ(read(path), "a,b\n");
  EXPECT_FALSE(std::filesystem::exists(partial));
  {
    OutputFile f(path.string());  // abandoned: the old file stays, no partial remains
    ASSERT_TRUE(f.open());
    f.stream() << "half";
  }
  EXPECT_EQ(read(path), "a,b\n");
  EXPECT_FALSE(std::filesystem::exists(partial));
  EXPECT_TRUE(write_file_atomically(path.string(), "x\n"));
  EXPECT_EQ(read(path), "x\n");
  EXPECT_FALSE(write_file_atomically((dir / "no-such-dir" / "f").string(), "x\n"));
  {
    OutputFile f(path.string());  // a write failed: the old file stays, no partial remains
    ASSERT_TRUE(f.open());
    f.stream() << "y\n";
    f.stream().setstate(std::ios::badbit);
    EXPECT_FALSE(f.commit());
  }
  EXPECT_EQ(read(path), "x\n");
  EXPECT_FALSE(std::filesystem::exists(partial));
  std::filesystem::remove_all(dir);
}

TEST(OutputFile, AWholeFileWrittenToAFifoGoesIntoItNotOverIt) {
  // Found writing --profile-out /dev/full as root: the rename replaced the device with a regular file.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "ff_output_fifo_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::filesystem::path fifo = dir / "fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const int reader = open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // so that opening it to write does not wait
  ASSERT_GE(reader, 0);
  EXPECT_TRUE(write_file_atomically(fifo.string(), "profile\n"));
  char buf[64];
  const ssize_t n = ::read(reader, buf, sizeof buf);
  close(reader);
  EXPECT_EQ(std::string(buf, n > 0 ? static_cast<size_t>(n) : 0), "profile\n");
  EXPECT_TRUE(std::filesystem::is_fifo(fifo));
  EXPECT_FALSE(std::filesystem::exists(dir / "fifo.partial"));
  std::filesystem::remove_all(dir);
}

TEST(ToolOutput, AFileIsCommittedAtomicallyADeviceWrittenIntoAFolderRefused) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "ff_tool_output_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / "out.csv";
  {
    ToolOutput out(path.string());
    ASSERT_TRUE(out.open());
    out.stream() << "a\n";
    EXPECT_TRUE(std::filesystem::exists(dir / "out.csv.partial"));
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_TRUE(out.commit());
  }
  EXPECT_EQ(read(path), "a\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "out.csv.partial"));
  {
    ToolOutput out("/dev/null");  // NAME.partial could not be renamed onto a device
    ASSERT_TRUE(out.open());
    EXPECT_NE(&out.stream(), &std::cout);
    out.stream() << "b\n";
    EXPECT_TRUE(out.commit());
  }
  EXPECT_FALSE(std::filesystem::exists("/dev/null.partial"));
  {
    ToolOutput out("/dev/full");  // every write fails (ENOSPC): seen at the commit's flush
    ASSERT_TRUE(out.open());
    out.stream() << "b\n";
    EXPECT_FALSE(out.commit());
  }
  {
    ToolOutput out(dir.string());  // a folder
    EXPECT_FALSE(out.open());
  }
  {
    ToolOutput out((dir / "no-such-dir" / "f").string());
    EXPECT_FALSE(out.open());
  }
  {
    ToolOutput out(path.string());  // a write failed: the old file stays
    ASSERT_TRUE(out.open());
    out.stream() << "c\n";
    out.stream().setstate(std::ios::badbit);
    EXPECT_FALSE(out.commit());
  }
  EXPECT_EQ(read(path), "a\n");
  {
    ToolOutput out("-");
    ASSERT_TRUE(out.open());
    EXPECT_EQ(&out.stream(), &std::cout);
    EXPECT_TRUE(out.commit());
  }
  EXPECT_EQ(std::filesystem::directory_iterator(dir)->path(), path);  // nothing else left
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ff::host
