// Hostile bake folders: bake folders travel between machines and people, so
// `bounce solve` must treat every file in one as untrusted. Each case damages
// one file of a real bake the way an attacker would (sizes that wrap around
// 64 bits, headers that ask for far more than the file holds, a manifest that
// lies about counts) and runs `bounce solve` with its address space capped,
// as `ulimit -v` does. Every case must end with exit code 1 and one error
// line naming the file and the field: never a signal, never the OOM killer's
// 137, never an "internal error" (3) from a failed allocation.
#include <cstdint>
#include <functional>
#include <limits>
#include <utility>

#include "../common/raw_npy.h"
#include "cli_harness.h"

namespace bounce::itest {
namespace {

// A solve of the small bake below peaks at about 0.9 GiB of address space
// with --multiply cpp and 1.3 GiB with auto, which maps PoCL's OpenCL
// runtime (VmPeak, measured; little of it resident); the hostile files ask
// for tens of gigabytes up to 2^64 bytes.
constexpr rlim_t kAddressCap = rlim_t(3) << 30;

struct HostileFile {
  const char* name;
  const char* file;                // the file the error must name
  std::vector<std::string> words;  // and what it must say about it
  std::function<void(const fs::path& bake, std::size_t patches)> apply;
  std::vector<std::string> options;  // solve options beyond the defaults below
};

void edit_manifest(const fs::path& bake, const std::function<void(json&)>& edit) {
  json m = read_manifest(bake);
  edit(m);
  write_text(bake / "manifest.json", m.dump());
}

// How many lights make (lights, n, 3) floats wrap around 64 bits to a
// handful of elements: with 3 n = 2^k o (o odd), lights = o^-1 mod 2^(64-k)
// gives lights * 3n = 2^k modulo 2^64. Returns the light count and 2^k.
std::pair<std::uint64_t, std::uint64_t> wrapping_light_count(std::uint64_t n) {
  std::uint64_t odd = 3 * n, low = 1;
  while (odd % 2 == 0) {
    odd /= 2;
    low *= 2;
  }
  std::uint64_t inverse = odd;  // Newton: each step doubles the correct low bits
  for (int step = 0; step < 6; ++step) inverse *= 2 - odd * inverse;
  const std::uint64_t lights = low == 1 ? inverse : inverse & (~std::uint64_t(0) / low);
  return {lights, low};
}

std::vector<HostileFile> hostile_files() {
  return {
      {"light_count_wraps_around",
       "lights_first_hit.npy",
       {"header field 'shape'", "overflows"},
       [](const fs::path& b, std::size_t n) {
         const auto [lights, floats] = wrapping_light_count(n);
         ASSERT_GT(lights, std::uint64_t(1) << 40);
         ASSERT_EQ(lights * n * 3, floats);  // the wrapped count a file can satisfy
         test::write_raw_npy(b / "lights_first_hit.npy",
                             test::npy_header("<f4", "(" + std::to_string(lights) + ", " +
                                                         std::to_string(n) + ", 3)"),
                             floats * 4);
       },
       {}},
      {"patch_rows_beyond_the_file",
       "patches.npy",
       {"truncated: header field 'shape' (1000000000, 15)", "file has 64"},
       [](const fs::path& b, std::size_t) {
         test::write_raw_npy(b / "patches.npy", test::npy_header("<f4", "(1000000000, 15)"), 64);
         edit_manifest(b, [](json& m) { m["counts"]["patches"] = 1000000000; });
       },
       {}},
      {"manifest_patch_count_lies",
       "patches.npy",
       {"has shape"},
       [](const fs::path& b, std::size_t n) {
         edit_manifest(b, [n](json& m) { m["counts"]["patches"] = n * 100000; });
       },
       {}},
      {"manifest_without_patches",
       "manifest.json",
       {"counts.patches is 0"},
       [](const fs::path& b, std::size_t) {
         edit_manifest(b, [](json& m) { m["counts"]["patches"] = 0; });
       },
       {}},
      {"manifest_padded_size_lies",
       "manifest.json",
       {"compression.padded_size is 2147483648"},
       [](const fs::path& b, std::size_t) {
         edit_manifest(b, [](json& m) { m["compression"]["padded_size"] = 2147483648u; });
       },
       {}},
      {"manifest_of_twenty_megabytes",
       "manifest.json",
       {"bytes; a bake manifest is at most 16777216"},
       [](const fs::path& b, std::size_t) {
         write_text(b / "manifest.json",
                    read_text(b / "manifest.json") + std::string(20 << 20, ' '));
       },
       {}},
      {"dds_size_beyond_the_file",
       "T.dds",
       {"header width x height 65536x65536"},
       [](const fs::path& b, std::size_t) {
         std::string dds = read_text(b / "T.dds");
         for (std::size_t at : {12u, 16u}) dds.replace(at, 4, std::string("\0\0\1\0", 4));
         write_text(b / "T.dds", dds);
       },
       {}},
      {"permutation_count_wraps_around",
       "permutation.npy",
       {"header field 'shape'", "overflows"},
       [](const fs::path& b, std::size_t) {
         test::write_raw_npy(b / "permutation.npy",
                             test::npy_header("<u4", "(4611686018427387904, 4)"), 0);
       },
       {}},
      {"kept_rows_end_beyond_the_columns",
       "T_kept_0_row_ptr.npy",
       {"the last row ends at 4000000000"},
       [](const fs::path& b, std::size_t) {
         NpyArray<std::uint32_t> rows = read_npy_u32(b / "T_kept_0_row_ptr.npy");
         rows.data.back() = 4000000000u;
         write_npy(b / "T_kept_0_row_ptr.npy", rows.data, rows.shape);
       },
       {}},
      {"kept_column_out_of_range",
       "T_kept_0_col.npy",
       {"entry 0 has column"},
       [](const fs::path& b, std::size_t n) {
         // Ours stores columns as uint16 below 65537 patches.
         NpyArray<std::uint16_t> cols = read_npy_u16(b / "T_kept_0_col.npy");
         ASSERT_FALSE(cols.data.empty());
         cols.data[0] = static_cast<std::uint16_t>(n);
         write_npy(b / "T_kept_0_col.npy", cols.data, cols.shape);
       },
       {}},
      {"kept_value_not_a_number",
       "T_kept_0_value.npy",
       {"entry 0 is not finite"},
       [](const fs::path& b, std::size_t) {
         NpyArray<std::uint16_t> bits = read_npy_half_bits(b / "T_kept_0_value.npy");
         ASSERT_FALSE(bits.data.empty());
         bits.data[0] = 0x7e00;  // a half NaN
         write_npy_half(b / "T_kept_0_value.npy", bits.data, bits.shape);
       },
       {}},
      {"kept_values_in_float32_where_the_manifest_says_float16",
       "T_kept_0_value.npy",
       {"wrong dtype, expected <f2"},
       [](const fs::path& b, std::size_t) {
         const NpyArray<std::uint16_t> bits = read_npy_half_bits(b / "T_kept_0_value.npy");
         const std::vector<float> wide(bits.data.size(), 0.5f);
         write_npy(b / "T_kept_0_value.npy", wide, bits.shape);
       },
       {}},
      {"kept_storage_unknown",
       "manifest.json",
       {"compression.kept_storage"},
       [](const fs::path& b, std::size_t) {
         edit_manifest(b, [](json& m) { m["compression"]["kept_storage"] = "float8"; });
       },
       {}},
      {"sample_patch_not_a_number",
       "samples.npy",
       {"row 0, column 11 is not finite"},
       [](const fs::path& b, std::size_t) {
         NpyArray<float> s = read_npy_f32(b / "samples.npy");
         s.data[11] = std::numeric_limits<float>::quiet_NaN();
         write_npy(b / "samples.npy", s.data, s.shape);
       },
       {}},
      {"carried_polygon_beyond_the_vertices",
       "carried_polygons.npy",
       {"polygon 0 has vertices"},
       [](const fs::path& b, std::size_t) {
         NpyArray<std::uint32_t> p = read_npy_u32(b / "carried_polygons.npy");
         p.data[1] = 4294967295u;  // first vertex
         write_npy(b / "carried_polygons.npy", p.data, p.shape);
       },
       {}},
      {"dense_matrix_count_wraps_around",
       "T.npy",
       {"header field 'shape'", "overflows"},
       [](const fs::path& b, std::size_t) {
         test::write_raw_npy(b / "T.npy", test::npy_header("<f4", "(4, 4294967296, 4294967296)"),
                             0);
       },
       {"--multiply", "dense"}},
      {"lights_file_is_a_device",
       "lights_first_hit.npy",
       {"not a regular file"},
       [](const fs::path& b, std::size_t) {
         fs::remove(b / "lights_first_hit.npy");
         fs::create_symlink("/dev/zero", b / "lights_first_hit.npy");
       },
       {}},
  };
}

class HostileBake : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp = new TempDir();
    bake = tmp->path() / "bake";
    const RunResult r = run({"bake", scene("cornell-box"), "--voxel", "4", "--codec", "ours",
                             "--dump-matrices", "--no-pictures", "--quiet", "--out", bake.string()},
                            tmp->path());
    ASSERT_EQ(r.exit_code, 0) << r;
  }
  static void TearDownTestSuite() { delete tmp; }

  static RunResult solve_capped(const fs::path& folder, const std::vector<std::string>& options) {
    std::vector<std::string> args{"solve",
                                  folder.string(),
                                  "--no-images",
                                  "--no-mesh",
                                  "--quiet",
                                  "--out",
                                  (folder / "solve").string()};
    args.insert(args.end(), options.begin(), options.end());
    RunOptions o;
    o.cwd = tmp->path();
    o.max_address_bytes = kAddressCap;
    return run(args, o);
  }

  static inline TempDir* tmp = nullptr;
  static inline fs::path bake;
};

TEST_F(HostileBake, TheIntactBakeSolvesUnderTheSameCap) {
  // The cap alone must not be what refuses the hostile folders below.
  const RunResult r = solve_capped(bake, {"--multiply", "cpp"});
  EXPECT_EQ(r.exit_code, 0) << r;
}

TEST_F(HostileBake, EveryHostileFileIsOneErrorNamingItUnderAMemoryCap) {
  const std::size_t n = read_manifest(bake)["counts"]["patches"].get<std::size_t>();
  for (const HostileFile& h : hostile_files()) {
    SCOPED_TRACE(h.name);
    const fs::path copy = tmp->path() / h.name;
    fs::copy(bake, copy, fs::copy_options::recursive);
    h.apply(copy, n);
    if (::testing::Test::HasFatalFailure()) return;
    const RunResult r = solve_capped(copy, h.options);
    EXPECT_FALSE(r.timed_out) << r;
    EXPECT_EQ(r.exit_code, 1) << r;
    const auto errors = lines_starting_with(r.err, "bounce: error: ");
    EXPECT_EQ(errors.size(), 1u) << r;
    if (errors.size() == 1) {
      EXPECT_TRUE(contains(errors[0], (copy / h.file).string())) << errors[0];
      for (const std::string& w : h.words) EXPECT_TRUE(contains(errors[0], w)) << errors[0];
    }
    fs::remove_all(copy);
  }
}

}  // namespace
}  // namespace bounce::itest
