#pragma once
// General scenes as text: one directive per line, '#' starts a comment.
//
//   rendering directional            # constant | position | directional
//   constant 0.5                     # constant rendering only
//   bias 0                           # position rendering only
//   evaluation table 4 int16 gradient   # or: evaluation closed
//   element point_sink weight 0.5 centre 700 40 radius 10 feather 20
//   element path_sink weight 0.5 a 0.2 curve cubic -200 [100 240 600] [band 10 20]
//   element path_sink weight 1 curve sine 240 120 400 [x0]
//   element path_sink weight 1 curve polyline 100,240 400,100 700,40
//   element tunnel weight 1 x_start 100 length 400 width 60 20 scale 1 y_centre 240
//   element vortex weight 1 centre 400 240
//   element saddle weight 1 centre 400 240
//   element texture weight 1 wavelength 160 160 height 20
#include <cstddef>
#include <string>

#include "frictionfield/core/scene.hpp"

namespace ff::host {

// false with "line N: message" in `error`.
bool parse_scene_text(const std::string& text, SceneDefinition& out, std::string& error);
// The largest file read_scene_file reads: 8 elements of 16-point polylines
// are a few KB, and /dev/zero or a trace given by mistake must not fill memory.
constexpr size_t kMaxSceneFileBytes = 1024 * 1024;
// false with "PATH: why" in `error` (a file over kMaxSceneFileBytes is refused unread beyond that).
bool read_scene_file(const std::string& path, SceneDefinition& out, std::string& error);
// The same format back (parse(format(s)) == s for every field the format carries).
std::string format_scene_text(const SceneDefinition& scene);

}  // namespace ff::host
