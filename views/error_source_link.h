#pragma once
// The patch view's explained error and the matrix view, linked both ways: a
// source picked in the patch view's panel (a block or kept entry of the
// picked patch's row) is marked in the matrix view, and the matrix view's
// marked row can be picked back in the patch view. Each side's "show" button
// calls the given function, which brings the other view to the front.
#include <functional>

namespace bounce::views {

class MatrixView;
class PatchView;

void link_error_sources(PatchView* patches, MatrixView* matrix,
                        std::function<void()> show_matrix_view,
                        std::function<void()> show_patch_view);

}  // namespace bounce::views
