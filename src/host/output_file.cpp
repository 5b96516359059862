#include "frictionfield/host/output_file.hpp"

#include <cstdio>
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
  OutputFile file(path);
  if (!file.open()) return false;
  file.stream() << content;
  return file.commit();
}

}  // namespace ff::host
