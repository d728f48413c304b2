#pragma once
// The matrix pictures of a bake folder (PNG, log colour map, see
// compress/matrix_picture.h), the same the studio shows:
//   T.png                 the multi-bounce matrix in patch order (mean of the
//                         stored channels);
//   T_reordered.png       the same after the codec's row/column permutation;
//   T_error.png           |T~ - T| per entry (sum over channels), reordered;
//   T_error_blocks.png    that error summed per 4x4 block of the DDS.
// The last three only for a compressed matrix.
#include <filesystem>
#include <string>
#include <vector>

#include "bake/bake.h"

namespace bounce {

struct WrittenPicture {
  std::string name;
  std::string content;
};

std::vector<WrittenPicture> write_matrix_pictures(const std::filesystem::path& dir,
                                                  const BakeResult& result);

}  // namespace bounce
