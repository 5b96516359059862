#include "frictionfield/host/output_file.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <system_error>
#include <utility>

namespace ff::host {

OutputFile::OutputFile(std::string path) : path_(std::move(path)), partial_(path_ + ".partial") {}

OutputFile::~OutputFile() {
  if (file_.is_open()) {  // not committed: commit() closes it
    file_.close();  // before the remove: Windows cannot remove an open file
    std::remove(partial_.c_str());
  }
}

bool OutputFile::open() {
  file_.open(partial_);
  return static_cast<bool>(file_);
}

bool OutputFile::commit() {
  file_.close();
  if (!file_ || std::rename(partial_.c_str(), path_.c_str()) != 0) {
    std::remove(partial_.c_str());
    return false;
  }
  return true;
}

bool write_file_atomically(const std::string& path, const std::string& content) {
  ToolOutput out(path);  // not an OutputFile alone: as root, its rename would replace /dev/null with a file
  if (!out.open()) return false;
  out.stream() << content;
  return out.commit();
}

ToolOutput::ToolOutput(std::string path) : path_(std::move(path)), out_(&std::cout) {}

bool ToolOutput::open() {
  if (path_ == "-") return true;
  std::error_code ec;
  if (std::filesystem::exists(path_, ec) && !std::filesystem::is_regular_file(path_, ec)) {
    direct_.open(path_);
    out_ = &direct_;
    return static_cast<bool>(direct_);
  }
  file_ = std::make_unique<OutputFile>(path_);
  out_ = &file_->stream();
  return file_->open();
}

bool ToolOutput::commit() {
  out_->flush();
  if (file_) return file_->commit();
  return static_cast<bool>(*out_);
}

}  // namespace ff::host
