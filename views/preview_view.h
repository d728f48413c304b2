#pragma once
// The studio's Preview tab: the live preview (PreviewWidget) under a row of
// switches for its passes (direct, indirect, ambient occlusion), for the
// light probes' overlay and the probe-lit sphere, and a line on how to move
// the light, the sphere and the camera.
#include <memory>

#include <QWidget>

#include "bake_view_data.h"

class QCheckBox;
class QLabel;
class QPushButton;

namespace bounce::views {

class PreviewWidget;
class ViewJobs;

class PreviewView : public QWidget {
  Q_OBJECT
 public:
  // The preview solves on `jobs` when a solve is too slow for the UI thread.
  explicit PreviewView(ViewJobs& jobs, QWidget* parent = nullptr);
  // A bake the preview cannot show (no scene on disk, no point or spot
  // light) leaves the preview empty and says why in the tab.
  void set_data(std::shared_ptr<const BakeViewData> data);
  PreviewWidget* preview() const { return preview_; }

 private:
  void apply_switches();
  void show_help();
  void choose_object();

  PreviewWidget* preview_;
  QCheckBox* direct_;
  QCheckBox* indirect_;
  QCheckBox* ao_;
  QCheckBox* normal_maps_;
  QCheckBox* probes_;
  QCheckBox* sphere_;
  QPushButton* load_object_;
  QLabel* status_;
};

}  // namespace bounce::views
