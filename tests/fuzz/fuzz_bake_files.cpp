// libFuzzer targets for the readers of a bake folder, which travels between
// machines and people and so is untrusted input. One source, four targets
// (tests/fuzz/CMakeLists.txt picks one with BOUNCE_FUZZ_BAKE_TARGET):
//   npy       the input is a .npy file, read as float32, uint32 and int32;
//   dds       the input is a DDS file;
//   manifest  the input is manifest.json of a small valid bake (tests/fuzz/
//             bake), read with BakeReader like `bounce solve` reads it;
//   folder    the input's first byte picks one file of that bake and the rest
//             replaces it; BakeReader reads the whole folder, then the stored
//             final gather and light probes are read as `bounce solve` and
//             the lighting session read them.
// Every input must either be read or throw bounce::Error; anything else
// (crash, sanitizer report, another exception type such as std::bad_alloc, a
// leak, an allocation beyond libFuzzer's -malloc_limit_mb) is a defect.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"
#include "compress/dds.h"
#include "folder/bake_format.h"
#include "folder/bake_reader.h"
#include "folder/final_gather_files.h"
#include "folder/light_probe_files.h"
#include "fuzz_workdir.h"
#include "io/npy.h"

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kTarget = BOUNCE_FUZZ_BAKE_TARGET;
static_assert(kTarget == "npy" || kTarget == "dds" || kTarget == "manifest" || kTarget == "folder");

// The files BakeReader reads, then the stored final gather's, in the order
// the folder target's first byte picks them (byte % count; the list in
// make_bake_corpus.sh follows it). voxels.npy and the pictures are not read.
const char* const kBakeFiles[] = {"manifest.json",
                                  "patches.npy",
                                  "samples.npy",
                                  "lights_first_hit.npy",
                                  "carried_polygons.npy",
                                  "carried_area.npy",
                                  "carried_vertices.npy",
                                  "T.dds",
                                  "permutation.npy",
                                  "T_kept_0_row_ptr.npy",
                                  "T_kept_0_col.npy",
                                  "T_kept_0_value.npy",
                                  "T_kept_1_row_ptr.npy",
                                  "T_kept_1_col.npy",
                                  "T_kept_1_value.npy",
                                  "T_kept_2_row_ptr.npy",
                                  "T_kept_2_col.npy",
                                  "T_kept_2_value.npy",
                                  "T.npy",
                                  bounce::bake_file::kGatherFirst,
                                  bounce::bake_file::kGatherSource,
                                  bounce::bake_file::kGatherWeight,
                                  bounce::bake_file::kGatherCluster,
                                  bounce::bake_file::kGatherShare,
                                  bounce::bake_file::kGatherSeenFirst,
                                  bounce::bake_file::kGatherSeenSample,
                                  bounce::bake_file::kGatherSeenWeight,
                                  bounce::bake_file::kGatherSpotFirst,
                                  bounce::bake_file::kGatherSpotWeight,
                                  bounce::bake_file::kGatherNearPosition,
                                  bounce::bake_file::kGatherNearNormal,
                                  bounce::bake_file::kGatherNearAlbedo,
                                  bounce::bake_file::kGatherNearPatch,
                                  bounce::bake_file::kProbePositions,
                                  "probe_gather_first.npy",
                                  "probe_gather_source.npy",
                                  "probe_gather_weight.npy",
                                  "probe_gather_cluster.npy",
                                  "probe_gather_share.npy",
                                  "probe_gather_seen_first.npy",
                                  "probe_gather_seen_sample.npy",
                                  "probe_gather_seen_weight.npy",
                                  bounce::bake_file::kProbeVolumes};
constexpr std::size_t kBakeFileCount = std::size(kBakeFiles);

[[maybe_unused]] std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The template bake, copied into the work folder once; each input replaces
// one file and puts the original back afterwards.
struct Bake {
  fs::path dir;
  std::vector<std::string> original;  // per kBakeFiles entry
};

Bake& bake() {
  static Bake b;
  return b;
}

[[maybe_unused]] void restore(std::size_t file) {
  const std::string& text = bake().original[file];
  bounce::fuzz::work_dir().write(std::string("bake/") + kBakeFiles[file],
                                 reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

[[maybe_unused]] void read_bake() {
  try {
    const bounce::LoadedBake b =
        bounce::BakeReader::read(bake().dir, bounce::BakeReader::Dense::kRead);
    (void)bounce::read_final_gather(bake().dir, b.size(), b.samples.samples.size());
    (void)bounce::read_light_probes(bake().dir, b.size(), b.samples.samples.size());
  } catch (const bounce::Error&) {
    // The expected way to refuse a damaged bake: one message naming the file.
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  if constexpr (kTarget == "manifest" || kTarget == "folder") {
    Bake& b = bake();
    b.dir = bounce::fuzz::work_dir().path() / "bake";
    fs::create_directories(b.dir);
    for (const char* name : kBakeFiles) {
      b.original.push_back(read_all(fs::path(BOUNCE_FUZZ_BAKE_DIR) / name));
      if (b.original.back().empty()) std::abort();  // the template bake is incomplete
    }
    for (std::size_t k = 0; k < kBakeFileCount; ++k) restore(k);
    // The template itself must read, its gather included: otherwise every
    // input fails early and the campaign tests nothing.
    const bounce::LoadedBake loaded =
        bounce::BakeReader::read(b.dir, bounce::BakeReader::Dense::kRead);
    if (!bounce::read_final_gather(b.dir, loaded.size(), loaded.samples.samples.size()))
      std::abort();
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if constexpr (kTarget == "npy") {
    const auto file = bounce::fuzz::work_dir().write("input.npy", data, size);
    try {
      (void)bounce::read_npy_f32(file);
    } catch (const bounce::Error&) {
    }
    try {
      (void)bounce::read_npy_u32(file);
    } catch (const bounce::Error&) {
    }
    try {
      (void)bounce::read_npy_i32(file);
    } catch (const bounce::Error&) {
    }
    try {
      (void)bounce::read_npy_u16(file);
    } catch (const bounce::Error&) {
    }
    try {
      (void)bounce::read_npy_half_bits(file);
    } catch (const bounce::Error&) {
    }
  } else if constexpr (kTarget == "dds") {
    const auto file = bounce::fuzz::work_dir().write("input.dds", data, size);
    try {
      (void)bounce::read_dds(file);
    } catch (const bounce::Error&) {
    }
  } else if constexpr (kTarget == "manifest") {
    bounce::fuzz::work_dir().write("bake/manifest.json", data, size);
    read_bake();
    restore(0);
  } else if (size > 0) {  // folder
    const std::size_t file = data[0] % kBakeFileCount;
    bounce::fuzz::work_dir().write(std::string("bake/") + kBakeFiles[file], data + 1, size - 1);
    read_bake();
    restore(file);
  }
  return 0;
}
