// bounce-studio from the outside: headless screenshots and option errors.
#include <cstdio>
#include <string>

#include "render_support.h"

namespace bounce::render_test {

namespace fs = std::filesystem;

namespace {

CommandRun run_studio(const std::string& args) {
  return run_command(std::string(BOUNCE_STUDIO) + " " + args);
}

}  // namespace

class StudioCli : public RenderTest {};

TEST_F(StudioCli, ScreenshotsOfEveryViewFromABakeFolder) {
  const fs::path dir = work_dir("screenshots");
  for (const char* view : {"voxels", "patches", "matrix", "error"}) {
    const fs::path png = dir / (std::string(view) + ".png");
    const CommandRun r = run_studio(fixture_bake().string() + " --screenshot " + png.string() +
                                    " --view " + view + " --size 400x300");
    ASSERT_EQ(r.code, 0) << view << ": " << r.output;
    const QImage image(QString::fromStdString(png.string()));
    ASSERT_FALSE(image.isNull()) << view;
    EXPECT_EQ(image.size(), QSize(400, 300)) << view;
    EXPECT_GT(non_uniform_share(image), 0.2) << view << " looks blank";
  }
}

TEST_F(StudioCli, HelpAndVersionNeedNoDisplay) {
  const std::string no_display = "env -u DISPLAY -u WAYLAND_DISPLAY -u QT_QPA_PLATFORM ";
  const std::string studio = std::string(BOUNCE_STUDIO);
  // Without a display the window cannot start: the environment really has none.
  const CommandRun window = run_command(no_display + studio + " --no-such-input-yet");
  EXPECT_NE(window.code, 0) << window.output;
  const CommandRun help = run_command(no_display + studio + " --help");
  EXPECT_EQ(help.code, 0) << help.output;
  EXPECT_NE(help.output.find("--screenshot"), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("--view"), std::string::npos) << help.output;
  const CommandRun version = run_command(no_display + studio + " --version");
  EXPECT_EQ(version.code, 0) << version.output;
  EXPECT_NE(version.output.find("Bounce Studio " BOUNCE_VERSION_TEXT), std::string::npos)
      << version.output;
}

TEST_F(StudioCli, SettingsChangeThePatchCount) {
  // The fixture is --voxel 4; a coarser grid through the studio's settings
  // (headless maps --voxel onto the settings panel) must give fewer patches.
  const fs::path dir = work_dir("settings");
  const CommandRun r =
      run_studio(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box --voxel 2 " +
                 "--screenshot " + (dir / "patches.png").string() +
                 " --view patches --size 320x240 --bake-out " + (dir / "bake").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir / "bake" / "manifest.json");
  const nlohmann::json coarse = nlohmann::json::parse(in);
  const nlohmann::json fine = fixture_manifest();
  EXPECT_EQ(coarse["settings"]["resolved"]["voxel_resolution"], 2);
  EXPECT_EQ(fine["settings"]["resolved"]["voxel_resolution"], 4);
  EXPECT_LT(coarse["counts"]["patches"].get<int>(), fine["counts"]["patches"].get<int>());
  EXPECT_LT(coarse["counts"]["occupied_voxels"].get<int>(),
            fine["counts"]["occupied_voxels"].get<int>());
}

TEST_F(StudioCli, SizeLimitReachesTheBake) {
  // The settings panel's size limit (headless --size-limit sets it as the
  // window's control would) is what the bake uses: the manifest's requested
  // and resolved size_limit.
  const fs::path dir = work_dir("size-limit");
  const CommandRun r =
      run_studio(std::string(BOUNCE_RESOURCE_DIR) + "/scenes/cornell-box --voxel 2 --codec ours " +
                 "--size-limit 0.3 --screenshot " + (dir / "patches.png").string() +
                 " --view patches --size 320x240 --bake-out " + (dir / "bake").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir / "bake" / "manifest.json");
  const nlohmann::json m = nlohmann::json::parse(in);
  EXPECT_DOUBLE_EQ(m["settings"]["requested"]["size_limit"].get<double>(), 0.3) << m["settings"];
  EXPECT_DOUBLE_EQ(m["settings"]["resolved"]["size_limit"].get<double>(), 0.3) << m["settings"];
  // Out of range: one line naming the option.
  const CommandRun bad = run_studio(std::string(BOUNCE_RESOURCE_DIR) +
                                    "/scenes/cornell-box --voxel 2 --size-limit 2 --screenshot " +
                                    (dir / "x.png").string());
  EXPECT_EQ(bad.code, 1) << bad.output;
  EXPECT_NE(bad.output.find("--size-limit"), std::string::npos) << bad.output;
}

TEST_F(StudioCli, BadOptionsFailWithOneLine) {
  // One case per kind of check: option values, then values against the bake.
  const fs::path dir = work_dir("errors");
  const std::string shot = " --screenshot " + (dir / "x.png").string();
  const struct {
    std::string args, names;
  } cases[] = {
      {fixture_bake().string() + shot + " --view nonsense", "--view"},
      {fixture_bake().string() + shot + " --view preview --sphere 0,1", "--sphere"},
      {fixture_bake().string() + shot + " --view voxels --probes", "--probes"},
      {fixture_bake().string() + shot + " --view matrix --object x.obj", "--object"},
      // The fixture was baked without light probes.
      {fixture_bake().string() + shot + " --view preview --probes", "light_probes"},
  };
  for (const auto& c : cases) {
    const CommandRun r = run_studio(c.args);
    EXPECT_EQ(r.code, 1) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find("bounce-studio: error: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.names), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "x.png")) << c.args;
  }
}

}  // namespace bounce::render_test
