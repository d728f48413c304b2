#include "patch_view.h"

#include <algorithm>
#include <cmath>

#include <QVTKOpenGLNativeWidget.h>
#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellPicker.h>
#include <vtkFloatArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGlyph3D.h>
#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRegularPolygonSource.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <QComboBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QMouseEvent>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>

#include "bounce/compression.h"
#include "bounce/metrics.h"
#include "bounce/pictures.h"
#include "bounce/relight.h"
#include "view_jobs.h"
#include "vtk_scene.h"

namespace bounce::views {

namespace {

std::array<unsigned char, 3> srgb(const glm::vec3& linear) {
  return {ToneMap::srgb8(linear.r), ToneMap::srgb8(linear.g), ToneMap::srgb8(linear.b)};
}

// A colour per id that neighbours tell apart: hues by the golden ratio.
std::array<unsigned char, 3> id_colour(std::size_t id) {
  const double h = std::fmod(static_cast<double>(id) * 0.618033988749895, 1.0) * 6.0;
  const int k = static_cast<int>(h);
  const double f = h - k;
  const double v = 0.95, s = 0.75, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  const double rgb[6][3] = {{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}};
  return {static_cast<unsigned char>(rgb[k][0] * 255), static_cast<unsigned char>(rgb[k][1] * 255),
          static_cast<unsigned char>(rgb[k][2] * 255)};
}

QString rgb_text(const glm::dvec3& v) {
  return QString("(%1, %2, %3)").arg(v.r, 0, 'g', 4).arg(v.g, 0, 'g', 4).arg(v.b, 0, 'g', 4);
}

}  // namespace

PatchView::PatchView(ViewJobs& jobs, QWidget* parent)
    : QWidget(parent),
      jobs_(jobs),
      vtk_widget_(new QVTKOpenGLNativeWidget(this)),
      colour_box_(new QComboBox(this)),
      light_box_(new QComboBox(this)),
      status_(new QLabel(this)),
      explain_(new QWidget(this)),
      explain_text_(new QLabel(explain_)),
      sources_(new QTableWidget(explain_)),
      matrix_button_(new QPushButton(tr("Show in the matrix view"), explain_)),
      renderer_(vtkSmartPointer<vtkRenderer>::New()),
      centres_(vtkSmartPointer<vtkPolyData>::New()),
      glyphs_(vtkSmartPointer<vtkGlyph3D>::New()),
      disc_actor_(vtkSmartPointer<vtkActor>::New()),
      sample_poly_(vtkSmartPointer<vtkPolyData>::New()),
      sample_actor_(vtkSmartPointer<vtkActor>::New()),
      picker_(vtkSmartPointer<vtkCellPicker>::New()) {
  colour_box_->addItems({tr("Albedo"), tr("Patch id"), tr("Radiosity (first light)"),
                         tr("Form-factor row"), tr("Closure"), tr("Balancing scale"),
                         tr("Indirect-light error")});
  colour_box_->setToolTip(
      tr("Albedo: the patch colour. Patch id: one colour per patch. Radiosity: light leaving "
         "each patch under the scene's first light, direct plus indirect through T. "
         "Form-factor row: how much of the picked patch's light reaches each patch (log "
         "scale); click a patch first. Closure: the share of each patch's light that lands on "
         "sampled surface (1 in a closed room; dark where light escapes). Balancing scale: how "
         "much the patch's form-factor row was scaled to reach its closure (white: 1, blue: "
         "scaled down, red: scaled up; strong colours show where the quadrature struggled). "
         "Indirect-light error: how far the compressed matrix's indirect light is from the "
         "exact one under the light chosen beside it, relative per patch, 0 .. 10%; click a "
         "patch for its exact and compressed light and the entries that make the difference "
         "(needs a compressed bake made with --dump-matrices)"));
  light_box_->setToolTip(tr("The light of the indirect-light error"));
  // The controls never force a minimum width on the view: at small sizes
  // (screenshots) they are cut off instead.
  auto* bar = new QWidget(this);
  bar->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
  auto* controls = new QHBoxLayout(bar);
  controls->setContentsMargins(0, 0, 0, 0);
  controls->addWidget(new QLabel(tr("Colour by"), this));
  controls->addWidget(colour_box_);
  controls->addWidget(light_box_);
  controls->addStretch(1);
  controls->addWidget(status_);
  // The picked patch's error, explained: beside the 3-D view, only in the
  // error mode with a picked patch.
  auto* explain_layout = new QVBoxLayout(explain_);
  explain_layout->setContentsMargins(0, 0, 0, 0);
  explain_text_->setWordWrap(true);
  explain_text_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  explain_layout->addWidget(explain_text_);
  sources_->setColumnCount(5);
  sources_->setHorizontalHeaderLabels(
      {tr("Share"), tr("Source"), tr("Stored columns"), tr("Patches"), tr("(T~ - T) b, R G B")});
  sources_->setToolTip(
      tr("The pieces of the picked patch's compressed row: a 4x4 block of the reordered matrix "
         "(the entries it decodes) or a kept entry (stored exactly). Share: dot(contribution, "
         "error) / |error|^2 over R, G, B; the shares of all pieces add up to 100%, a negative "
         "one cancels part of the others. Pick one to mark it in the matrix view."));
  sources_->setSelectionBehavior(QAbstractItemView::SelectRows);
  sources_->setSelectionMode(QAbstractItemView::SingleSelection);
  sources_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  sources_->verticalHeader()->setVisible(false);
  sources_->horizontalHeader()->setStretchLastSection(true);
  explain_layout->addWidget(sources_, 1);
  explain_layout->addWidget(matrix_button_);
  explain_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
  explain_->hide();
  auto* body = new QHBoxLayout;
  body->addWidget(vtk_widget_, 3);
  body->addWidget(explain_, 2);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(bar);
  layout->addLayout(body, 1);
  connect(sources_, &QTableWidget::currentCellChanged, this,
          [this](int row, int, int, int) { emit_source(row); });
  connect(matrix_button_, &QPushButton::clicked, this, [this] {
    emit_source(sources_->currentRow());
    emit matrix_requested();
  });

  auto window = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  vtk_widget_->setRenderWindow(window);
  window->AddRenderer(renderer_);
  renderer_->SetBackground(0.12, 0.12, 0.14);

  // A unit disc in the y-z plane: vtkGlyph3D turns the glyph's x axis onto
  // the patch normal and scales it by the patch radius.
  auto disc = vtkSmartPointer<vtkRegularPolygonSource>::New();
  disc->SetNumberOfSides(20);
  disc->SetRadius(1.0);
  disc->SetNormal(1.0, 0.0, 0.0);
  glyphs_->SetSourceConnection(disc->GetOutputPort());
  glyphs_->SetInputData(centres_);
  glyphs_->SetVectorModeToUseNormal();
  glyphs_->SetScaleModeToScaleByScalar();
  glyphs_->SetScaleFactor(1.0);
  glyphs_->GeneratePointIdsOn();  // "InputPointIds": the patch of each glyph point
  glyphs_->SetColorModeToColorByScalar();
  auto disc_mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  disc_mapper->SetInputConnection(glyphs_->GetOutputPort());
  disc_mapper->SetScalarModeToUsePointFieldData();
  disc_mapper->SelectColorArray("colour");
  disc_mapper->SetColorModeToDirectScalars();
  disc_mapper->ScalarVisibilityOn();
  disc_actor_->SetMapper(disc_mapper);
  disc_actor_->GetProperty()->BackfaceCullingOff();
  disc_actor_->GetProperty()->SetAmbient(0.35);
  disc_actor_->GetProperty()->SetDiffuse(0.65);
  renderer_->AddActor(disc_actor_);

  auto sample_mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  sample_mapper->SetInputData(sample_poly_);
  sample_actor_->SetMapper(sample_mapper);
  sample_actor_->GetProperty()->SetColor(kSampleColour[0] / 255.0, kSampleColour[1] / 255.0,
                                         kSampleColour[2] / 255.0);
  sample_actor_->GetProperty()->SetPointSize(6.0f);
  sample_actor_->GetProperty()->LightingOff();
  renderer_->AddActor(sample_actor_);

  picker_->SetTolerance(0.0005);
  picker_->PickFromListOn();
  picker_->AddPickList(disc_actor_);

  connect(colour_box_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int) { recolour(); });
  connect(light_box_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int) { recolour(); });

  // A click without a drag picks; VTK's trackball keeps rotating on drag.
  auto click = vtkSmartPointer<vtkCallbackCommand>::New();
  click->SetClientData(this);
  click->SetCallback([](vtkObject* caller, unsigned long, void* self, void*) {
    auto* view = static_cast<PatchView*>(self);
    auto* interactor = static_cast<vtkRenderWindowInteractor*>(caller);
    if (interactor->GetRepeatCount() != 0) return;
    const int* pos = interactor->GetEventPosition();
    // VTK's origin is bottom-left, in device pixels.
    const double ratio = view->vtk_widget_->devicePixelRatioF();
    const int x = static_cast<int>(pos[0] / ratio);
    const int y = view->vtk_widget_->height() - 1 - static_cast<int>(pos[1] / ratio);
    const int p = view->patch_at(x, y);
    if (p >= 0) view->select_patch(p);
  });
  window->GetInteractor()->AddObserver(vtkCommand::LeftButtonPressEvent, click, 1.0f);
}

PatchView::~PatchView() = default;

void PatchView::set_data(std::shared_ptr<const BakeViewData> bake) {
  data_ = std::move(bake);
  selected_ = -1;
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto normals = vtkSmartPointer<vtkFloatArray>::New();
  normals->SetNumberOfComponents(3);
  normals->SetName("normal");
  auto radius = vtkSmartPointer<vtkFloatArray>::New();
  radius->SetName("radius");
  const std::size_t n = data_ ? data_->patch_count() : 0;
  for (std::size_t p = 0; p < n; ++p) {
    const Patch& patch = data_->bake.patches.patches[p];
    points->InsertNextPoint(patch.position.x, patch.position.y, patch.position.z);
    normals->InsertNextTuple3(patch.normal.x, patch.normal.y, patch.normal.z);
    // A disc of the patch's own area.
    radius->InsertNextValue(std::sqrt(patch.area / 3.14159265f));
  }
  centres_->Initialize();
  centres_->SetPoints(points);
  centres_->GetPointData()->SetNormals(normals);
  centres_->GetPointData()->SetScalars(radius);
  decoded_.reset();
  light_box_->blockSignals(true);
  light_box_->clear();
  if (data_) {
    light_box_->addItem(tr("scene's lights"));
    for (std::size_t l = 0; l < data_->bake.probe.first_hit.size(); ++l)
      light_box_->addItem(tr("evaluation light %1").arg(l));
  }
  light_box_->blockSignals(false);
  colour_box_->setItemData(static_cast<int>(ColourBy::IndirectError),
                           can_show_indirect_error() ? QVariant() : QVariant(0), Qt::UserRole - 1);
  const bool has_f = data_ && !data_->form_factors.empty();
  colour_box_->setItemData(3, has_f ? QVariant() : QVariant(0), Qt::UserRole - 1);
  recolour();
  if (data_ && data_->scene)
    apply_scene_camera(*data_->scene, *renderer_);
  else
    renderer_->ResetCamera();
  render();
}

void PatchView::set_colour_by(ColourBy by) { colour_box_->setCurrentIndex(static_cast<int>(by)); }

void PatchView::set_error_light(int index) { light_box_->setCurrentIndex(index); }

bool PatchView::can_show_indirect_error() const {
  return data_ && data_->bake.compressed && !data_->bake.dense.empty() &&
         !data_->bake.probe.first_hit.empty();
}

QString PatchView::status_text() const { return status_->text(); }

void PatchView::select_patch(int p) {
  selected_ = data_ && p >= 0 && static_cast<std::size_t>(p) < data_->patch_count() ? p : -1;
  if (selected_ >= 0 && !data_->form_factors.empty() &&
      colour_box_->currentIndex() != static_cast<int>(ColourBy::IndirectError))
    colour_box_->setCurrentIndex(static_cast<int>(ColourBy::FormFactorRow));
  show_samples();
  recolour();
  emit patch_selected(selected_);
}

void PatchView::recolour() {
  const std::size_t n = data_ ? data_->patch_count() : 0;
  auto by = static_cast<ColourBy>(colour_box_->currentIndex());
  if (by == ColourBy::FormFactorRow && (selected_ < 0 || !data_ || data_->form_factors.empty()))
    by = ColourBy::Albedo;
  if ((by == ColourBy::Closure || by == ColourBy::RowScale) && (!data_ || data_->closure.empty()))
    by = ColourBy::Albedo;
  if (by == ColourBy::IndirectError && !can_show_indirect_error()) by = ColourBy::Albedo;
  light_box_->setEnabled(by == ColourBy::IndirectError);
  explanation_.reset();
  // A colouring still being computed gives way to this one.
  jobs_.forget(this);
  if (by == ColourBy::Radiosity) {
    colour_by_radiosity();
    return;
  }
  if (by == ColourBy::IndirectError) {
    colour_by_indirect_error();
    return;
  }
  colours_.assign(n, {0, 0, 0});
  QString what;
  if (by == ColourBy::Albedo) {
    for (std::size_t p = 0; p < n; ++p) colours_[p] = srgb(data_->bake.patches.patches[p].albedo);
  } else if (by == ColourBy::PatchId) {
    for (std::size_t p = 0; p < n; ++p) colours_[p] = id_colour(p);
  } else if (by == ColourBy::Closure) {
    float lo = 1.0f;
    for (std::size_t p = 0; p < n; ++p) {
      std::uint8_t c[3];
      colormap(static_cast<double>(data_->closure[p]), c);
      colours_[p] = {c[0], c[1], c[2]};
      lo = std::min(lo, data_->closure[p]);
    }
    what = tr("closure (0 .. 1; lowest %1)").arg(static_cast<double>(lo), 0, 'f', 3);
  } else if (by == ColourBy::RowScale) {
    // Diverging about 1 on a log scale: +-25% is full colour.
    float lo = 1.0f, hi = 1.0f;
    for (std::size_t p = 0; p < n; ++p) {
      const float s = data_->row_scale[p];
      lo = std::min(lo, s);
      hi = std::max(hi, s);
      const double t = std::clamp(std::log(std::max(s, 1e-6f)) / std::log(1.25), -1.0, 1.0);
      const auto fade = static_cast<unsigned char>(255.0 * (1.0 - std::abs(t)));
      colours_[p] = t >= 0 ? std::array<unsigned char, 3>{255, fade, fade}
                           : std::array<unsigned char, 3>{fade, fade, 255};
    }
    what = tr("form-factor row scale %1 .. %2 (white 1, full colour 25%)")
               .arg(static_cast<double>(lo), 0, 'f', 3)
               .arg(static_cast<double>(hi), 0, 'f', 3);
  } else {
    // F[selected][q]: the share of the picked patch's light that reaches q.
    const float* row = &data_->form_factors[static_cast<std::size_t>(selected_) * n];
    const float vmax = *std::max_element(row, row + n);
    constexpr double kDecades = 4.0;
    for (std::size_t q = 0; q < n; ++q) {
      std::uint8_t c[3] = {0, 0, 0};
      if (row[q] > 0.0f && vmax > 0.0f)
        colormap(1.0 + std::log10(static_cast<double>(row[q] / vmax)) / kDecades, c);
      colours_[q] = {c[0], c[1], c[2]};
    }
    what = tr("F row of patch %1 (max %2, log scale, 4 decades; black: unseen)")
               .arg(selected_)
               .arg(static_cast<double>(vmax), 0, 'g', 3);
  }
  show_colours(what);
}

void PatchView::show_pending(const QString& what) {
  // The last colours stay on screen until the new ones arrive.
  const std::size_t n = data_ ? data_->patch_count() : 0;
  if (colours_.size() != n) {
    colours_.assign(n, {0, 0, 0});
    for (std::size_t p = 0; p < n; ++p) colours_[p] = srgb(data_->bake.patches.patches[p].albedo);
  }
  show_colours(what);
}

void PatchView::show_colours(const QString& what) {
  const std::size_t n = data_ ? data_->patch_count() : 0;
  auto array = vtkSmartPointer<vtkUnsignedCharArray>::New();
  array->SetName("colour");
  array->SetNumberOfComponents(3);
  for (const auto& c : colours_) array->InsertNextTuple3(c[0], c[1], c[2]);
  centres_->GetPointData()->RemoveArray("colour");
  centres_->GetPointData()->AddArray(array);
  centres_->Modified();
  QString text = data_ ? tr("%1 patches").arg(n) : tr("no bake");
  if (selected_ >= 0)
    text += tr(", patch %1 picked (%2 samples)")
                .arg(selected_)
                .arg(data_->bake.patches.member_count(static_cast<std::size_t>(selected_)));
  if (!what.isEmpty()) text += " - " + what;
  status_->setText(text);
  show_explanation();
  render();
}

void PatchView::colour_by_radiosity() {
  show_pending(tr("computing the radiosity..."));
  auto bake = data_;
  jobs_.run<PatchRadiosity>(
      this, kColourJob, [bake](const ViewJobs::KeepGoing&) { return patch_radiosity(bake->bake); },
      [this](PatchRadiosity r) {
        const LoadedBake& b = data_->bake;
        const std::size_t n = r.radiosity.size();
        std::vector<float> lum(n);
        for (std::size_t p = 0; p < n; ++p) lum[p] = luminance(r.radiosity[p]);
        const float exposure = ToneMap::exposure_for(lum);
        colours_.resize(n);
        for (std::size_t p = 0; p < n; ++p) colours_[p] = srgb(r.radiosity[p] * exposure);
        const QString what =
            r.lit ? tr("radiosity under %1")
                        .arg(QString::fromStdString(b.description.scene_lights.empty()
                                                        ? std::string("the first evaluation light")
                                                        : b.description.scene_lights.front().name))
                  : tr("no exact T in this bake: emission only");
        show_colours(what);
      },
      [this](const QString& message) { show_pending(tr("radiosity failed: %1").arg(message)); });
}

void PatchView::colour_by_indirect_error() {
  show_pending(tr("computing the indirect-light error..."));
  struct Result {
    std::shared_ptr<const std::vector<std::vector<float>>> decoded;
    PatchIndirectError error;
  };
  auto bake = data_;
  auto decoded = decoded_;
  const std::size_t set = static_cast<std::size_t>(std::max(0, light_box_->currentIndex()));
  const std::optional<std::size_t> patch =
      selected_ >= 0 ? std::optional(static_cast<std::size_t>(selected_)) : std::nullopt;
  jobs_.run<Result>(
      this, kColourJob,
      [bake, decoded, set, patch](const ViewJobs::KeepGoing&) {
        Result r{decoded, {}};
        // The decoded matrix is made once per bake and kept by the view.
        if (!r.decoded)
          r.decoded = std::make_shared<const std::vector<std::vector<float>>>(
              decode_compressed(bake->bake));
        r.error = compressed_indirect_error(bake->bake, *r.decoded, set, patch);
        return r;
      },
      [this, set](Result r) {
        decoded_ = std::move(r.decoded);
        const PatchLightError& e = r.error.error;
        error_rms_ = e.rel_rms;
        colours_.resize(e.relative.size());
        for (std::size_t p = 0; p < e.relative.size(); ++p) {
          std::uint8_t c[3];
          colormap(std::min(1.0, static_cast<double>(e.relative[p]) / kErrorFullScale), c);
          colours_[p] = {c[0], c[1], c[2]};
        }
        const QString name =
            set == 0 ? tr("the scene's lights") : tr("evaluation light %1").arg(set - 1);
        QString what = tr("indirect-light error under %1: %2 relative RMS (area-weighted), per "
                          "patch 0 .. %3%")
                           .arg(name)
                           .arg(e.rel_rms, 0, 'g', 4)
                           .arg(100.0 * kErrorFullScale, 0, 'g', 3);
        explanation_ = std::move(r.error.explanation);
        if (explanation_)
          what +=
              tr("; patch %1: exact %2, compressed %3 (its matrix row explained beside the view)")
                  .arg(explanation_->patch)
                  .arg(rgb_text(explanation_->exact))
                  .arg(rgb_text(explanation_->compressed));
        show_colours(what);
      },
      [this](const QString& message) {
        show_pending(tr("indirect-light error failed: %1").arg(message));
      });
}

QString PatchView::explanation_text() const { return explain_text_->text(); }

void PatchView::select_source(int rank) { sources_->setCurrentCell(rank, 0); }

void PatchView::emit_source(int rank) {
  if (!explanation_ || rank < 0 || static_cast<std::size_t>(rank) >= explanation_->sources.size())
    return;
  const RowErrorSource& s = explanation_->sources[static_cast<std::size_t>(rank)];
  // The stored columns the source's entries lie in: a block's 4 (fewer in
  // the padded last block), or the kept entry's own.
  std::size_t first = s.block_col * 4;
  std::size_t last = std::min(first + 4, data_->patch_count());
  if (s.kind == RowErrorSource::Kind::Kept) {
    first = s.entries.front().stored_col;
    last = first + 1;
  }
  emit error_source_selected(selected_, static_cast<int>(explanation_->stored_row),
                             static_cast<int>(first), static_cast<int>(last));
}

void PatchView::show_explanation() {
  const QSignalBlocker quiet(sources_);
  sources_->clearContents();
  if (!explanation_) {
    sources_->setRowCount(0);
    explain_text_->clear();
    explain_->hide();
    return;
  }
  const RowErrorContributions& r = *explanation_;
  const glm::dvec3 relative =
      glm::abs(r.difference) / glm::max(glm::abs(r.exact), glm::dvec3(1e-30));
  explain_text_->setText(
      tr("Patch %1 (stored row %2 of the reordered matrix, block row %3). Indirect light, R G B:\n"
         "exact %4\ncompressed %5\ndifference %6 (%7%, %8%, %9%)\n"
         "Its row's %10 pieces by share of the difference (largest %11 below):")
          .arg(r.patch)
          .arg(r.stored_row)
          .arg(r.stored_row / 4)
          .arg(rgb_text(r.exact))
          .arg(rgb_text(r.compressed))
          .arg(rgb_text(r.difference))
          .arg(100.0 * relative.r, 0, 'f', 2)
          .arg(100.0 * relative.g, 0, 'f', 2)
          .arg(100.0 * relative.b, 0, 'f', 2)
          .arg(r.sources.size())
          .arg(std::min<std::size_t>(r.sources.size(), kSourcesShown)));
  const int rows = static_cast<int>(std::min<std::size_t>(r.sources.size(), kSourcesShown));
  sources_->setRowCount(rows);
  for (int row = 0; row < rows; ++row) {
    const RowErrorSource& s = r.sources[static_cast<std::size_t>(row)];
    QString columns, patches;
    for (const RowEntry& e : s.entries) {
      columns += (columns.isEmpty() ? "" : " ") + QString::number(e.stored_col);
      patches += (patches.isEmpty() ? "" : " ") + QString::number(e.column);
    }
    const QString source = s.kind == RowErrorSource::Kind::Block
                               ? tr("block %1, %2").arg(s.block_row).arg(s.block_col)
                               : tr("kept T[%1][%2]").arg(r.patch).arg(s.entries.front().column);
    const QStringList cells = {QString("%1%").arg(100.0 * s.share, 0, 'f', 1), source, columns,
                               patches, rgb_text(s.contribution)};
    for (int col = 0; col < cells.size(); ++col)
      sources_->setItem(row, col, new QTableWidgetItem(cells[col]));
  }
  sources_->resizeColumnsToContents();
  explain_->show();
}

void PatchView::show_samples() {
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto verts = vtkSmartPointer<vtkCellArray>::New();
  if (selected_ >= 0) {
    const PatchSet& ps = data_->bake.patches;
    const auto p = static_cast<std::size_t>(selected_);
    for (std::uint32_t k = ps.member_first[p]; k < ps.member_first[p + 1]; ++k) {
      const Sample& s = data_->bake.samples.samples[ps.member_samples[k]];
      // Lifted off the surface along its normal so the disc does not hide it.
      const glm::vec3 q = s.position + s.normal * (0.02f * data_->cell_size);
      const vtkIdType id = points->InsertNextPoint(q.x, q.y, q.z);
      verts->InsertNextCell(1, &id);
    }
  }
  sample_poly_->Initialize();
  sample_poly_->SetPoints(points);
  sample_poly_->SetVerts(verts);
}

int PatchView::patch_at(int x, int y) {
  const double ratio = vtk_widget_->devicePixelRatioF();
  const int height = vtk_widget_->renderWindow()->GetSize()[1];
  if (!picker_->Pick(x * ratio, height - 1 - y * ratio, 0.0, renderer_)) return -1;
  const vtkIdType cell = picker_->GetCellId();
  vtkPolyData* out = glyphs_->GetOutput();
  auto* ids = vtkIdTypeArray::SafeDownCast(out->GetPointData()->GetArray("InputPointIds"));
  if (cell < 0 || !ids || cell >= out->GetNumberOfCells()) return -1;
  return static_cast<int>(ids->GetValue(out->GetCell(cell)->GetPointId(0)));
}

QPoint PatchView::project_patch(int p) {
  const glm::vec3 c = data_->bake.patches.patches[static_cast<std::size_t>(p)].position;
  renderer_->SetWorldPoint(c.x, c.y, c.z, 1.0);
  renderer_->WorldToDisplay();
  double d[3];
  renderer_->GetDisplayPoint(d);
  const double ratio = vtk_widget_->devicePixelRatioF();
  const int height = vtk_widget_->renderWindow()->GetSize()[1];
  return {static_cast<int>(d[0] / ratio), static_cast<int>((height - 1 - d[1]) / ratio)};
}

void PatchView::render() { vtk_widget_->renderWindow()->Render(); }

QImage PatchView::render_image() {
  render();
  return vtk_widget_->grabFramebuffer();
}

}  // namespace bounce::views
