#include "error_source_link.h"

#include "matrix_view.h"
#include "patch_view.h"

namespace bounce::views {

void link_error_sources(PatchView* patches, MatrixView* matrix,
                        std::function<void()> show_matrix_view,
                        std::function<void()> show_patch_view) {
  QObject::connect(patches, &PatchView::error_source_selected, matrix,
                   [matrix](int patch, int stored_row, int col_first, int col_last) {
                     matrix->mark_row(patch, static_cast<std::size_t>(stored_row),
                                      static_cast<std::size_t>(col_first),
                                      static_cast<std::size_t>(col_last));
                   });
  QObject::connect(patches, &PatchView::matrix_requested, matrix,
                   [show = std::move(show_matrix_view)] { show(); });
  QObject::connect(matrix, &MatrixView::patch_requested, patches,
                   [patches, show = std::move(show_patch_view)](int patch) {
                     patches->select_patch(patch);
                     show();
                   });
}

}  // namespace bounce::views
