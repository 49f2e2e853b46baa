#pragma once
// The viewer's script language (`nanoview view PKG --script FILE`): one command per line, '#'
// starts a comment. The whole file is parsed before the window opens, so a typo on line 40 fails
// at once instead of after 39 rendered frames. Errors are InputError("FILE", "line N", what).
//
//   camera position=x,y,z;look_at=x,y,z;up=x,y,z;fov_degrees=DEG
//                                                keys left out keep the current camera; as --camera,
//                                                pos, at and fov are aliases
//   clip plane nx,ny,nz,d                        adds a plane (points with n·p + d ≥ 0 stay)
//   clip box x0,y0,z0,x1,y1,z1                   sets the clip box
//   clip off                                     removes every plane and the box
//   effect NAME on|off                           NAME one of the effect table's names (common/effect_table.hpp)
//   preset NAME                                  turns on a preset's effects with its values (illustrative)
//   show NAME | hide NAME                        NAME: medium (the scene's plasma), a compartment or a molecule
//                                                type of the package (as render --hide), in the picture or not
//   time SECONDS                                 animation / jitter time
//   wait N                                       renders N frames
//   pick X Y                                     prints the pixel's describe_hit JSON (one line)
//   screenshot PATH                              PATH (PNG) and PATH with extension .ids
//   size WxH                                     render (and window) size
//   keyframe SECONDS                             appends the current camera to the camera path
//                                                at that time (times must increase)
//   path save FILE                               writes the path (JSON, atomically) for render --path
//   path load FILE                               replaces the path with FILE's
//   path clear                                   forgets every keyframe
//   path frame K                                 camera and effect time of the path's frame K
//                                                (time K / fps), as `render --path --frames K:K`
//   path play A B                                renders frames A … B of the path, one each
//   quit                                         stops here
//
// The path starts empty, or as `view --path FILE` loaded it; it is the one the panel records
// into (K) and plays (L).
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>
#include <span>

#include "runtime/placement/visibility.hpp"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace nano::viewer {

struct ScriptCommand {
  enum class Kind {
    camera, clip_plane, clip_box, clip_off, effect, preset, show, time, wait, pick, screenshot, size,
    keyframe, path_save, path_load, path_clear, path_frame, path_play, quit
  };
  Kind kind = Kind::quit;
  std::size_t line = 0;        // 1-based line in the script, for errors found while running
  std::string text;            // camera: the spec; effect, preset, show: the name; screenshot, path save/load: the file
  glm::dvec4 plane{0.0};       // clip_plane
  std::pair<glm::dvec3, glm::dvec3> box{};  // clip_box
  bool on = false;             // effect; show: shown
  double seconds = 0;          // time, keyframe
  std::uint32_t count = 0;     // wait
  std::uint32_t x = 0, y = 0;  // pick: pixel; size: width, height
  std::uint32_t first = 0, last = 0;  // path frame: first; path play: first … last
};

struct Script {
  std::string file;  // as errors name it
  std::vector<ScriptCommand> commands;
};

// `file` only names the script in errors.
Script parse_script(std::string_view text, const std::string& file);
// Reads and parses; InputError naming the path when it cannot be read.
Script load_script(const std::filesystem::path& path);
// Every show / hide names something of the package (`names`: placement::hideable_names), so a typo
// fails before the window opens: InputError(file, "line N", the names there are).
void check_show_names(const Script& script, std::span<const placement::HideableName> names);


}  // namespace nano::viewer
