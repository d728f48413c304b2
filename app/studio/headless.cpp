#include "headless.h"

#include <memory>
#include <tuple>

#include <QApplication>
#include <QSaveFile>
#include <QTemporaryDir>

#include "bake_job.h"
#include "error_view.h"
#include "matrix_view.h"
#include "patch_view.h"
#include "preview_widget.h"
#include "report_screenshot.h"
#include "settings_panel.h"
#include "view_jobs.h"
#include "voxel_view.h"
#include "vtk_error_capture.h"

namespace bounce::studio {

namespace {

void settle() {
  // Let layouts, resizes and the first OpenGL paint happen.
  for (int k = 0; k < 5; ++k) QApplication::processEvents();
}

// "direct,indirect,ao" (any subset; empty: all of them).
views::PreviewWidget::Passes preview_passes(const QString& list) {
  views::PreviewWidget::Passes p;
  if (list.isEmpty()) return p;
  p.direct = p.indirect = p.ao = false;
  for (const QString& name : list.split(',')) {
    if (name == "direct")
      p.direct = true;
    else if (name == "indirect")
      p.indirect = true;
    else if (name == "ao")
      p.ao = true;
    else
      throw Error("--passes", "names direct, indirect or ao, separated by commas; got '" +
                                  name.toStdString() + "'");
  }
  return p;
}

// Every option against the view it belongs to, before any bake.
void check_request(const ScreenshotRequest& r) {
  if (r.view != "voxels" && r.view != "patches" && r.view != "matrix" && r.view != "error" &&
      r.view != "preview" && r.view != "report")
    throw Error("--view", "must be voxels, patches, matrix, error, preview or report, got '" +
                              r.view.toStdString() + "'");
  if (!r.report.isEmpty() && r.view != "report")
    throw Error("--report", "is the report view's data: use it with --view report");
  if (!r.compare_codec.isEmpty() && r.view != "error")
    throw Error("--compare-codec", "switches the error view's codec: use it with --view error");
  if (r.has_light && r.view != "preview")
    throw Error("--light", "moves the preview's light: use it with --view preview");
  if (!r.passes.isEmpty() && r.view != "preview")
    throw Error("--passes", "switches the preview's passes: use it with --view preview");
  if ((r.probes || r.has_sphere || !r.object.isEmpty()) && r.view != "preview")
    throw Error(r.probes       ? "--probes"
                : r.has_sphere ? "--sphere"
                               : "--object",
                "draws in the preview's picture: use it with --view preview");
  preview_passes(r.passes);  // bad names fail before any bake
  if (r.width < 64 || r.height < 64 || r.width > 8192 || r.height > 8192)
    throw Error("--size", "must be WxH with each side between 64 and 8192");
}

// The bake folder given, or the scene baked (into --bake-out or `temp`).
std::shared_ptr<const views::BakeViewData> load_or_bake(const ScreenshotRequest& r,
                                                        const QTemporaryDir& temp) {
  if (is_bake_folder(r.input.toStdString()))
    return views::load_bake_view_data(r.input.toStdString());
  // The same mapping from options to BakeSettings as the window's panel.
  SettingsPanel panel;
  if (r.voxel > 0) panel.set_grid(SettingsPanel::GridChoice::VoxelSize, r.voxel);
  if (r.patches_total > 0) panel.set_grid(SettingsPanel::GridChoice::PatchesTotal, r.patches_total);
  for (const auto& [option, setting, text] :
       {std::tuple<const char*, const char*, QString>{"--codec", "codec", r.codec},
        {"--size-limit", "size_limit", r.size_limit}}) {
    if (text.isEmpty()) continue;
    try {
      // The panel's spin boxes would clamp a value out of range: check it
      // as a bake would first, so a wrong value is an error, not another bake.
      const SettingRow& row = setting_row(setting);
      BakeSettings check;
      row.set(check, parse_setting(row, text.toStdString()));
      check.validate();
      panel.set(setting, text.toStdString());
    } catch (const BakeSettings::InvalidSetting& e) {
      throw Error(option, e.what());
    }
  }
  if (r.bake_out.isEmpty() && !temp.isValid())
    throw Error("--bake-out", "no temporary folder available; give one");
  const QString folder = r.bake_out.isEmpty() ? temp.path() + "/bake" : r.bake_out;
  Progress progress;
  return run_bake_job(r.input.toStdString(), panel.settings(), folder.toStdString(), progress).data;
}

// The views own themselves through `owner` from the start, so that an error
// while setting one up deletes it.
void make_preview_view(const ScreenshotRequest& r, std::shared_ptr<const views::BakeViewData> data,
                       views::ViewJobs& jobs, std::unique_ptr<QWidget>& owner) {
  auto* v = new views::PreviewWidget(jobs);
  owner.reset(v);
  v->set_data(data);
  v->set_passes(preview_passes(r.passes));
  if (r.has_light) v->set_light_position({r.light_x, r.light_y, r.light_z}, true);
  const bool object = r.has_sphere || !r.object.isEmpty();
  if ((r.probes || object) && !v->has_probes())
    throw Error(r.input.toStdString(),
                "has no light probes to draw: bake it with the setting light_probes on");
  v->set_probes_shown(r.probes);
  if (!r.object.isEmpty()) v->load_object(r.object.toStdString());
  if (r.has_sphere) v->set_sphere_position({r.sphere_x, r.sphere_y, r.sphere_z});
  v->set_sphere_shown(object);
}

void make_error_view(const ScreenshotRequest& r, std::shared_ptr<const views::BakeViewData> data,
                     views::ViewJobs& jobs, std::unique_ptr<QWidget>& owner) {
  auto* v = new views::ErrorView(jobs);
  owner.reset(v);
  v->set_data(data);
  if (!r.compare_codec.isEmpty()) {
    if (r.compare_codec != "paper" && r.compare_codec != "ours")
      throw Error("--compare-codec",
                  "must be paper or ours, got '" + r.compare_codec.toStdString() + "'");
    // The comparison runs on the view jobs: wait for it.
    bool done = false;
    QString failure;
    QObject::connect(v, &views::ErrorView::comparison_ready, [&] { done = true; });
    QObject::connect(v, &views::ErrorView::comparison_failed, [&](const QString& why) {
      failure = why;
      done = true;
    });
    v->compare(
        r.compare_codec == "paper" ? CodecChoice::LargestEntries : CodecChoice::LightWeighted,
        std::nullopt);
    while (!done) QApplication::processEvents(QEventLoop::WaitForMoreEvents);
    if (!failure.isEmpty()) throw Error("--compare-codec", failure.toStdString());
  }
}

void make_view(const ScreenshotRequest& r, std::shared_ptr<const views::BakeViewData> data,
               views::ViewJobs& jobs, std::unique_ptr<QWidget>& owner) {
  if (r.view == "voxels") {
    auto* v = new views::VoxelView;
    owner.reset(v);
    v->set_data(data);
  } else if (r.view == "patches") {
    auto* v = new views::PatchView(jobs);
    owner.reset(v);
    v->set_data(data);
    if (r.pick_patch >= 0) {
      if (static_cast<std::size_t>(r.pick_patch) >= data->patch_count())
        throw Error("--pick-patch", "the bake has " + std::to_string(data->patch_count()) +
                                        " patches, got " + std::to_string(r.pick_patch));
      v->select_patch(r.pick_patch);
    }
  } else if (r.view == "preview") {
    make_preview_view(r, std::move(data), jobs, owner);
  } else if (r.view == "error") {
    make_error_view(r, std::move(data), jobs, owner);
  } else {
    auto* v = new views::MatrixView;
    owner.reset(v);
    v->set_data(data);
  }
}

// The view at the requested size, once shown and fitted, as a picture.
QImage capture(QWidget* view, const ScreenshotRequest& r) {
  view->resize(r.width, r.height);
  view->show();
  settle();
  if (auto* m = dynamic_cast<views::MatrixView*>(view)) m->fit();
  if (auto* e = dynamic_cast<views::ErrorView*>(view)) {
    e->element_panel()->fit();
    e->block_panel()->fit();
  }
  settle();
  if (auto* p = dynamic_cast<views::PreviewWidget*>(view)) {
    p->measure_frame_ms(10);           // so the overlay's frame rate is a measured one
    QImage image = p->render_image();  // grabFramebuffer: the GL picture with its overlay
    if (!p->gl_error().isEmpty()) throw Error("preview", p->gl_error().toStdString());
    return image;
  }
  return view->grab().toImage();
}

}  // namespace

void take_screenshot(const ScreenshotRequest& r) {
  check_request(r);
  if (r.view == "report") {
    take_report_screenshot(r);
    return;
  }
  QTemporaryDir temp;
  std::shared_ptr<const views::BakeViewData> data = load_or_bake(r, temp);
  // The views' computations run here; the picture is taken once they are
  // shown.
  views::ViewJobs jobs;
  std::unique_ptr<QWidget> owner;
  make_view(r, std::move(data), jobs, owner);
  jobs.wait_idle();
  save_view_png(capture(owner.get(), r), r.screenshot);
}

void save_view_png(const QImage& image, const QString& path) {
  const std::vector<std::string> vtk = views::VtkErrorCapture::messages();
  if (!vtk.empty()) throw Error("render", "VTK reported: " + vtk.front());
  QSaveFile file(path);
  if (!file.open(QIODevice::WriteOnly) || !image.save(&file, "PNG") || !file.commit())
    throw Error(path.toStdString(), "cannot write the PNG: " + file.errorString().toStdString());
}

}  // namespace bounce::studio
