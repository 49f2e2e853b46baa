#include "runtime/viewer/script.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.hpp"
#include "runtime/render/camera_spec.hpp"
#include "runtime/render/image_io.hpp"
#include "runtime/render/effects.hpp"

namespace nano::viewer {
namespace {

using K = ScriptCommand::Kind;

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

// Splits off the first whitespace-separated word; `rest` is the remainder, trimmed.
std::string_view next_word(std::string_view s, std::string_view& rest) {
  s = trim(s);
  const auto end = s.find_first_of(" \t");
  if (end == std::string_view::npos) {
    rest = {};
    return s;
  }
  rest = trim(s.substr(end));
  return s.substr(0, end);
}

template <typename T>
bool parse_number(std::string_view s, T& value) {
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
  return error == std::errc() && end == s.data() + s.size();
}

std::uint32_t parse_count(std::string_view s, const char* what, std::uint32_t max, const InputSource& source) {
  std::uint32_t value = 0;
  if (!parse_number(s, value) || value > max)
    source.fail(std::string(what) + " must be a whole number from 0 to " + std::to_string(max) + ", got '" + std::string(s) + "'");
  return value;
}

void expect_no_more(std::string_view rest, std::string_view command, const InputSource& source) {
  if (!rest.empty())
    source.fail("unexpected '" + std::string(rest) + "' after '" + std::string(command) + "'");
}

// A camera spec may leave keys out (they keep the camera current when the line runs), so it can
// only be checked against a stand-in camera here. Two unrelated stand-ins: a spec that parses
// against either is well formed; one that fails against both is wrong whatever camera it meets
// (bad syntax, position = look_at, fov_degrees out of range).
void check_camera_syntax(const std::string& spec, const InputSource& source) {
  const Camera a{};
  Camera b;
  b.position = {-311.0, 517.0, 1931.0};
  b.look_at = {7.0, -11.0, 13.0};
  b.up = {0.3, 0.5, 0.8};
  b.fov_degrees = 33;
  try {
    (void)render::parse_camera(spec, a, source);
  } catch (const InputError& first) {
    try {
      (void)render::parse_camera(spec, b, source);
    } catch (const InputError&) {
      throw first;
    }
  }
}

// Paths have at most 10 million frames (render/camera_path.cpp), so a frame number fits 32 bits.
constexpr std::uint32_t kMaxPathFrame = 10'000'000;

// `path save FILE | load FILE | clear | frame K | play A B`; `rest` is what follows "path".
void parse_path_command(std::string_view, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  std::string_view args;
  const std::string_view what = next_word(rest, args);
  if (what == "save" || what == "load") {
    // The rest of the line, spaces included, as screenshot takes it.
    if (args.empty()) source.fail("path " + std::string(what) + " expects a FILE (.json)");
    c.kind = what == "save" ? K::path_save : K::path_load;
    c.text = std::string(args);
  } else if (what == "clear") {
    expect_no_more(args, "path clear", source);
    c.kind = K::path_clear;
  } else if (what == "frame") {
    std::string_view tail;
    const std::string_view k = next_word(args, tail);
    if (k.empty()) source.fail("path frame expects a frame number K");
    c.first = parse_count(k, "path frame K", kMaxPathFrame, source);
    expect_no_more(tail, "path frame K", source);
    c.kind = K::path_frame;
  } else if (what == "play") {
    std::string_view tail;
    const std::string_view a = next_word(args, args);
    const std::string_view b = next_word(args, tail);
    if (a.empty() || b.empty()) source.fail("path play expects A B (first and last frame)");
    c.first = parse_count(a, "path play A", kMaxPathFrame, source);
    c.last = parse_count(b, "path play B", kMaxPathFrame, source);
    if (c.first > c.last)
      source.fail("path play A B needs A ≤ B, got " + std::to_string(c.first) + " > " + std::to_string(c.last));
    expect_no_more(tail, "path play A B", source);
    c.kind = K::path_play;
  } else {
    source.fail("path expects 'save FILE', 'load FILE', 'clear', 'frame K' or 'play A B', got '" + std::string(rest) + "'");
  }
}

void parse_camera_command(std::string_view, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  if (rest.empty()) source.fail("camera needs a spec position=x,y,z;look_at=x,y,z;up=x,y,z;fov_degrees=DEG");
  c.kind = K::camera;
  c.text = std::string(rest);
  check_camera_syntax(c.text, source);
}

void parse_clip_command(std::string_view, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  std::string_view args;
  const std::string_view what = next_word(rest, args);
  if (what == "plane") {
    c.kind = K::clip_plane;
    c.plane = render::parse_clip_plane(args, source);
  } else if (what == "box") {
    c.kind = K::clip_box;
    c.box = render::parse_clip_box(args, source);
  } else if (what == "off") {
    c.kind = K::clip_off;
    expect_no_more(args, "clip off", source);
  } else {
    source.fail("clip expects 'plane nx,ny,nz,d', 'box x0,y0,z0,x1,y1,z1' or 'off', got '" + std::string(rest) + "'");
  }
}

void parse_effect_command(std::string_view, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  std::string_view tail;
  const std::string_view name = next_word(rest, rest);
  const std::string_view state = next_word(rest, tail);
  render::EffectSettings scratch;
  (void)render::effect_flag(scratch, name, source);  // throws for an unknown name
  if (state != "on" && state != "off")
    source.fail("effect " + std::string(name) + " expects on or off, got '" + std::string(state) + "'");
  expect_no_more(tail, "effect NAME on|off", source);
  c.kind = K::effect;
  c.text = std::string(name);
  c.on = state == "on";
}

void parse_preset_command(std::string_view, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  std::string_view tail;
  const std::string_view name = next_word(rest, tail);
  render::EffectSettings scratch;
  render::apply_preset(scratch, name, source);  // throws for an unknown name
  expect_no_more(tail, "preset NAME", source);
  c.kind = K::preset;
  c.text = std::string(name);
}

// `show NAME` and `hide NAME`.
void parse_show_command(std::string_view word, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  std::string_view tail;
  const std::string_view what = next_word(rest, tail);
  if (what.empty()) source.fail(std::string(word) + " expects medium or the name of a compartment or molecule type");
  expect_no_more(tail, std::string(word) + " NAME", source);
  c.kind = K::show;
  c.text = std::string(what);
  c.on = word == "show";
}

// A time in seconds ≥ 0 and nothing after it; `expects` and `usage` word the errors.
double parse_seconds(std::string_view rest, std::string_view expects, std::string_view usage, const InputSource& source) {
  std::string_view tail;
  const std::string_view value = next_word(rest, tail);
  double seconds = 0;
  if (!parse_number(value, seconds) || !std::isfinite(seconds) || seconds < 0)
    source.fail(std::string(expects) + ", got '" + std::string(value) + "'");
  expect_no_more(tail, usage, source);
  return seconds;
}

void parse_time_command(std::string_view, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  c.seconds = parse_seconds(rest, "time expects seconds ≥ 0", "time SECONDS", source);
  c.kind = K::time;
}

void parse_keyframe_command(std::string_view, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  c.seconds = parse_seconds(rest, "keyframe expects its time in seconds ≥ 0", "keyframe SECONDS", source);
  c.kind = K::keyframe;
}

void parse_wait_command(std::string_view, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  std::string_view tail;
  c.count = parse_count(next_word(rest, tail), "wait N", 100000, source);
  expect_no_more(tail, "wait N", source);
  c.kind = K::wait;
}

void parse_pick_command(std::string_view, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  std::string_view tail;
  const std::string_view x = next_word(rest, rest);
  const std::string_view y = next_word(rest, tail);
  if (x.empty() || y.empty()) source.fail("pick expects X Y (pixel column and row)");
  c.x = parse_count(x, "pick X", 16383, source);
  c.y = parse_count(y, "pick Y", 16383, source);
  expect_no_more(tail, "pick X Y", source);
  c.kind = K::pick;
}

void parse_screenshot_command(std::string_view, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  if (rest.empty()) source.fail("screenshot expects a PATH (.png)");
  c.kind = K::screenshot;
  c.text = std::string(rest);
  if (std::filesystem::path(c.text).extension() == ".ids")
    source.fail("screenshot PATH must not end in .ids: the hit ids are written beside it as PATH.ids");
}

void parse_size_command(std::string_view, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  std::string_view tail;
  const auto [w, h] = render::parse_image_size(next_word(rest, tail), source);
  expect_no_more(tail, "size WxH", source);
  c.kind = K::size;
  c.x = w, c.y = h;
}

void parse_quit_command(std::string_view, std::string_view rest, const InputSource& source, ScriptCommand& c) {
  expect_no_more(rest, "quit", source);
  c.kind = K::quit;
}

// A command's parser is given the command word and what follows it on the line.
using CommandParser = void (*)(std::string_view word, std::string_view rest, const InputSource& source, ScriptCommand& c);
constexpr std::pair<std::string_view, CommandParser> kCommands[] = {
    {"camera", parse_camera_command},
    {"clip", parse_clip_command},
    {"effect", parse_effect_command},
    {"preset", parse_preset_command},
    {"show", parse_show_command},
    {"hide", parse_show_command},
    {"time", parse_time_command},
    {"wait", parse_wait_command},
    {"pick", parse_pick_command},
    {"screenshot", parse_screenshot_command},
    {"size", parse_size_command},
    {"keyframe", parse_keyframe_command},
    {"path", parse_path_command},
    {"quit", parse_quit_command},
};

ScriptCommand parse_line(std::string_view line, const InputSource& source) {
  ScriptCommand c;
  std::string_view rest;
  const std::string_view word = next_word(line, rest);
  const auto command = std::find_if(std::begin(kCommands), std::end(kCommands), [&](const auto& entry) { return entry.first == word; });
  if (command == std::end(kCommands)) {
    std::string known;
    for (const auto& entry : kCommands) known += (known.empty() ? "" : ", ") + std::string(entry.first);
    source.fail("unknown command '" + std::string(word) + "' (" + known + ")");
  }
  command->second(word, rest, source, c);
  return c;
}

}  // namespace

Script parse_script(std::string_view text, const std::string& file) {
  Script script;
  script.file = file;
  std::size_t line_number = 0;
  while (!text.empty()) {
    const auto end = text.find('\n');
    std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    ++line_number;
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    line = trim(line);
    if (line.empty()) continue;
    ScriptCommand command = parse_line(line, {file, "line " + std::to_string(line_number)});
    command.line = line_number;
    script.commands.push_back(std::move(command));
  }
  return script;
}

Script load_script(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot read the script file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_script(text.str(), path.string());
}

void check_show_names(const Script& script, std::span<const placement::HideableName> names) {
  for (const ScriptCommand& c : script.commands) {
    if (c.kind != ScriptCommand::Kind::show) continue;
    if (placement::hideable_matches(names, c.text) == 1) continue;
    throw InputError(script.file, "line " + std::to_string(c.line),
                     std::string(c.on ? "show" : "hide") + " '" + c.text + "': " +
                         (placement::hideable_matches(names, c.text) == 0 ? "the package has no such name; it has: "
                                                                           : "ambiguous; qualify it: ") +
                         placement::hideable_listing(names));
  }
}

}  // namespace nano::viewer
