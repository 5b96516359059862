#pragma once
// One fingerprint of a condition (scene and amplitude settings), so a file can
// say which condition produced it and a reader can check it was given the
// same one: FNV-1a 64 over a canonical little-endian encoding of every field
// set_condition() reads (floats by their bits, -0 as 0; enums as bytes).
// Every tool that names a condition in its output uses this, nothing else.
#include <cstdint>
#include <string>

#include "frictionfield/core/condition.hpp"

namespace ff::host {

uint64_t condition_hash(const Condition& condition);
// 16 lower-case hex digits, e.g. "cbf29ce484222325".
std::string hash_hex(uint64_t hash);

}  // namespace ff::host
