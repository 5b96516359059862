// OutputFile: nothing under the real name until commit; an uncommitted or
// failed file leaves nothing at all. ToolOutput: the same for a file, and
// standard output or a device as they are. A failure says why, in the
// words of the errno of what failed.
#include "frictionfield/host/output_file.hpp"

#include <gtest/gtest.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "support/file_size_limit.hpp"
#include "support/scratch_path.hpp"

namespace ff::host {
namespace {

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(OutputFile, AppearsUnderItsNameOnlyWhenCommitted) {
  const std::filesystem::path dir = support::scratch_path("output_file_test");
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
  std::string error;
  EXPECT_TRUE(write_file_atomically(path.string(), "x\n", error));
  EXPECT_EQ(read(path), "x\n");
  EXPECT_FALSE(write_file_atomically((dir / "no-such-dir" / "f").string(), "x\n", error));
  EXPECT_EQ(error, "cannot write " + (dir / "no-such-dir" / "f").string() + ": No such file or directory");
  {
    OutputFile f(path.string());  // a write failed: the old file stays, no partial remains
    ASSERT_TRUE(f.open());
    f.stream() << "y\n";
    f.stream().setstate(std::ios::badbit);
    EXPECT_FALSE(f.commit());
    EXPECT_EQ(f.error(), "cannot write " + path.string() + ": a write failed");  // no errno to tell
  }
  EXPECT_EQ(read(path), "x\n");
  EXPECT_FALSE(std::filesystem::exists(partial));
  const std::filesystem::path folder = dir / "taken";  // a folder with a file in it: the rename fails
  std::filesystem::create_directories(folder / "inside");
  {
    OutputFile f(folder.string());
    ASSERT_TRUE(f.open());
    f.stream() << "z\n";
    EXPECT_FALSE(f.commit());
    EXPECT_EQ(f.error(), "cannot write " + folder.string() + ": Is a directory");
  }
  EXPECT_FALSE(std::filesystem::exists(folder.string() + ".partial"));
  std::filesystem::remove_all(dir);
}

TEST(OutputFile, AWholeFileWrittenToAFifoGoesIntoItNotOverIt) {
  // Found writing --profile-out /dev/full as root: the rename replaced the device with a regular file.
  const std::filesystem::path dir = support::scratch_path("output_fifo_test");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::filesystem::path fifo = dir / "fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const int reader = open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // so that opening it to write does not wait
  ASSERT_GE(reader, 0);
  std::string error;
  EXPECT_TRUE(write_file_atomically(fifo.string(), "profile\n", error));
  char buf[64];
  const ssize_t n = ::read(reader, buf, sizeof buf);
  close(reader);
  EXPECT_EQ(std::string(buf, n > 0 ? static_cast<size_t>(n) : 0), "profile\n");
  EXPECT_TRUE(std::filesystem::is_fifo(fifo));
  EXPECT_FALSE(std::filesystem::exists(dir / "fifo.partial"));
  std::filesystem::remove_all(dir);
}

TEST(ToolOutput, AFileIsCommittedAtomicallyADeviceWrittenIntoAFolderRefused) {
  const std::filesystem::path dir = support::scratch_path("tool_output_test");
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
    EXPECT_EQ(out.error(), "cannot write /dev/full: No space left on device");
  }
  {
    ToolOutput out(dir.string());  // a folder
    EXPECT_FALSE(out.open());
    EXPECT_EQ(out.error(), "cannot write " + dir.string() + ": Is a directory");
  }
  {
    ToolOutput out((dir / "no-such-dir" / "f").string());
    EXPECT_FALSE(out.open());
    EXPECT_EQ(out.error(), "cannot write " + (dir / "no-such-dir" / "f").string() + ": No such file or directory");
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

TEST(ToolOutput, AWriteThatFailsMidwayKeepsItsReasonNotALaterErrno) {
  const std::filesystem::path dir = support::scratch_path("tool_output_full");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "out.csv").string();
  {
    support::FileSizeLimit full(4096);
    ToolOutput out(path);
    ASSERT_TRUE(out.open());
    for (int i = 0; i < 10000 && out.stream(); ++i) out.stream() << i << ",row\n";  // small writes, buffered
    EXPECT_FALSE(out.stream());
    errno = ENOTTY;  // what a later isatty() leaves: not the reason
    EXPECT_FALSE(out.commit());
    EXPECT_EQ(out.error(), "cannot write " + path + ": File too large");
  }
  std::string error;
  {
    support::FileSizeLimit full(4096);
    EXPECT_FALSE(write_file_atomically(path, std::string(100000, 'x'), error));  // one large write, past the buffer
  }
  EXPECT_EQ(error, "cannot write " + path + ": File too large");
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
  {
    ToolOutput out(path);
    ASSERT_TRUE(out.open());
    {
      support::FileSizeLimit full(4096);
      // put(): a character at a time, so the buffer's overflow() is what writes and fails (operator<< goes
      // through xsputn).
      for (int i = 0; i < 100000 && out.stream(); ++i) out.stream().put('x');
    }
    // Space freed before the commit (another job's files deleted): the file lacks what failed all the same.
    EXPECT_FALSE(out.commit());
    EXPECT_EQ(out.error(), "cannot write " + path + ": File too large");
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  std::filesystem::remove_all(dir);
}

TEST(ReasonedFileBuffer, KeepsTheFirstReasonNotALaterOne) {
  const std::string path = support::scratch_path("reasoned_buffer");
  ReasonedFileBuffer buffer;
  ASSERT_NE(buffer.open(path, std::ios::out), nullptr);
  EXPECT_EQ(buffer.first_error(), 0);
  {
    support::FileSizeLimit full(4096);
    const std::string block(100000, 'x');
    EXPECT_LT(buffer.sputn(block.data(), static_cast<std::streamsize>(block.size())), 100000);
  }
  EXPECT_EQ(buffer.first_error(), EFBIG);
  errno = EIO;  // a later failure, for another reason
  buffer.note_failure();
  EXPECT_EQ(buffer.first_error(), EFBIG);
  buffer.close();
  std::remove(path.c_str());
}

TEST(ToolOutput, StandardOutputThatCannotBeWrittenSaysWhy) {
  std::cout.flush();
  std::fflush(stdout);
  const int saved = dup(STDOUT_FILENO);
  const int full = ::open("/dev/full", O_WRONLY);
  ASSERT_GE(full, 0);
  dup2(full, STDOUT_FILENO);
  ToolOutput out("-");
  ASSERT_TRUE(out.open());
  out.stream() << "row\n";
  const bool committed = out.commit();
  std::clearerr(stdout);
  dup2(saved, STDOUT_FILENO);
  close(saved);
  close(full);
  std::cout.clear();
  EXPECT_FALSE(committed);
  EXPECT_EQ(out.error(), "cannot write standard output: No space left on device");
}

TEST(ToolOutput, StandardOutputThatFailedBeforeGivesNoStaleReason) {
  ToolOutput out("-");
  ASSERT_TRUE(out.open());
  std::cout.setstate(std::ios::badbit);  // an earlier write failed; this flush writes nothing
  errno = ENOTTY;  // what an isatty() since left behind
  const bool committed = out.commit();
  std::cout.clear();
  EXPECT_FALSE(committed);
  EXPECT_EQ(out.error(), "cannot write standard output: a write failed");
}

}  // namespace
}  // namespace ff::host
