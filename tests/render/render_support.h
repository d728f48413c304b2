#pragma once
// Shared by the render tests: the fixture bake, picture statistics, running
// the command-line programs, and a check that VTK said nothing while a test
// rendered.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>

#include <QApplication>
#include <QImage>
#include <nlohmann/json.hpp>

#include "bake_view_data.h"
#include "vtk_error_capture.h"

namespace bounce::render_test {

inline std::filesystem::path fixture_bake() { return BOUNCE_RENDER_BAKE; }

inline std::shared_ptr<const views::BakeViewData> load_fixture() {
  return views::load_bake_view_data(fixture_bake());
}

inline nlohmann::json fixture_manifest() {
  std::ifstream in(fixture_bake() / "manifest.json");
  return nlohmann::json::parse(in);
}

struct CommandRun {
  int code = -1;
  std::string output;  // stdout and stderr
};

// Runs a shell command line, stdout and stderr together.
inline CommandRun run_command(const std::string& command_line) {
  CommandRun r;
  FILE* pipe = ::popen((command_line + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) r.output += buffer;
  const int status = ::pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// A fresh, empty folder for one test's outputs.
inline std::filesystem::path work_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(BOUNCE_RENDER_WORK) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline void settle() {
  for (int k = 0; k < 5; ++k) QApplication::processEvents();
}

// Pixels within `tolerance` of `rgb` in every channel.
inline std::size_t count_colour(const QImage& image, std::array<int, 3> rgb, int tolerance = 2) {
  std::size_t count = 0;
  const QImage im = image.convertToFormat(QImage::Format_RGB32);
  for (int y = 0; y < im.height(); ++y)
    for (int x = 0; x < im.width(); ++x) {
      const QRgb p = im.pixel(x, y);
      if (std::abs(qRed(p) - rgb[0]) <= tolerance && std::abs(qGreen(p) - rgb[1]) <= tolerance &&
          std::abs(qBlue(p) - rgb[2]) <= tolerance)
        ++count;
    }
  return count;
}

// Share of pixels that differ from the most common colour: 0 for a blank picture.
inline double non_uniform_share(const QImage& image) {
  const QImage im = image.convertToFormat(QImage::Format_RGB32);
  std::map<QRgb, std::size_t> histogram;
  for (int y = 0; y < im.height(); ++y)
    for (int x = 0; x < im.width(); ++x) ++histogram[im.pixel(x, y)];
  std::size_t top = 0;
  for (const auto& [colour, count] : histogram) top = std::max(top, count);
  const auto total = static_cast<double>(im.width()) * im.height();
  return total > 0 ? 1.0 - static_cast<double>(top) / total : 0.0;
}

// Every test fails on a VTK error or warning printed while it ran.
class RenderTest : public ::testing::Test {
 protected:
  void SetUp() override { views::VtkErrorCapture::clear(); }
  void TearDown() override {
    for (const std::string& m : views::VtkErrorCapture::messages()) ADD_FAILURE() << m;
  }
};

}  // namespace bounce::render_test
