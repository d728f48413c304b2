// `bounce solve BAKE --compare-exact`: what compression changes in the light
// a user sees, checked against two plain solves of the same frame, one with
// the compressed product and one with the exact matrix (--multiply dense):
// the per-patch figure, the per-vertex error in the PLY and the camera
// picture's figure are recomputed from their outputs.
#include <OpenImageIO/imageio.h>

#include "cli_harness.h"
#include "folder/bake_reader.h"
#include "folder/final_gather_files.h"
#include "ply_vertices.h"
#include "solve_fixture.h"

namespace bounce::itest {
namespace {

std::vector<float> read_exr(const fs::path& path, int& width, int& height) {
  auto in = OIIO::ImageInput::open(path.string());
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return {};
  width = in->spec().width;
  height = in->spec().height;
  std::vector<float> pixels(static_cast<std::size_t>(width) * height * 3);
  EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, pixels.data()));
  return pixels;
}

// sqrt(sum |x - y|^2 / sum |y|^2), optionally weighted.
double relative_rms(const std::vector<double>& x, const std::vector<double>& y,
                    const std::vector<double>& w) {
  double d2 = 0.0, y2 = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double wk = w.empty() ? 1.0 : w[k / 3];
    d2 += wk * (x[k] - y[k]) * (x[k] - y[k]);
    y2 += wk * y[k] * y[k];
  }
  return std::sqrt(d2 / y2);
}

// Runs solve at a small camera size; returns what it printed.
RunResult solve_small(const fs::path& bake, const fs::path& out, std::vector<std::string> extra) {
  std::vector<std::string> args{"solve",   bake.string(), "--out",    out.string(), "--json",
                                "--width", "64",          "--height", "48",         "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  return run(args, out.parent_path(), 120.0);
}

TEST_F(Solve, CompareExactFiguresAndFilesMatchASolveThroughTheExactMatrix) {
  // float32: the compressed product exactly as decoded.
  const RunResult compared = solve_small(bake, tmp->path() / "compared",
                                         {"--multiply", "cpp", "--float32", "--compare-exact"});
  ASSERT_EQ(compared.exit_code, 0) << compared;
  const RunResult exact = solve_small(bake, tmp->path() / "exact", {"--multiply", "dense"});
  ASSERT_EQ(exact.exit_code, 0) << exact;
  const json c = parse_json(compared.out)["compare_exact"];
  const fs::path a = tmp->path() / "compared", b = tmp->path() / "exact";

  // Per patch: the indirect light (slot 2 of patch_light.npy), area-weighted.
  const NpyArray<float> la = read_npy_f32(a / "patch_light.npy");
  const NpyArray<float> lb = read_npy_f32(b / "patch_light.npy");
  const NpyArray<float> patches = read_npy_f32(bake / "patches.npy");
  std::vector<double> x, y, area;
  for (std::size_t p = 0; p < la.shape[0]; ++p) {
    area.push_back(at(patches, p, 6));
    for (std::size_t k = 0; k < 3; ++k) {
      x.push_back(la.data[p * 9 + 6 + k]);
      y.push_back(lb.data[p * 9 + 6 + k]);
    }
  }
  const double patch = relative_rms(x, y, area);
  EXPECT_GT(patch, 0.0);
  EXPECT_NEAR(c["patch_indirect_rel_rms"].get<double>(), patch, 1e-4 * patch);

  // Per vertex: error_abs in the PLY is |L~ - L| against the exact solve's
  // radiance; the summary's relative RMS is over every vertex.
  const PlyVertices va = read_ply_vertices(a / "lit.ply");
  const PlyVertices vb = read_ply_vertices(b / "lit.ply");
  ASSERT_EQ(va.rows.size(), vb.rows.size());
  ASSERT_GT(va.rows.size(), 0u);
  const std::size_t r = va.column("radiance_r"), e_abs = va.column("error_abs");
  const std::size_t e_rel = va.column("error_rel");
  std::vector<double> vx, vy;
  double worst_rel = 0.0;
  for (std::size_t v = 0; v < va.rows.size(); ++v) {
    double d2 = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      const double xa = va.rows[v][r + k], xb = vb.rows[v][vb.column("radiance_r") + k];
      vx.push_back(xa);
      vy.push_back(xb);
      d2 += (xa - xb) * (xa - xb);
    }
    ASSERT_NEAR(va.rows[v][e_abs], std::sqrt(d2), 1e-5 * (1.0 + std::sqrt(d2))) << "vertex " << v;
    worst_rel = std::max(worst_rel, static_cast<double>(va.rows[v][e_rel]));
  }
  const double vertex = relative_rms(vx, vy, {});
  EXPECT_NEAR(c["vertex_rel_rms"].get<double>(), vertex, 1e-4 * vertex);
  EXPECT_NEAR(c["vertex_max_relative"].get<double>(), worst_rel, 1e-5 * worst_rel);

  // The camera's indirect picture against the exact solve's.
  int w = 0, h = 0, w2 = 0, h2 = 0;
  const std::vector<float> ia = read_exr(a / "camera_indirect.exr", w, h);
  const std::vector<float> ib = read_exr(b / "camera_indirect.exr", w2, h2);
  ASSERT_EQ(w, w2);
  const double image = relative_rms(std::vector<double>(ia.begin(), ia.end()),
                                    std::vector<double>(ib.begin(), ib.end()), {});
  EXPECT_NEAR(c["image_indirect_rel_rms"].get<double>(), image, 1e-3 * image);
  const std::vector<float> err = read_exr(a / "camera_indirect_error.exr", w2, h2);
  ASSERT_EQ(err.size(), ia.size());
  for (std::size_t k = 0; k < err.size(); ++k)
    ASSERT_NEAR(err[k], std::abs(ia[k] - ib[k]), 1e-6f * (1.0f + std::abs(ib[k]))) << k;
  EXPECT_TRUE(fs::exists(a / "camera_indirect_error.png"));
}

// The manifest's vertex figure: per evaluation light, the indirect light
// T b and T~ b (T.npy, and T.dds decoded) carried to the lit mesh's vertices
// through the stored final gather, summed here row by row (patch, cluster
// and sample sources), then the relative RMS over vertices; worst and mean
// over the lights.
TEST_F(Solve, ManifestVertexLightErrorIsTheGatheredIndirectLightsError) {
  const LoadedBake b = BakeReader::read(bake, BakeReader::Dense::kRead);
  ASSERT_TRUE(b.compressed);
  ASSERT_FALSE(b.dense.empty());
  const std::size_t n = b.size();
  const std::optional<FinalGather> g = read_final_gather(bake, n, b.samples.samples.size());
  ASSERT_TRUE(g) << "the fixture bakes with a final gather";
  std::vector<std::vector<float>> decoded(b.dense.size(), std::vector<float>(n * n));
  for (std::size_t c = 0; c < decoded.size(); ++c)
    decompress_channel(*b.compressed, static_cast<int>(c), decoded[c].data());
  // Each sample's patch, from the patches' member lists.
  std::vector<std::int64_t> patch_of(b.samples.samples.size(), -1);
  for (std::size_t p = 0; p < n; ++p)
    for (std::uint32_t k = b.patches.member_first[p]; k < b.patches.member_first[p + 1]; ++k)
      patch_of[b.patches.member_samples[k]] = static_cast<std::int64_t>(p);
  const auto vertex_light = [&](const std::vector<std::vector<float>>& t,
                                const std::vector<glm::vec3>& light) {
    std::vector<glm::dvec3> tb(n, glm::dvec3(0.0));
    for (std::size_t p = 0; p < n; ++p)
      for (int k = 0; k < 3; ++k) {
        const auto& m = t[static_cast<std::size_t>(b.channel_of_rgb[static_cast<std::size_t>(k)])];
        for (std::size_t j = 0; j < n; ++j) tb[p][k] += double(m[p * n + j]) * light[j][k];
      }
    std::vector<glm::dvec3> source(g->patches + g->clusters + g->samples + g->near.size(),
                                   glm::dvec3(0.0));
    for (std::size_t p = 0; p < n; ++p) {
      source[p] = tb[p];
      source[n + g->cluster_of_patch[p]] += double(g->cluster_share[p]) * tb[p];
    }
    for (std::size_t s = 0; s < g->samples; ++s)
      if (patch_of[s] >= 0) source[n + g->clusters + s] = tb[static_cast<std::size_t>(patch_of[s])];
    // Near sources carry their patch's T b too (their direct part is not
    // the matrix's).
    for (std::size_t k = 0; k < g->near.size(); ++k)
      source[n + g->clusters + g->samples + k] = tb[g->near.patch[k]];
    std::vector<glm::dvec3> e(g->points(), glm::dvec3(0.0));
    for (std::size_t v = 0; v < g->points(); ++v)
      for (std::uint64_t k = g->first[v]; k < g->first[v + 1]; ++k)
        e[v] += double(g->weight[k]) * source[g->source[k]];
    return e;
  };
  double worst = 0.0, sum = 0.0;
  int lights = 0;
  for (const std::vector<glm::vec3>& light : b.probe.first_hit) {
    const std::vector<glm::dvec3> x = vertex_light(b.dense, light),
                                  y = vertex_light(decoded, light);
    double err2 = 0.0, ref2 = 0.0;
    for (std::size_t v = 0; v < x.size(); ++v) {
      err2 += glm::dot(y[v] - x[v], y[v] - x[v]);
      ref2 += glm::dot(x[v], x[v]);
    }
    if (!(ref2 > 0.0)) continue;
    const double rel = std::sqrt(err2 / ref2);
    worst = std::max(worst, rel);
    sum += rel;
    ++lights;
  }
  ASSERT_GT(lights, 0);
  const json& manifest = b.manifest["compression"]["errors"]["indirect_light_vertices"];
  ASSERT_TRUE(manifest.is_object()) << b.manifest["compression"]["errors"].dump();
  EXPECT_EQ(manifest["lights"].get<int>(), lights);
  EXPECT_GT(worst, 0.0);
  EXPECT_NEAR(manifest["rel_rms_max"].get<double>(), worst, 1e-3 * worst);
  EXPECT_NEAR(manifest["rel_rms_mean"].get<double>(), sum / lights, 1e-3 * sum / lights);
}

TEST_F(Solve, CompareExactNeedsTheExactAndTheCompressedMatrix) {
  const RunResult dense =
      solve_small(bake, tmp->path() / "dense", {"--multiply", "dense", "--compare-exact"});
  EXPECT_EQ(dense.exit_code, 1) << dense;
  EXPECT_TRUE(contains(dense.err, "--compare-exact")) << dense;
  // A copy of the bake without its exact matrix.
  const fs::path copy = tmp->path() / "without_exact";
  fs::copy(bake, copy, fs::copy_options::recursive);
  fs::remove(copy / "T.npy");
  const RunResult missing = solve_small(copy, tmp->path() / "missing", {"--compare-exact"});
  EXPECT_EQ(missing.exit_code, 1) << missing;
  EXPECT_TRUE(contains(missing.err, "--dump-matrices")) << missing;
}

}  // namespace
}  // namespace bounce::itest
