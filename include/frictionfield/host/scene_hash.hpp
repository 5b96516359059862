#pragma once
// One fingerprint of a condition's definition (scene and amplitude settings),
// so a file can say which condition produced it and a reader can check it was
// given the same one: FNV-1a 64 over a canonical little-endian encoding of the
// definition as normalised (elements in order, each with the parameters of its
// kind; floats by their bits, -0 as 0; enums as bytes). It names the
// definition, not the rendering: definitions that render identically (a point
// sink's unused radius in a directional scene, elements swapped, all weights
// doubled) can hash differently (docs/tools.md, "Scene hash").
// Every tool that names a condition in its output uses this, nothing else.
#include <cstdint>
#include <string>

#include "frictionfield/core/condition.hpp"

namespace ff::host {

uint64_t condition_hash(const Condition& condition);
// 16 lower-case hex digits, e.g. "cbf29ce484222325".
std::string hash_hex(uint64_t hash);

}  // namespace ff::host
