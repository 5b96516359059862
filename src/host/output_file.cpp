#include "frictionfield/host/output_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <system_error>
#include <utility>

namespace ff::host {

std::string cannot_write(const std::string& path, int error) {
  return "cannot write " + path + ": " + (error != 0 ? std::strerror(error) : "a write failed");
}

void ReasonedFileBuffer::note_failure() {
  if (first_error_ == 0) first_error_ = errno;
}

// A failed write(2) below has just set errno.
ReasonedFileBuffer::int_type ReasonedFileBuffer::overflow(int_type c) {
  const int_type r = std::filebuf::overflow(c);
  if (traits_type::eq_int_type(r, traits_type::eof())) note_failure();  // success returns not_eof(c)
  return r;
}

std::streamsize ReasonedFileBuffer::xsputn(const char* s, std::streamsize n) {
  const std::streamsize r = std::filebuf::xsputn(s, n);
  if (r < n) note_failure();
  return r;
}

OutputFile::OutputFile(std::string path, Mode mode)
    : path_(std::move(path)), written_(mode == Mode::InPlace ? path_ : path_ + ".partial") {}

OutputFile::~OutputFile() {
  if (buffer_.is_open()) {  // not committed: commit() closes it
    buffer_.close();  // before the remove: Windows cannot remove an open file
    if (written_ != path_) std::remove(written_.c_str());
  }
}

bool OutputFile::open() {
  if (buffer_.open(written_, std::ios::out | std::ios::trunc) != nullptr) return true;
  error_ = errno;
  return false;
}

bool OutputFile::commit() {
  // Writes what is buffered: a failure is kept by overflow(). (If only close(2) fails, as on a full NFS
  // server, no write kept a reason: "a write failed".)
  const bool closed = buffer_.close() != nullptr;
  error_ = buffer_.first_error();
  if (!closed || !stream_) {  // !stream_: a write failed earlier, even if the space has been freed since
    if (written_ != path_) std::remove(written_.c_str());
    return false;
  }
  if (written_ != path_ && std::rename(written_.c_str(), path_.c_str()) != 0) {
    error_ = errno;
    std::remove(written_.c_str());
    return false;
  }
  return true;
}

std::string OutputFile::error() const { return cannot_write(path_, error_); }

bool write_file_atomically(const std::string& path, const std::string& content, std::string& error) {
  ToolOutput out(path);  // not an OutputFile alone: as root, its rename would replace /dev/null with a file
  if (out.open()) {
    out.stream() << content;
    if (out.commit()) return true;
  }
  error = out.error();
  return false;
}

ToolOutput::ToolOutput(std::string path) : path_(std::move(path)), out_(&std::cout) {}

bool ToolOutput::open() {
  if (path_ == "-") return true;
  std::error_code ec;
  const bool in_place = std::filesystem::exists(path_, ec) && !std::filesystem::is_regular_file(path_, ec);
  file_ = std::make_unique<OutputFile>(path_, in_place ? OutputFile::Mode::InPlace : OutputFile::Mode::ThroughPartial);
  out_ = &file_->stream();
  return file_->open();
}

bool ToolOutput::commit() {
  if (file_) return file_->commit();
  errno = 0;  // a stream that failed before does not write again: whatever errno holds is not its reason
  if (out_->flush()) return true;
  stdout_error_ = errno;
  return false;
}

std::string ToolOutput::error() const {
  return file_ ? file_->error() : cannot_write("standard output", stdout_error_);
}

}  // namespace ff::host
