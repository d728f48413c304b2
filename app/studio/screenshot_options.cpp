#include "screenshot_options.h"

#include <cmath>
#include <string>

#include "bounce/error.h"

namespace bounce::studio {

namespace {

std::string flag(const QCommandLineOption& option) {
  return "--" + option.names().front().toStdString();
}

// A whole number >= 0, or `fallback` when the option is not given.
int integer(const QCommandLineParser& parser, const QCommandLineOption& option, int fallback) {
  if (!parser.isSet(option)) return fallback;
  bool ok = false;
  const int v = parser.value(option).toInt(&ok);
  if (!ok || v < 0)
    throw Error(flag(option),
                "must be a whole number >= 0, got '" + parser.value(option).toStdString() + "'");
  return v;
}

// x,y,z: three finite numbers.
void point(const QCommandLineParser& parser, const QCommandLineOption& option, float& x, float& y,
           float& z) {
  const QStringList xyz = parser.value(option).split(',');
  bool ok = xyz.size() == 3;
  float* coordinate[3] = {&x, &y, &z};
  for (int k = 0; ok && k < 3; ++k) {
    *coordinate[k] = xyz[k].toFloat(&ok);
    ok = ok && std::isfinite(*coordinate[k]);
  }
  if (!ok)
    throw Error(flag(option),
                "must be x,y,z (three numbers), got '" + parser.value(option).toStdString() + "'");
}

}  // namespace

void ScreenshotOptions::add_to(QCommandLineParser& parser) const {
  parser.addOptions({screenshot_, view_, size_, voxel_, patches_total_, codec_, size_limit_,
                     bake_out_, pick_, light_, report_, passes_, probes_, sphere_, object_,
                     compare_codec_});
}

ScreenshotRequest ScreenshotOptions::read(const QCommandLineParser& parser,
                                          const QStringList& inputs) const {
  if (inputs.size() != 1) throw Error("--screenshot", "needs exactly one scene or bake folder");
  if (parser.isSet(voxel_) && parser.isSet(patches_total_))
    throw Error("--patches-total", "cannot be combined with --voxel");
  ScreenshotRequest r;
  r.input = inputs.front();
  r.screenshot = parser.value(screenshot_);
  r.view = parser.value(view_);
  read_size(parser, r);
  r.voxel = integer(parser, voxel_, 0);
  r.patches_total = integer(parser, patches_total_, 0);
  r.codec = parser.value(codec_);
  r.size_limit = parser.value(size_limit_);
  r.bake_out = parser.value(bake_out_);
  r.pick_patch = integer(parser, pick_, -1);
  r.compare_codec = parser.value(compare_codec_);
  r.report = parser.value(report_);
  read_preview(parser, r);
  return r;
}

void ScreenshotOptions::read_size(const QCommandLineParser& parser, ScreenshotRequest& r) const {
  const QStringList wh = parser.value(size_).split('x');
  bool ok_w = false, ok_h = false;
  if (wh.size() == 2) {
    r.width = wh[0].toInt(&ok_w);
    r.height = wh[1].toInt(&ok_h);
  }
  if (!ok_w || !ok_h)
    throw Error("--size",
                "must be WxH, e.g. 1024x768, got '" + parser.value(size_).toStdString() + "'");
}

void ScreenshotOptions::read_preview(const QCommandLineParser& parser, ScreenshotRequest& r) const {
  r.passes = parser.value(passes_);
  r.has_light = parser.isSet(light_);
  if (r.has_light) point(parser, light_, r.light_x, r.light_y, r.light_z);
  r.has_sphere = parser.isSet(sphere_);
  if (r.has_sphere) point(parser, sphere_, r.sphere_x, r.sphere_y, r.sphere_z);
  r.probes = parser.isSet(probes_);
  r.object = parser.value(object_);
}

}  // namespace bounce::studio
