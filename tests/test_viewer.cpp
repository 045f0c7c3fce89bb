// test_viewer.cpp: `vgeo view` under Xvfb (Debian xvfb) on lavapipe with the validation layer: a script
// moves the camera, freezes the cut and flies on, switches every view, resizes the window and takes
// screenshots; each screenshot is the PNG `vgeo render` writes for the same camera and settings, byte
// for byte (the same renderer, so no tolerance is needed). Without a display the viewer says so in one
// line that points to `vgeo render`; a bad script line is one line naming the file and the line.
#include <stb/stb_image.h>

#include <filesystem>

#include "../renderer/debug_modes.h"
#include "test_util.h"

namespace vgeo {
namespace {

class Viewer : public ::testing::Test {
 protected:
  // A folder of the test's own: ctest runs the tests of a suite side by side.
  void SetUp() override {
    dir = test::tempDir();
    writeVgeo(test::build(test::asset("horned_cube.obj"), 2), dir + "/horned.vgeo");
  }
  // `vgeo view` of the horned cube in a 3 x 3 grid under a fresh Xvfb display.
  test::RunResult view(const std::string& options) const {
    EXPECT_TRUE(std::filesystem::exists("/usr/bin/xvfb-run")) << "xvfb-run is missing (scripts/setup.sh installs xvfb)";
    return test::runShell("xvfb-run -a -s '-screen 0 1280x1024x24' " + std::string(VGEO_BINARY) + " view " + dir +
                          "/horned.vgeo --grid 3 " + options);
  }
  std::string dir;
};

TEST_F(Viewer, ScriptedScreenshotsAreWhatRenderWrites) {
  const std::string near = "2.5,1.8,3.5,0,0,0", far = "-4,1.2,2.5,0.3,0.1,0";
  struct Shot {
    std::string name, renderOptions;
    uint32_t frame;
  };
  std::vector<Shot> shots;
  std::string script = "# frame command arguments\n0 camera " + near + "\n";
  uint32_t frame = 2;
  auto shoot = [&](const std::string& name, const std::string& renderOptions) {
    script += std::to_string(frame) + " screenshot " + dir + "/" + name + ".png\n";
    shots.push_back({name, renderOptions, frame});
    frame += 2;
  };
  shoot("start", "--camera " + near);
  // Frozen at `near`, flown along a path to `far`: the cut stays the frozen one.
  script += std::to_string(frame) + " freeze on\n" + std::to_string(frame) + " path 5 " + far + "\n";
  frame += 6;
  shoot("frozen", "--camera " + far + " --freeze-camera " + near);
  script += std::to_string(frame) + " mode frozen-diff\n";
  frame++;
  shoot("frozen_diff", "--camera " + far + " --freeze-camera " + near + " --mode frozen-diff");
  script += std::to_string(frame) + " freeze off\n" + std::to_string(frame) + " resize 400x240\n";
  frame += 2;
  for (const DebugMode& m : kDebugModes) {
    script += std::to_string(frame) + " mode " + m.name + "\n";
    frame++;
    shoot(std::string("mode_") + m.name, "--size 400x240 --camera " + far + " --mode " + m.name);
  }
  script += std::to_string(frame) + " mode lit\n" + std::to_string(frame) + " tau 4\n" + std::to_string(frame) +
            " occlusion on\n" + std::to_string(frame) + " patches off\n";
  frame++;
  shoot("settings", "--size 400x240 --camera " + far + " --tau 4 --occlusion on --no-patches");
  // The headlight, and the camera printed (C) as options for `vgeo render` to pass back.
  script += std::to_string(frame) + " key L\n" + std::to_string(frame) + " key C\n";
  script += std::to_string(frame + 1) + " screenshot " + dir + "/headlight.png\n";
  frame += 2;
  script += std::to_string(frame) + " freeze on\n" + std::to_string(frame) + " path 3 " + near + "\n";
  frame += 4;
  script += std::to_string(frame) + " window-screenshot " + dir + "/window.png\n";
  script += std::to_string(frame + 1) + " quit\n";
  const std::string scriptPath = test::writeFile(dir, "script.txt", script);

  // The same script without a window (`render --path`) first: a PNG a frame (its screenshots the viewer's
  // run then writes again).
  const std::string frames = dir + "/frames";
  std::filesystem::create_directories(frames);
  const test::RunResult path = test::runVgeo(
      "render " + dir + "/horned.vgeo --grid 3 --size 320x200 --validate --path " + scriptPath + " -o " + frames);
  ASSERT_EQ(path.exitCode, 0) << path.output;
  const test::RunResult run = view("--size 320x200 --validate --script " + scriptPath);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(run.output.find("validation"), std::string::npos) << run.output;
  for (const Shot& shot : shots) {
    SCOPED_TRACE(shot.name);
    const std::string shown = dir + "/" + shot.name + ".png", rendered = dir + "/" + shot.name + "_render.png";
    const std::string size = shot.renderOptions.find("--size") == std::string::npos ? "--size 320x200 " : "";
    const test::RunResult r =
        test::runVgeo("render " + dir + "/horned.vgeo --grid 3 " + size + shot.renderOptions + " -o " + rendered);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_TRUE(std::filesystem::exists(shown));
    EXPECT_TRUE(test::readFile(shown) == test::readFile(rendered)) << shown << " differs from " << rendered;
    char frame[32];
    std::snprintf(frame, sizeof frame, "/frame_%05u.png", shot.frame);
    EXPECT_TRUE(test::readFile(shown) == test::readFile(frames + frame)) << shown << " differs from " << frame;
  }
  // The camera and light the viewer printed, passed back to `vgeo render`.
  const size_t printed = run.output.find("--camera ");
  ASSERT_NE(printed, std::string::npos) << run.output;
  const std::string options = run.output.substr(printed, run.output.find('\n', printed) - printed);
  EXPECT_NE(options.find("--light "), std::string::npos) << options;
  const test::RunResult r =
      test::runVgeo("render " + dir + "/horned.vgeo --grid 3 --size 400x240 --tau 4 --occlusion on " + "--no-patches " +
                    options + " -o " + dir + "/headlight_render.png");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(test::readFile(dir + "/headlight.png") == test::readFile(dir + "/headlight_render.png"));
  EXPECT_FALSE(test::readFile(dir + "/headlight.png") == test::readFile(dir + "/settings.png"));
  // The window, panel and all (and the frozen frustum), at the size the script gave it.
  EXPECT_GT(std::filesystem::file_size(dir + "/window.png"), 1000u);
}

struct Rgba {
  int width = 0, height = 0;
  std::vector<uint8_t> pixels;
  bool same(const Rgba& o, int x, int y) const {
    return std::equal(&pixels[(size_t(y) * width + x) * 4], &pixels[(size_t(y) * width + x) * 4 + 3],
                      &o.pixels[(size_t(y) * width + x) * 4]);
  }
};
Rgba readPng(const std::string& path) {
  Rgba image;
  int channels = 0;
  uint8_t* p = stbi_load(path.c_str(), &image.width, &image.height, &channels, 4);
  EXPECT_NE(p, nullptr) << path;
  if (p) image.pixels.assign(p, p + size_t(image.width) * image.height * 4);
  stbi_image_free(p);
  return image;
}

// The panel is opaque and drawn once, then copied while it does not change: the window shows the
// picture everywhere but in the panel's rectangle at the top left, and a changed panel is drawn again.
TEST_F(Viewer, ThePanelIsItsRectangleOverThePicture) {
  const std::string script = "0 camera 2.5,1.8,3.5,0,0,0\n4 screenshot " + dir + "/a.png\n4 window-screenshot " + dir +
                             "/a_window.png\n5 mode normal\n8 screenshot " + dir + "/b.png\n8 window-screenshot " +
                             dir + "/b_window.png\n9 quit\n";
  const test::RunResult run = view("--size 900x640 --validate --script " + test::writeFile(dir, "script.txt", script));
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(run.output.find("validation"), std::string::npos) << run.output;
  Rgba panels[2];
  for (int shot = 0; shot < 2; shot++) {
    const std::string name = dir + (shot ? "/b" : "/a");
    const Rgba picture = readPng(name + ".png"), window = readPng(name + "_window.png");
    ASSERT_EQ(picture.width, 900);
    ASSERT_EQ(window.width, 900);
    ASSERT_EQ(window.height, picture.height);
    int x0 = window.width, y0 = window.height, x1 = -1, y1 = -1;
    for (int y = 0; y < window.height; y++)
      for (int x = 0; x < window.width; x++)
        if (!window.same(picture, x, y)) {
          x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
        }
    ASSERT_GE(x1, x0) << name << ": no panel";
    SCOPED_TRACE(name + ": the panel at " + std::to_string(x0) + "," + std::to_string(y0) + " to " +
                 std::to_string(x1) + "," + std::to_string(y1));
    EXPECT_LE(x0, 10);
    EXPECT_LE(y0, 10);
    EXPECT_LT(x1, 8 + 490);
    EXPECT_LT(y1, window.height - 8);
    uint64_t differ = 0;
    for (int y = y0; y <= y1; y++)
      for (int x = x0; x <= x1; x++) differ += !window.same(picture, x, y);
    EXPECT_GT(differ, uint64_t(x1 - x0 + 1) * (y1 - y0 + 1) * 9 / 10) << "the panel is opaque";
    panels[shot] = window;
  }
  // The normal view's legend is another panel.
  uint64_t changed = 0;
  for (int y = 0; y < 400; y++)
    for (int x = 0; x < 440; x++) changed += !panels[0].same(panels[1], x + 8, y + 8);
  EXPECT_GT(changed, 1000u);
}

// Minimised (by twm, a window manager under Xvfb), the viewer draws nothing and takes no script frame;
// restored, it draws what `vgeo render` writes.
TEST_F(Viewer, MinimisedItWaitsAndComesBack) {
  ASSERT_TRUE(std::filesystem::exists("/usr/bin/twm")) << "twm is missing (scripts/setup.sh installs it)";
  const std::string script = "0 camera 2.5,1.8,3.5,0,0,0\n2 minimise 1.5\n3 screenshot " + dir + "/back.png\n4 quit\n";
  const std::string scriptPath = test::writeFile(dir, "script.txt", script);
  // twm's own fonts are not in Debian's xfonts-base ("fixed" is); it places new windows itself.
  const std::string twmrc = test::writeFile(dir, "twmrc",
                                            "TitleFont \"fixed\"\nResizeFont \"fixed\"\nMenuFont \"fixed\"\n"
                                            "IconFont \"fixed\"\nIconManagerFont \"fixed\"\nRandomPlacement\n");
  const test::RunResult run =
      test::runShell("xvfb-run -a -s '-screen 0 1280x1024x24' sh -c 'twm -f " + twmrc +
                     " >/dev/null 2>&1 & sleep 1; timeout 120 " + std::string(VGEO_BINARY) + " view " + dir +
                     "/horned.vgeo --grid 3 --size 320x200 --validate --script " + scriptPath + "'");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(run.output.find("validation"), std::string::npos) << run.output;
  const size_t at = run.output.find("minimised for ");
  ASSERT_NE(at, std::string::npos) << run.output;
  EXPECT_GE(std::stod(run.output.substr(at + 14)), 1.4) << run.output;
  const test::RunResult r =
      test::runVgeo("render " + dir + "/horned.vgeo --grid 3 --size 320x200 --camera 2.5,1.8,3.5,0,0,0 -o " + dir +
                    "/back_render.png");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(test::readFile(dir + "/back.png") == test::readFile(dir + "/back_render.png"));
}

TEST_F(Viewer, WithoutADisplayItSaysSoInOneLine) {
  const test::RunResult r =
      test::runShell("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(VGEO_BINARY) + " view " + dir + "/horned.vgeo");
  EXPECT_EQ(r.exitCode, 5) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find("vgeo render"), std::string::npos) << r.output;
}

TEST_F(Viewer, ABadScriptLineIsOneLineNamingIt) {
  for (const auto& [text, expected] : std::vector<std::pair<std::string, std::string>>{
           {"0 camera 1,2\n", "line 1: camera: expected six numbers"},
           {"4 quit\n2 quit\n", "line 2: frame 2 comes before"},
           {"0 mode bogus\n", "line 1: mode takes a view's name"},
           {"0 fly\n", "line 1: unknown command 'fly'"},
           {"x quit\n", "line 1: a line starts with a frame number"},
           {"0 key Z\n", "line 1: key takes one of the viewer's keys"},
           {"0 resize 10\n", "line 1: resize takes a size WxH"},
           {"0 minimise 0\n", "line 1: minimise takes seconds"},
           {"0 quit now\n", "line 1: quit takes no more than its arguments"}}) {
    SCOPED_TRACE(text);
    const std::string path = test::writeFile(dir, "bad.txt", text);
    const test::RunResult r = test::runVgeo("view " + dir + "/horned.vgeo --script " + path);
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find(path + ": " + expected), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace vgeo
