#include "bake/bake_pictures.h"

#include "compress/matrix_picture.h"
#include "folder/bake_format.h"
#include "io/png_writer.h"

namespace bounce {

std::vector<WrittenPicture> write_matrix_pictures(const std::filesystem::path& dir,
                                                  const BakeResult& r) {
  std::vector<WrittenPicture> written;
  const std::size_t n = r.transport.n;
  if (n == 0) return written;
  std::vector<float> mean(n * n, 0.0f);
  const float scale = 1.0f / static_cast<float>(r.transport.channels.size());
  for (const ChannelTransport& c : r.transport.channels)
    for (std::size_t k = 0; k < n * n; ++k) mean[k] += c.t[k] * scale;
  MatrixPictureSettings settings;
  const std::string what =
      r.transport.channels.size() == 1 ? "T" : "T (mean of the stored channels)";
  const std::string size = std::to_string(n) + " x " + std::to_string(n);
  settings.title = what + ", patch order, " + size;
  write_png(dir / bake_file::kPictureTransport, matrix_picture(mean.data(), n, settings));
  written.push_back(
      {bake_file::kPictureTransport, "picture: multi-bounce matrix, patch order, log colour map"});
  if (!r.storage.compressed) return written;

  const Permutation& perm = r.storage.compressed->permutation;
  const std::string order = ", reordered (" + r.storage.compressed->ordering + ")";
  settings.title = what + order;
  write_png(dir / bake_file::kPictureReordered, matrix_picture(mean.data(), n, settings, &perm));
  written.push_back(
      {bake_file::kPictureReordered, "picture: multi-bounce matrix after the codec's reordering"});
  settings.title = "|T~ - T| per entry" + order;
  write_png(dir / bake_file::kPictureError,
            matrix_picture(r.storage.abs_error_sum.data(), n, settings, &perm));
  written.push_back(
      {bake_file::kPictureError, "picture: |compressed - exact| per entry, reordered"});

  // Blocks live in the reordered (stored) matrix.
  std::vector<float> stored(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      stored[i * n + j] = r.storage.abs_error_sum[perm[i] * n + perm[j]];
  std::size_t blocks = 0;
  const std::vector<float> sums = block_error_sums(stored.data(), n, blocks);
  settings.title = "|T~ - T| per 4x4 block of T.dds (" + r.storage.codec + ", " +
                   r.storage.compressed->encoder + ")";
  write_png(dir / bake_file::kPictureErrorBlocks, matrix_picture(sums.data(), blocks, settings));
  written.push_back({bake_file::kPictureErrorBlocks,
                     "picture: |compressed - exact| summed per 4x4 block of T.dds"});
  return written;
}

}  // namespace bounce
