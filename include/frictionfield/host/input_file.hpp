#pragma once
// An input file opened for reading, or why not, in one set of words for every
// tool: "cannot open: No such file or directory", "is a folder, not a file".
// A folder has to be refused by name: on Linux it opens like a file and then
// reads as empty, which a trace reader would call an empty file.
#include <fstream>
#include <string>

namespace ff::host {

// false with `why` (without the path: callers write "PATH: why").
bool open_input_file(const std::string& path, std::ifstream& in, std::string& why);

}  // namespace ff::host
