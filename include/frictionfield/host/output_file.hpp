#pragma once
// An output file written as NAME.partial and renamed to NAME only when the
// tool commits it, so a failed or killed run never leaves a half file under
// the real name (docs/tools.md). Uncommitted, the partial file is removed.
// A failure keeps its reason (the errno of the first write, or of the rename,
// that failed) for the tool's message: "cannot write out.csv: No space left on device".
#include <fstream>
#include <memory>
#include <ostream>
#include <string>

namespace ff::host {

// "cannot write PATH: REASON", the reason from an errno (0: "a write failed"): every tool's words for it.
std::string cannot_write(const std::string& path, int error);

// A std::filebuf that keeps the errno of its first failed write: a stream
// only keeps badbit, and errno is overwritten long before the tool reports
// (and a later write may fail for another reason, or succeed once space is freed).
class ReasonedFileBuffer final : public std::filebuf {
 public:
  int first_error() const { return first_error_; }  // 0: none kept
  void note_failure();  // keeps errno unless an error is already kept

 protected:
  int_type overflow(int_type c) override;  // a buffer's worth of small writes
  std::streamsize xsputn(const char* s, std::streamsize n) override;  // a large write, straight to the file

 private:
  int first_error_ = 0;
};

// Where bytes go (how they get to their name): NAME.partial renamed at the
// commit, or, for a device or a FIFO (/dev/null, a pipe), straight into it,
// since a rename onto it would replace the device with a regular file.
class OutputFile {
 public:
  enum class Mode { ThroughPartial, InPlace };
  explicit OutputFile(std::string path, Mode mode = Mode::ThroughPartial);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  bool open();
  std::ostream& stream() { return stream_; }
  // Closes and renames: false if a write failed or the rename did.
  bool commit();
  // After a failed open() or commit(): "cannot write NAME: REASON".
  std::string error() const;

 private:
  std::string path_, written_;  // written_: NAME.partial, or NAME in place
  ReasonedFileBuffer buffer_;
  std::ostream stream_{&buffer_};
  int error_ = 0;  // 0 and failed: no reason known
};

// `content` to `path` as a ToolOutput writes it (a file whole through an
// OutputFile; "-", a device or a FIFO straight into): false (and no file,
// `error` "cannot write PATH: REASON") on failure.
bool write_file_atomically(const std::string& path, const std::string& content, std::string& error);

// A tool's -o PATH: "-" is standard output; a device or a FIFO is written
// straight into; anything else goes through NAME.partial.
class ToolOutput {
 public:
  explicit ToolOutput(std::string path);
  ToolOutput(const ToolOutput&) = delete;
  ToolOutput& operator=(const ToolOutput&) = delete;

  bool open();
  std::ostream& stream() { return *out_; }
  // Flushes, and commits a file: false if any write failed.
  bool commit();
  // After a failed open() or commit(): "cannot write PATH: REASON".
  std::string error() const;

 private:
  std::string path_;
  std::unique_ptr<OutputFile> file_;
  std::ostream* out_;
  int stdout_error_ = 0;
};

}  // namespace ff::host
