#include "headless.h"

#include <memory>

#include <QApplication>
#include <QSaveFile>
#include <QTemporaryDir>

#include "bake_job.h"
#include "error_view.h"
#include "matrix_view.h"
#include "patch_view.h"
#include "settings_panel.h"
#include "voxel_view.h"
#include "vtk_error_capture.h"

namespace bounce::studio {

namespace {

void settle() {
  // Let layouts, resizes and the first OpenGL paint happen.
  for (int k = 0; k < 5; ++k) QApplication::processEvents();
}

}  // namespace

void take_screenshot(const ScreenshotRequest& r) {
  if (r.view != "voxels" && r.view != "patches" && r.view != "matrix" && r.view != "error")
    throw Error("--view",
                "must be voxels, patches, matrix or error, got '" + r.view.toStdString() + "'");
  if (r.width < 64 || r.height < 64 || r.width > 8192 || r.height > 8192)
    throw Error("--size", "must be WxH with each side between 64 and 8192");

  std::shared_ptr<const views::BakeViewData> data;
  QTemporaryDir temp;
  if (is_bake_folder(r.input.toStdString())) {
    data = views::load_bake_view_data(r.input.toStdString());
  } else {
    // The same mapping from options to BakeSettings as the window's panel.
    SettingsPanel panel;
    if (r.voxel > 0) panel.set_grid(SettingsPanel::GridChoice::VoxelSize, r.voxel);
    if (r.patches_total > 0)
      panel.set_grid(SettingsPanel::GridChoice::PatchesTotal, r.patches_total);
    if (!r.codec.isEmpty()) {
      const std::string c = r.codec.toStdString();
      if (c != "auto" && c != "dense" && c != "paper" && c != "ours")
        throw Error("--codec", "must be auto, dense, paper or ours, got '" + c + "'");
      panel.set_codec(c == "dense"   ? CodecChoice::Dense
                      : c == "paper" ? CodecChoice::Paper
                      : c == "ours"  ? CodecChoice::Ours
                                     : CodecChoice::Auto);
    }
    if (r.bake_out.isEmpty() && !temp.isValid())
      throw Error("--bake-out", "no temporary folder available; give one");
    const QString folder = r.bake_out.isEmpty() ? temp.path() + "/bake" : r.bake_out;
    Progress progress;
    data =
        run_bake_job(r.input.toStdString(), panel.settings(), folder.toStdString(), progress).data;
  }

  QWidget* view = nullptr;
  std::unique_ptr<QWidget> owner;
  if (r.view == "voxels") {
    auto* v = new views::VoxelView;
    owner.reset(v);
    v->set_data(data);
    view = v;
  } else if (r.view == "patches") {
    auto* v = new views::PatchView;
    owner.reset(v);
    v->set_data(data);
    if (r.pick_patch >= 0) {
      if (static_cast<std::size_t>(r.pick_patch) >= data->patch_count())
        throw Error("--pick-patch", "the bake has " + std::to_string(data->patch_count()) +
                                        " patches, got " + std::to_string(r.pick_patch));
      v->select_patch(r.pick_patch);
    }
    view = v;
  } else if (r.view == "error") {
    auto* v = new views::ErrorView;
    owner.reset(v);
    v->set_data(data);
    view = v;
  } else {
    auto* v = new views::MatrixView;
    owner.reset(v);
    v->set_data(data);
    view = v;
  }
  view->resize(r.width, r.height);
  view->show();
  settle();
  if (auto* m = dynamic_cast<views::MatrixView*>(view)) m->fit();
  if (auto* e = dynamic_cast<views::ErrorView*>(view)) {
    e->element_panel()->fit();
    e->block_panel()->fit();
  }
  settle();
  const QImage image = view->grab().toImage();
  const std::vector<std::string> vtk = views::VtkErrorCapture::messages();
  if (!vtk.empty()) throw Error("render", "VTK reported: " + vtk.front());
  QSaveFile file(r.screenshot);
  if (!file.open(QIODevice::WriteOnly) || !image.save(&file, "PNG") || !file.commit())
    throw Error(r.screenshot.toStdString(),
                "cannot write the PNG: " + file.errorString().toStdString());
}

}  // namespace bounce::studio
