#pragma once
// Shared by the render tests: the fixture bake, picture statistics, and a
// check that VTK said nothing while a test rendered.
#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

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
