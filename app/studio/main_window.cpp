#include "main_window.h"

#include <QAction>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSettings>
#include <QStatusBar>
#include <QTabWidget>
#include <QUrl>
#include <QVBoxLayout>

#include "error_source_link.h"
#include "error_view.h"
#include "matrix_view.h"
#include "mesh_density_panel.h"
#include "patch_view.h"
#include "preview_view.h"
#include "preview_widget.h"
#include "report_controller.h"
#include "report_view.h"
#include "settings_panel.h"
#include "view_jobs.h"
#include "voxel_view.h"

namespace bounce::studio {

namespace {

constexpr int kMaxRecent = 8;

QString eta_text(double seconds) {
  if (seconds < 0.0) return QObject::tr("ETA ...");
  if (seconds < 90.0) return QObject::tr("ETA %1 s").arg(static_cast<int>(seconds + 0.5));
  return QObject::tr("ETA %1 min").arg(seconds / 60.0, 0, 'f', 1);
}

}  // namespace

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent),
      jobs_(new views::ViewJobs(this)),
      settings_(new SettingsPanel(this)),
      meshes_(new MeshDensityPanel(this)),
      controller_(new BakeController(*jobs_, this)),
      tabs_(new QTabWidget(this)),
      voxel_view_(new views::VoxelView(this)),
      patch_view_(new views::PatchView(*jobs_, this)),
      matrix_view_(new views::MatrixView(this)),
      error_view_(new views::ErrorView(*jobs_, this)),
      preview_view_(new views::PreviewView(*jobs_, this)),
      bake_button_(new QPushButton(tr("Bake"), this)),
      cancel_button_(new QPushButton(tr("Cancel"), this)),
      stage_bars_(new QVBoxLayout),
      scene_label_(new QLabel(tr("No scene: File > Open, or drop a scene here"), this)) {
  setWindowTitle(tr("Bounce Studio"));
  setAcceptDrops(true);
  tabs_->addTab(voxel_view_, tr("Voxels"));
  tabs_->addTab(patch_view_, tr("Patches"));
  tabs_->addTab(matrix_view_, tr("Matrix"));
  tabs_->addTab(error_view_, tr("Compression error"));
  tabs_->addTab(preview_view_, tr("Preview"));
  setCentralWidget(tabs_);

  auto* panel = new QWidget(this);
  auto* layout = new QVBoxLayout(panel);
  scene_label_->setWordWrap(true);
  layout->addWidget(scene_label_);
  layout->addWidget(settings_);
  auto* buttons = new QHBoxLayout;
  bake_button_->setToolTip(tr("Bake the scene with these settings (on a worker thread)"));
  cancel_button_->setToolTip(tr("Stop the bake at its next check; nothing is written"));
  buttons->addWidget(bake_button_);
  buttons->addWidget(cancel_button_);
  layout->addLayout(buttons);
  layout->addLayout(stage_bars_);
  layout->addStretch(1);
  auto* dock = new QDockWidget(tr("Bake"), this);
  dock->setObjectName("bake_dock");
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
  auto* scroll = new QScrollArea(dock);
  scroll->setWidgetResizable(true);
  scroll->setWidget(panel);
  dock->setWidget(scroll);
  addDockWidget(Qt::LeftDockWidgetArea, dock);
  cancel_button_->setEnabled(false);
  bake_button_->setEnabled(false);

  build_menus();
  build_report_tab();
  build_mesh_dock();
  views::link_error_sources(
      patch_view_, matrix_view_, [this] { show_tab(Tab::Matrix); },
      [this] { show_tab(Tab::Patches); });
  connect(bake_button_, &QPushButton::clicked, this, &MainWindow::start_bake);
  connect(cancel_button_, &QPushButton::clicked, this, [this] {
    controller_->cancel();
    statusBar()->showMessage(tr("Cancelling..."));
  });
  connect(controller_, &BakeController::stage_progress, this, &MainWindow::on_stage_progress);
  connect(controller_, &BakeController::finished, this, &MainWindow::on_bake_finished);
  connect(controller_, &BakeController::partial, this, &MainWindow::show_partial);
  connect(controller_, &BakeController::failed, this, [this](const QString& message) {
    set_busy(false);
    show_error(tr("Bake failed"), message);
  });
  connect(controller_, &BakeController::cancelled, this, [this] {
    set_busy(false);
    statusBar()->showMessage(tr("Bake cancelled"));
  });

  QSettings store;
  settings_->load(store);
  restoreGeometry(store.value("window/geometry").toByteArray());
  restoreState(store.value("window/state").toByteArray());
}

MainWindow::~MainWindow() = default;

void MainWindow::build_menus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(
      tr("&Open scene..."), this,
      [this] {
        const QString path = QFileDialog::getOpenFileName(
            this, tr("Open scene"), QString(),
            tr("Scenes (scene.json *.obj *.ply *.gltf *.glb);;All files (*)"));
        if (!path.isEmpty()) open(path);
      },
      QKeySequence::Open);
  file->addAction(tr("Open &bake folder..."), this, [this] {
    const QString dir = QFileDialog::getExistingDirectory(this, tr("Open bake folder"));
    if (!dir.isEmpty()) open(dir);
  });
  recent_menu_ = file->addMenu(tr("Open &recent"));
  rebuild_recent_menu();
  export_action_ = file->addAction(tr("&Export bake..."), this, &MainWindow::export_bake_folder);
  export_action_->setEnabled(false);
  export_glb_action_ =
      file->addAction(tr("Export lit mesh as &glTF..."), this, &MainWindow::export_lit_glb);
  export_glb_action_->setEnabled(false);
  file->addSeparator();
  file->addAction(tr("&Quit"), this, &QWidget::close, QKeySequence::Quit);
}

void MainWindow::build_report_tab() {
  report_view_ = new views::ReportView(this);
  report_controller_ = new ReportController(*jobs_, this);
  tabs_->addTab(report_view_, tr("Report"));
  connect(report_view_, &views::ReportView::run_requested, this, [this] {
    if (scene_path_.isEmpty()) {
      show_error(tr("No scene"), tr("Open a scene first: the sweep bakes it."));
      return;
    }
    report_view_->set_busy(true);
    report_view_->set_status(tr("Running the quick sweep of %1...").arg(scene_path_));
    report_controller_->start(scene_path_);
  });
  connect(report_view_, &views::ReportView::open_requested, this, [this] {
    const QString file = QFileDialog::getOpenFileName(this, tr("Open report"), QString(),
                                                      tr("Reports (report.json *.json)"));
    if (file.isEmpty()) return;
    try {
      report_view_->set_report(std::make_shared<const ReportData>(read_report(file.toStdString())));
    } catch (const std::exception& e) {
      show_error(tr("Cannot read report"), QString::fromStdString(e.what()));
    }
  });
  connect(report_controller_, &ReportController::progress, this,
          [this](const QString& stage, double fraction) {
            report_view_->set_status(
                tr("Report: %1 %2%").arg(stage).arg(static_cast<int>(100.0 * fraction)));
          });
  connect(report_controller_, &ReportController::finished, this,
          [this](std::shared_ptr<const ReportData> report) {
            report_view_->set_busy(false);
            report_view_->set_report(std::move(report));
          });
  connect(report_controller_, &ReportController::failed, this, [this](const QString& message) {
    report_view_->set_busy(false);
    report_view_->set_status(message);
  });
  connect(report_view_, &views::ReportView::row_clicked, this, [this](int row) {
    const auto& report = report_view_->report();
    if (!report || row < 0 || static_cast<std::size_t>(row) >= report->rows.size()) return;
    settings_->apply(report_row_settings(report->rows[static_cast<std::size_t>(row)]));
    statusBar()->showMessage(tr("Settings of the clicked point loaded: press Bake to bake them"));
  });
}

void MainWindow::build_mesh_dock() {
  auto* dock = new QDockWidget(tr("Meshes"), this);
  dock->setObjectName("mesh_dock");
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
  dock->setWidget(meshes_);
  addDockWidget(Qt::RightDockWidgetArea, dock);
  connect(meshes_, &MeshDensityPanel::rebake_requested, this, &MainWindow::start_bake);
}

void MainWindow::show_meshes(const views::BakeViewData& bake, bool editable) {
  try {
    meshes_->show_meshes(manifest_meshes(bake.bake), editable);
  } catch (const std::exception& e) {
    meshes_->clear();
    statusBar()->showMessage(tr("Mesh list: %1").arg(QString::fromStdString(e.what())));
  }
}

void MainWindow::rebuild_recent_menu() {
  recent_menu_->clear();
  const QStringList recent = QSettings().value("recent").toStringList();
  for (const QString& path : recent)
    recent_menu_->addAction(path, this, [this, path] { open(path); });
  recent_menu_->setEnabled(!recent.isEmpty());
}

void MainWindow::open(const QString& path) {
  const QFileInfo info(path);
  if (!info.exists()) {
    show_error(tr("Cannot open"), tr("%1: no such file or folder").arg(path));
    return;
  }
  QSettings store;
  QStringList recent = store.value("recent").toStringList();
  recent.removeAll(info.absoluteFilePath());
  recent.prepend(info.absoluteFilePath());
  while (recent.size() > kMaxRecent) recent.removeLast();
  store.setValue("recent", recent);
  rebuild_recent_menu();

  if (is_bake_folder(path.toStdString())) {
    try {
      const auto bake = views::load_bake_view_data(path.toStdString());
      show_data(bake);
      // No scene held to bake again: the densities are shown, not edited.
      show_meshes(*bake, false);
      scene_label_->setText(tr("Bake folder %1").arg(info.absoluteFilePath()));
      scene_path_.clear();
      bake_button_->setEnabled(false);
    } catch (const std::exception& e) {
      show_error(tr("Cannot read bake folder"), QString::fromStdString(e.what()));
    }
    return;
  }
  scene_path_ = info.absoluteFilePath();
  scene_label_->setText(tr("Scene %1").arg(scene_path_));
  bake_button_->setEnabled(!controller_->busy());
  // Opening reads the scene afresh (it may have changed on disk): a full
  // bake with the scene's own densities, unless the cache holds one.
  if (!controller_->busy()) {
    last_job_.reset();
    meshes_->clear();
  }
  start_bake();
}

void MainWindow::show_data(std::shared_ptr<const views::BakeViewData> bake) {
  voxel_view_->set_data(bake);
  patch_view_->set_data(bake);
  matrix_view_->set_data(bake);
  error_view_->set_data(bake);
  preview_view_->set_data(bake);
  // The preview may decline a bake (no point or spot light to move).
  export_glb_action_->setEnabled(preview_view_->preview()->vertex_count() > 0);
}

void MainWindow::show_tab(Tab tab) { tabs_->setCurrentIndex(static_cast<int>(tab)); }

void MainWindow::on_bake_finished(std::shared_ptr<const BakeJobResult> job) {
  set_busy(false);
  last_job_ = job;
  export_action_->setEnabled(true);
  show_data(job->data);
  show_meshes(*job->data, true);
  if (job->reused) {
    statusBar()->showMessage(
        tr("Opened the cached bake %1: same scene contents and settings, nothing baked")
            .arg(QString::fromStdString(job->folder.string())));
    return;
  }
  const RebakePlan& plan = job->result->plan;
  const QString rerun = plan.first == BakeStage::Geometry ? QString()
                        : plan.first == BakeStage::None
                            ? tr(" (no stage affected: bake reused)")
                            : tr(" (re-ran from %1: %2)")
                                  .arg(QString::fromUtf8(to_string(plan.first)),
                                       QString::fromStdString(plan.reasons.front()));
  const QString note =
      job->cache_note.empty()
          ? QString()
          : tr("; cached bake not reused: %1").arg(QString::fromStdString(job->cache_note));
  statusBar()->showMessage(tr("Baked %1 patches in %2 s%3%4")
                               .arg(job->data->patch_count())
                               .arg(job->result->total_seconds, 0, 'f', 2)
                               .arg(rerun, note));
}

void MainWindow::show_partial(std::shared_ptr<const views::BakeViewData> bake) {
  // The views that can draw a bake in progress; the others keep what they
  // show until the bake ends.
  voxel_view_->set_data(bake);
  if (bake->patch_count() > 0) patch_view_->set_data(bake);
  statusBar()->showMessage(
      bake->patch_count() > 0
          ? tr("Baking %1: %2 patches shown, form factors and transport running...")
                .arg(scene_path_)
                .arg(bake->patch_count())
          : tr("Baking %1: voxel grid shown (%2 voxels)...")
                .arg(scene_path_)
                .arg(bake->voxels.size()));
}

void MainWindow::start_bake() {
  if (scene_path_.isEmpty() || controller_->busy()) return;
  QSettings store;
  settings_->save(store);
  const BakeSettings settings = settings_->settings();
  try {
    settings.validate();
  } catch (const std::exception& e) {
    show_error(tr("Invalid setting"), QString::fromStdString(e.what()));
    return;
  }
  while (QLayoutItem* item = stage_bars_->takeAt(0)) {
    if (QLayout* row = item->layout()) {
      while (QLayoutItem* w = row->takeAt(0)) {
        delete w->widget();
        delete w;
      }
    }
    delete item->widget();
    delete item;
  }
  current_stage_.clear();
  current_bar_ = nullptr;
  set_busy(true);
  statusBar()->showMessage(tr("Baking %1...").arg(scene_path_));
  // A re-bake of the same scene runs only the stages the changed settings
  // affect (core plan_rebake); the rest comes from the last bake.
  // The mesh list's densities apply to a re-bake of the scene it shows.
  std::shared_ptr<const BakeJobResult> previous;
  std::vector<float> densities;
  if (last_job_ && last_job_->result && last_job_->scene_path == scene_path_.toStdString()) {
    previous = last_job_;
    if (static_cast<std::size_t>(meshes_->mesh_count()) == previous->scene->meshes.size())
      densities = meshes_->densities();
  }
  // Every bake goes to the cache, a folder per content key, which the views
  // read back; a bake of the same contents and settings there is shown.
  const QString cache = QString::fromStdString(user_cache_dir("bakes").string());
  QDir().mkpath(cache);
  controller_->start(scene_path_, settings, cache, previous, densities, true);
}

void MainWindow::on_stage_progress(const QString& stage, double fraction, double eta) {
  if (stage != current_stage_ || !current_bar_) {
    // A bar per stage: finished stages stay full, the current one moves.
    current_stage_ = stage;
    auto* row = new QHBoxLayout;
    current_bar_ = new QProgressBar(this);
    current_bar_->setRange(0, 1000);
    current_bar_->setFormat(stage + " %p%");
    current_eta_ = new QLabel(this);
    row->addWidget(current_bar_, 1);
    row->addWidget(current_eta_);
    stage_bars_->addLayout(row);
  }
  current_bar_->setValue(static_cast<int>(fraction * 1000.0 + 0.5));
  current_eta_->setText(fraction >= 1.0 ? tr("done") : eta_text(eta));
}

void MainWindow::set_busy(bool busy) {
  bake_button_->setEnabled(!busy && !scene_path_.isEmpty());
  cancel_button_->setEnabled(busy);
  settings_->setEnabled(!busy);
  meshes_->setEnabled(!busy);
}

void MainWindow::export_bake_folder() {
  if (!last_job_) return;
  const QString dir = QFileDialog::getSaveFileName(this, tr("Export bake folder"),
                                                   QFileInfo(scene_path_).completeBaseName());
  if (dir.isEmpty()) return;
  try {
    export_bake(*last_job_, dir.toStdString());
    statusBar()->showMessage(tr("Exported to %1").arg(dir));
  } catch (const std::exception& e) {
    show_error(tr("Export failed"), QString::fromStdString(e.what()));
  }
}

void MainWindow::export_lit_glb() {
  const QString path = QFileDialog::getSaveFileName(
      this, tr("Export lit mesh (binary glTF)"), QFileInfo(scene_path_).completeBaseName() + ".glb",
      tr("Binary glTF (*.glb)"));
  if (path.isEmpty()) return;
  try {
    // The preview's light where it is now, as `bounce solve` writes lit.glb.
    preview_view_->preview()->export_lit_glb(path.toStdString());
    statusBar()->showMessage(tr("Exported the lit mesh to %1").arg(path));
  } catch (const std::exception& e) {
    show_error(tr("Export failed"), QString::fromStdString(e.what()));
  }
}

void MainWindow::show_error(const QString& what, const QString& message) {
  statusBar()->showMessage(what);
  QMessageBox::critical(this, what, message);
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  if (event->mimeData()->hasUrls()) event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
  const QList<QUrl> urls = event->mimeData()->urls();
  if (!urls.isEmpty() && urls.front().isLocalFile()) open(urls.front().toLocalFile());
}

void MainWindow::closeEvent(QCloseEvent* event) {
  QSettings store;
  settings_->save(store);
  store.setValue("window/geometry", saveGeometry());
  store.setValue("window/state", saveState());
  if (controller_->busy()) controller_->cancel();
  event->accept();
}

}  // namespace bounce::studio
