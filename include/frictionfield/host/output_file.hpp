#pragma once
// An output file written as NAME.partial and renamed to NAME only when the
// tool commits it, so a failed or killed run never leaves a half file under
// the real name (docs/tools.md). Uncommitted, the partial file is removed.
#include <fstream>
#include <memory>
#include <ostream>
#include <string>

namespace ff::host {

class OutputFile {
 public:
  explicit OutputFile(std::string path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  bool open();
  std::ostream& stream() { return file_; }
  // Closes and renames: false if a write failed or the rename did.
  bool commit();

 private:
  std::string path_, partial_;
  std::ofstream file_;
};

// `content` to `path` as a ToolOutput writes it (a file whole through an
// OutputFile; "-", a device or a FIFO straight into): false (and no file) on failure.
bool write_file_atomically(const std::string& path, const std::string& content);

// A tool's -o PATH: "-" is standard output; a device or a FIFO (/dev/null, a
// pipe) is written straight into, since NAME.partial cannot be renamed onto
// it; anything else goes through an OutputFile.
class ToolOutput {
 public:
  explicit ToolOutput(std::string path);
  ToolOutput(const ToolOutput&) = delete;
  ToolOutput& operator=(const ToolOutput&) = delete;

  bool open();
  std::ostream& stream() { return *out_; }
  // Flushes, and commits a file: false if any write failed.
  bool commit();

 private:
  std::string path_;
  std::unique_ptr<OutputFile> file_;
  std::ofstream direct_;
  std::ostream* out_;
};

}  // namespace ff::host
