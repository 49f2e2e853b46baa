// The viewer's script language: every command, comments, and errors that name file and line.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "runtime/render/image_io.hpp"
#include "runtime/viewer/script.hpp"

namespace nano::viewer {
namespace {

using K = ScriptCommand::Kind;

TEST(Script, ParsesEveryCommand) {
  const Script s = parse_script(
      "# a comment line\n"
      "camera pos=0,0,900;at=0,0,0;up=0,1,0;fov=40\n"
      "\n"
      "clip plane 0,0,1,-10   # trailing comment\n"
      "clip box -1,-2,-3,4,5,6\n"
      "clip off\n"
      "effect ao on\n"
      "effect shadows off\n"
      "time 2.5\n"
      "wait 3\n"
      "pick 10 20\n"
      "screenshot out/a.png\n"
      "size 64x48\n"
      "  quit  \r\n",
      "s.txt");
  ASSERT_EQ(s.commands.size(), 12u);
  EXPECT_EQ(s.file, "s.txt");
  EXPECT_EQ(s.commands[0].kind, K::camera);
  EXPECT_EQ(s.commands[0].line, 2u);
  EXPECT_EQ(s.commands[0].text, "pos=0,0,900;at=0,0,0;up=0,1,0;fov=40");
  EXPECT_EQ(s.commands[1].kind, K::clip_plane);
  EXPECT_EQ(s.commands[1].line, 4u);
  EXPECT_EQ(s.commands[1].plane.z, 1.0);
  EXPECT_EQ(s.commands[1].plane.w, -10.0);
  EXPECT_EQ(s.commands[2].kind, K::clip_box);
  EXPECT_EQ(s.commands[2].box.first, glm::dvec3(-1, -2, -3));
  EXPECT_EQ(s.commands[2].box.second, glm::dvec3(4, 5, 6));
  EXPECT_EQ(s.commands[3].kind, K::clip_off);
  EXPECT_EQ(s.commands[4].kind, K::effect);
  EXPECT_EQ(s.commands[4].text, "ao");
  EXPECT_TRUE(s.commands[4].on);
  EXPECT_FALSE(s.commands[5].on);
  EXPECT_EQ(s.commands[6].kind, K::time);
  EXPECT_EQ(s.commands[6].seconds, 2.5);
  EXPECT_EQ(s.commands[7].kind, K::wait);
  EXPECT_EQ(s.commands[7].count, 3u);
  EXPECT_EQ(s.commands[8].kind, K::pick);
  EXPECT_EQ(s.commands[8].x, 10u);
  EXPECT_EQ(s.commands[8].y, 20u);
  EXPECT_EQ(s.commands[9].kind, K::screenshot);
  EXPECT_EQ(s.commands[9].text, "out/a.png");
  EXPECT_EQ(s.commands[10].kind, K::size);
  EXPECT_EQ(s.commands[10].x, 64u);
  EXPECT_EQ(s.commands[10].y, 48u);
  EXPECT_EQ(s.commands[11].kind, K::quit);
  EXPECT_EQ(s.commands[11].line, 14u);
}

TEST(Script, ParsesKeyframeAndPathCommands) {
  const Script s = parse_script(
      "keyframe 0\n"
      "keyframe 2.5\n"
      "path save out/my path.json\n"
      "path load p.json\n"
      "path clear\n"
      "path frame 7\n"
      "path play 3 3\n"
      "path play 0 10000000\n",
      "s.txt");
  ASSERT_EQ(s.commands.size(), 8u);
  EXPECT_EQ(s.commands[0].kind, K::keyframe);
  EXPECT_EQ(s.commands[0].seconds, 0.0);
  EXPECT_EQ(s.commands[1].seconds, 2.5);
  EXPECT_EQ(s.commands[2].kind, K::path_save);
  EXPECT_EQ(s.commands[2].text, "out/my path.json");  // the rest of the line, as screenshot takes it
  EXPECT_EQ(s.commands[3].kind, K::path_load);
  EXPECT_EQ(s.commands[3].text, "p.json");
  EXPECT_EQ(s.commands[4].kind, K::path_clear);
  EXPECT_EQ(s.commands[5].kind, K::path_frame);
  EXPECT_EQ(s.commands[5].first, 7u);
  EXPECT_EQ(s.commands[6].kind, K::path_play);
  EXPECT_EQ(s.commands[6].first, 3u);
  EXPECT_EQ(s.commands[6].last, 3u);
  EXPECT_EQ(s.commands[7].last, 10000000u);
  EXPECT_EQ(s.commands[7].line, 8u);
}

TEST(Script, ShowsAndHidesByName) {
  const Script s = parse_script("hide medium\nshow medium\nhide red_cell\n", "s");
  ASSERT_EQ(s.commands.size(), 3u);
  EXPECT_EQ(s.commands[0].kind, ScriptCommand::Kind::show);
  EXPECT_EQ(s.commands[0].text, "medium");
  EXPECT_FALSE(s.commands[0].on);
  EXPECT_TRUE(s.commands[1].on);
  EXPECT_EQ(s.commands[2].text, "red_cell");
  EXPECT_FALSE(s.commands[2].on);
}

// The names are the package's: checked before the window opens, with the line and the names there are.
TEST(Script, ShowNamesAreCheckedAgainstThePackage) {
  using Kind = placement::HideableName::Kind;
  const std::vector<placement::HideableName> names{
      {Kind::medium, "medium", {}}, {Kind::compartment, "red_cell", {0}}, {Kind::molecule_type, "POPC", {0, 3}},
      {Kind::compartment, "band3", {1}}, {Kind::molecule_type, "band3", {2}}};
  EXPECT_NO_THROW(check_show_names(parse_script("hide medium\nhide red_cell\nshow POPC\nhide molecule:band3\n", "s"), names));
  try {
    check_show_names(parse_script("wait 1\nhide red_cells\n", "s.txt"), names);
    FAIL() << "a misspelt name passed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "s.txt");
    EXPECT_EQ(e.where(), "line 2");
    EXPECT_NE(e.rule().find("no such name"), std::string::npos) << e.rule();
    EXPECT_NE(e.rule().find("compartment:red_cell"), std::string::npos) << e.rule();
  }
  EXPECT_THROW(check_show_names(parse_script("hide band3\n", "s"), names), InputError);  // compartment or molecule?
  EXPECT_THROW(check_show_names(parse_script("hide medium\n", "s"), std::vector<placement::HideableName>{}), InputError);
}

TEST(Script, PartialCameraSpecIsAccepted) {
  // Keys left out keep the camera current when the line runs, so these must parse on their own.
  EXPECT_NO_THROW(parse_script("camera fov=20\ncamera at=0,0,1000\ncamera pos=0,5,0\n", "s"));
}

// The error names the file, the line and the problem.
void expect_error(const std::string& text, const std::string& line, const std::string& fragment) {
  try {
    parse_script(text, "bad.txt");
    FAIL() << "no error for: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.txt") << text;
    EXPECT_EQ(e.where(), line) << text;
    EXPECT_NE(e.rule().find(fragment), std::string::npos) << "'" << e.rule() << "' lacks '" << fragment << "'";
  }
}

TEST(Script, ErrorsNameFileLineAndProblem) {
  expect_error("wait 1\nfly away\n", "line 2", "unknown command 'fly'");
  // Every command is offered, as the table holds them.
  expect_error("fly away\n", "line 1", "(camera, clip, effect, preset, show, hide, time, wait, pick, screenshot, size, keyframe, path, quit)");
  expect_error("camera\n", "line 1", "camera needs a spec");
  expect_error("camera pos=1,2\n", "line 1", "pos");
  expect_error("camera pos=0,0,0;at=0,0,0\n", "line 1", "same point");
  expect_error("camera fov=200\n", "line 1", "fov");
  expect_error("camera zoom=2\n", "line 1", "unknown key");
  expect_error("\n\nclip plane 0,0,0,1\n", "line 3", "normal");
  expect_error("clip plane 1,2\n", "line 1", "clip plane");
  expect_error("clip box 1,1,1,0,0,0\n", "line 1", "x0 < x1");
  expect_error("clip sphere 1\n", "line 1", "clip expects");
  expect_error("clip off now\n", "line 1", "unexpected 'now'");
  expect_error("effect bloom on\n", "line 1", "unknown effect 'bloom'");
  expect_error("preset goodsell\n", "line 1", "unknown preset 'goodsell' (illustrative)");
  expect_error("preset illustrative now\n", "line 1", "unexpected 'now'");
  expect_error("effect ao maybe\n", "line 1", "on or off");
  expect_error("effect ao\n", "line 1", "on or off");
  expect_error("hide\n", "line 1", "hide expects medium or the name");
  expect_error("hide red cells\n", "line 1", "unexpected 'cells'");
  expect_error("show medium now\n", "line 1", "unexpected 'now'");
  expect_error("time -1\n", "line 1", "time");
  expect_error("time soon\n", "line 1", "time");
  expect_error("wait\n", "line 1", "wait N");
  expect_error("wait 1.5\n", "line 1", "wait N");
  expect_error("wait -2\n", "line 1", "wait N");
  expect_error("pick 3\n", "line 1", "pick expects X Y");
  expect_error("pick a b\n", "line 1", "pick X");
  expect_error("pick 1 2 3\n", "line 1", "unexpected '3'");
  expect_error("screenshot\n", "line 1", "PATH");
  expect_error("screenshot a.ids\n", "line 1", ".ids");
  expect_error("size 0x10\n", "line 1", "WxH");
  expect_error("size 10\n", "line 1", "WxH");
  expect_error("size 10x20x30\n", "line 1", "WxH");
  expect_error("quit now\n", "line 1", "unexpected");
  expect_error("keyframe\n", "line 1", "keyframe expects");
  expect_error("keyframe -1\n", "line 1", "seconds ≥ 0");
  expect_error("keyframe soon\n", "line 1", "keyframe expects");
  expect_error("keyframe inf\n", "line 1", "keyframe expects");
  expect_error("keyframe 1 2\n", "line 1", "unexpected '2'");
  expect_error("path\n", "line 1", "path expects");
  expect_error("path record\n", "line 1", "path expects");
  expect_error("path save\n", "line 1", "path save expects a FILE");
  expect_error("path load\n", "line 1", "path load expects a FILE");
  expect_error("path clear all\n", "line 1", "unexpected 'all'");
  expect_error("path frame\n", "line 1", "path frame expects");
  expect_error("path frame -1\n", "line 1", "path frame K");
  expect_error("path frame 1.5\n", "line 1", "path frame K");
  expect_error("path frame 10000001\n", "line 1", "path frame K");
  expect_error("path frame 1 2\n", "line 1", "unexpected '2'");
  expect_error("path play 1\n", "line 1", "path play expects A B");
  expect_error("path play x 2\n", "line 1", "path play A");
  expect_error("path play 1 y\n", "line 1", "path play B");
  expect_error("path play 3 2\n", "line 1", "A ≤ B");
  expect_error("path play 1 2 3\n", "line 1", "unexpected '3'");
}

TEST(Script, MissingFileIsAnInputError) {
  EXPECT_THROW(load_script("/nonexistent/dir/script.txt"), InputError);
}

TEST(Script, SizeText) {
  EXPECT_EQ(render::parse_image_size("640x480", "--size"), std::pair(640u, 480u));
  for (const char* wrong : {"16385x1", "x1", "+64x48"}) {
    try {
      (void)render::parse_image_size(wrong, "--size");
      ADD_FAILURE() << "accepted: " << wrong;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), std::string("--size: expected a size WxH with 1 ≤ W, H ≤ 16384, got '") + wrong + "'");
    }
  }
}

}  // namespace
}  // namespace nano::viewer
