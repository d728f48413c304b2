#include "settings/settings_table.h"

#include <algorithm>
#include <optional>
#include <string>

#include "transport/text_format.h"
#include "voxel/voxel_grid.h"

namespace bounce {

namespace {

// Typed accessors of BakeSettings members, as the table's plain function
// pointers.
template <auto M>
SettingValue get_int(const BakeSettings& s) {
  return static_cast<std::int64_t>(s.*M);
}
template <auto M>
void set_int(BakeSettings& s, const SettingValue& v) {
  s.*M = static_cast<int>(std::get<std::int64_t>(v));
}
template <auto M>
SettingValue get_optional_int(const BakeSettings& s) {
  return s.*M ? SettingValue(static_cast<std::int64_t>(*(s.*M))) : SettingValue();
}
template <auto M>
void set_optional_int(BakeSettings& s, const SettingValue& v) {
  if (std::holds_alternative<std::monostate>(v))
    (s.*M).reset();
  else
    s.*M = static_cast<int>(std::get<std::int64_t>(v));
}
template <auto M>
SettingValue get_optional_real(const BakeSettings& s) {
  return s.*M ? SettingValue(*(s.*M)) : SettingValue();
}
template <auto M>
void set_optional_real(BakeSettings& s, const SettingValue& v) {
  if (std::holds_alternative<std::monostate>(v))
    (s.*M).reset();
  else
    s.*M = std::get<double>(v);
}
template <auto M>
SettingValue get_real(const BakeSettings& s) {
  return s.*M;
}
template <auto M>
void set_real(BakeSettings& s, const SettingValue& v) {
  s.*M = std::get<double>(v);
}
template <auto M>
SettingValue get_flag(const BakeSettings& s) {
  return s.*M;
}
template <auto M>
void set_flag(BakeSettings& s, const SettingValue& v) {
  s.*M = std::get<bool>(v);
}

const char* name_of(PatchMode m) { return m == PatchMode::Voxel ? "voxel" : "virtual"; }
const char* name_of(CodecChoice c) { return to_string(c); }
const char* name_of(OutOfCore o) { return to_string(o); }
const char* name_of(ProbePlacementMode m) { return to_string(m); }
const char* name_of(OrderingMethod o) { return ordering_name(o); }
const char* name_of(TransportSettings::Backend b) {
  switch (b) {
    case TransportSettings::Backend::OpenBLAS:
      return "openblas";
    case TransportSettings::Backend::CLBlast:
      return "clblast";
    case TransportSettings::Backend::Auto:
      break;
  }
  return "auto";
}

// The enumerator named `name` (a Choice row's value, checked against the
// row's choices before it gets here).
template <typename E, std::size_t N>
E named(const E (&all)[N], const SettingValue& v) {
  const std::string& name = std::get<std::string>(v);
  for (const E e : all)
    if (name == name_of(e)) return e;
  throw Error("settings table", "no enumerator named '" + name + "'");
}

constexpr PatchMode kPatchModes[] = {PatchMode::Virtual, PatchMode::Voxel};
constexpr CodecChoice kCodecs[] = {CodecChoice::Auto, CodecChoice::Dense,
                                   CodecChoice::LargestEntries, CodecChoice::LightWeighted};
constexpr OutOfCore kOutOfCore[] = {OutOfCore::Auto, OutOfCore::On, OutOfCore::Off};
constexpr ProbePlacementMode kProbeModes[] = {ProbePlacementMode::Auto, ProbePlacementMode::On,
                                              ProbePlacementMode::VolumesOnly,
                                              ProbePlacementMode::Off};
constexpr OrderingMethod kOrderings[] = {OrderingMethod::None, OrderingMethod::GreedyRowTour,
                                         OrderingMethod::GreedyRowThenColumnTour,
                                         OrderingMethod::SketchTour};
constexpr TransportSettings::Backend kBackends[] = {TransportSettings::Backend::Auto,
                                                    TransportSettings::Backend::OpenBLAS,
                                                    TransportSettings::Backend::CLBlast};

// Three fields of BakeSettings are not rows, on purpose: the tuning constants
// of the automatic choices in TransportSettings, auto_tolerance (the share of
// the light below which --bounces auto stops adding bounces), max_auto_bounces
// (where it switches to K = infinity) and auto_probe_min_seconds (the
// predicted OpenBLAS time below which --gemm auto does not probe CLBlast).
// They are not user-facing: no front end offers them, the help of --bounces
// states the tolerance, and a row would add a CLI flag and two keys to every
// manifest's settings. Library callers and tests may still set them;
// the transport stage checks their ranges, and the re-bake plan compares the
// two that decide the number of bounces by hand.
std::vector<SettingRow> make_rows() {
  using S = BakeSettings;
  std::vector<SettingRow> rows;
  rows.push_back({
      .name = "voxel_resolution",
      .manifest_key = "voxel_resolution",
      .flag = "--voxel",
      .type = SettingType::Int,
      .optional = true,
      .unset = "the scene's, else 16",
      .min = 1,
      .max = VoxelGrid::kMaxResolution,
      .help = "Voxel grid resolution: cells along the scene's longest axis. More cells = more, "
              "smaller patches (default: the scene's own, else 16)",
      .label = "Voxel size",
      .studio_help = "Voxels along the scene's longest side. More voxels: smaller patches, finer "
                     "light detail, longer bakes (patch count grows about with the square)",
      .stage = BakeStage::Geometry,
      .grid = true,
      .get = get_optional_int<&S::voxel_resolution>,
      .set = set_optional_int<&S::voxel_resolution>,
  });
  rows.push_back({
      .name = "patches_total",
      .manifest_key = "patches_total_target",
      .flag = "--patches-total",
      .type = SettingType::Int,
      .optional = true,
      .unset = "none",
      .min = 1,
      .max = 1 << 20,
      .excludes = "voxel_resolution",
      .help = "This many patches: picks the voxel resolution for you, then (virtual patches) "
              "spends the budget where merging costs most, so curved or unevenly lit voxels "
              "keep more patches than flat walls",
      .label = "Total patches",
      .studio_help =
          "Aim for about this many patches; the bake picks the voxel size that comes closest",
      .stage = BakeStage::Geometry,
      .grid = true,
      .get = get_optional_int<&S::patches_total>,
      .set = set_optional_int<&S::patches_total>,
  });
  rows.push_back({
      .name = "patches_per_voxel",
      .manifest_key = "patches_per_voxel",
      .flag = "--patches-per-voxel",
      .type = SettingType::Int,
      .optional = true,
      .unset = "the scene's, else 3",
      .min = 1,
      .max = 64,
      .help = "Virtual patches kept per voxel after clustering (default: the scene's, else 3: a "
              "box corner holds three orientations); with --patches-total, the average used to "
              "pick the grid",
      .label = "Patches per voxel",
      .studio_help = "Patches kept in each voxel after clustering its samples. 3 keeps the three "
                     "walls of a room corner apart; more subdivides flat surfaces",
      .stage = BakeStage::Patches,
      .get = get_optional_int<&S::patches_per_voxel>,
      .set = set_optional_int<&S::patches_per_voxel>,
  });
  rows.push_back({
      .name = "patch_mode",
      .manifest_key = "patch_mode",
      .flag = "--patches",
      .type = SettingType::Choice,
      .choices = {{"virtual", "virtual patches"}, {"voxel", "voxel baseline"}},
      .help_shows_default = true,
      .help = "virtual: cluster samples into virtual patches (the method, default); voxel: one "
              "patch per voxel and normal direction (the baseline)",
      .label = "Patches",
      .studio_help = "virtual: the samples in each voxel clustered into patches (the method); "
                     "voxel baseline: one patch per voxel, for comparison",
      .stage = BakeStage::Patches,
      .get = [](const S& s) -> SettingValue { return std::string(name_of(s.patch_mode)); },
      .set = [](S& s, const SettingValue& v) { s.patch_mode = named(kPatchModes, v); },
  });
  rows.push_back({
      .name = "samples_per_face",
      .manifest_key = "samples_per_face",
      .flag = "--samples-per-face",
      .type = SettingType::Int,
      .optional = true,
      .unset = "the scene's, else 4",
      .min = 1,
      .max = 64,
      .help = "Rays per voxel face are N x N (default: the scene's, else 4: 96 rays per voxel)",
      .stage = BakeStage::Geometry,
      .get = get_optional_int<&S::samples_per_face>,
      .set = set_optional_int<&S::samples_per_face>,
  });
  // The form-factor rows below re-run from the patches, not the form
  // factors: the checks prune the patches that see nothing, so new form
  // factors need the unpruned patches, i.e. the clustering again (see
  // BakeStage; that stage also builds the ray tracer the closure and the
  // final gather trace with).
  rows.push_back({
      .name = "visibility_rays",
      .manifest_key = "visibility_rays",
      .flag = "--visibility-rays",
      .type = SettingType::Int,
      .min = 1,
      .max = 1024,
      .help_shows_default = true,
      .help = "Shadow rays per patch pair for form-factor visibility",
      .stage = BakeStage::Patches,
      .get = get_int<&S::visibility_rays>,
      .set = set_int<&S::visibility_rays>,
  });
  rows.push_back({
      .name = "closure_rays",
      .manifest_key = "closure_rays",
      .flag = "--closure-rays",
      .type = SettingType::Int,
      .min = 0,
      .max = 65536,
      .range_note = "0: no balancing",
      .help_shows_default = true,
      .help = "Rays per patch measuring the share of its light that lands on sampled surface "
              "(its closure, 1 in a closed room); the form factors are then balanced so each "
              "row sums to it and reciprocity is exact. 0: keep the raw quadrature",
      .stage = BakeStage::Patches,
      .get = get_int<&S::closure_rays>,
      .set = set_int<&S::closure_rays>,
  });
  rows.push_back({
      .name = "final_gather_rays",
      .manifest_key = "final_gather_rays",
      .flag = "--final-gather-rays",
      .type = SettingType::Int,
      .min = 0,
      .max = 65536,
      .range_note = "0: no final gather",
      .help_shows_default = true,
      .help = "Rays per vertex of the lit mesh: each vertex gathers its indirect light from "
              "the patches it sees through these ray-traced form factors, stored in the bake "
              "(gather_*.npy). 0: no final gather; vertices take the nearest patches' light",
      .label = "Gather rays per vertex",
      .studio_help = "Rays each vertex of the lit mesh sends to find the surfaces it gathers "
                     "light from: more is smoother and sharper, and every light move reads "
                     "more entries. 0: vertices blend the nearest patches' light",
      .stage = BakeStage::Patches,
      .get = get_int<&S::final_gather_rays>,
      .set = set_int<&S::final_gather_rays>,
  });
  rows.push_back({
      .name = "final_gather_near",
      .manifest_key = "final_gather_near",
      .flag = "--final-gather-near",
      .type = SettingType::Real,
      .min = 0.0,
      .max = 16.0,
      .range_note = "0: no near sources",
      .help_shows_default = true,
      .help = "Distance in voxels within which a vertex's gather rays read near sources: "
              "cells of 1/24 voxel on the surface they hit, lit every frame at their own "
              "position (one shadow ray per light each), instead of a sample's light, which "
              "is that of its centre. Follows sun edges and contact light next to the vertex; "
              "each frame traces one more shadow ray per near source. 0: none",
      .label = "Near sources (voxels)",
      .studio_help = "Vertices read the light of the surface within this many voxels at their "
                     "own resolution (sunlit ledges, shadow edges next to them); more costs "
                     "shadow rays every frame",
      .stage = BakeStage::Patches,
      .get = get_real<&S::final_gather_near>,
      .set = set_real<&S::final_gather_near>,
  });
  rows.push_back({
      .name = "final_gather_near_min_rays",
      .manifest_key = "final_gather_near_min_rays",
      .flag = "--final-gather-near-min-rays",
      .type = SettingType::Int,
      .min = 1,
      .max = 65536,
      .range_note = "1: keep every near source",
      .help_shows_default = true,
      .help = "Near sources that fewer than this many gather rays landed in (over all "
              "vertices) go back to the sample or patch the vertices read for that surface. "
              "Each near source costs one shadow ray per light every frame; on Sponza (4096 "
              "patches) 2 keeps 67% of them and 3 keeps 53%, for 0.4% and 1% more vertex error, "
              "and 2 brings a light move there under 16 ms on 2 cores. A source one ray landed "
              "in is 1/256 of one vertex's light. Vertices far apart (on large faces) share few "
              "near sources: theirs hold a ray or two each and are the ones that go. 1: keep all",
      .label = "Near sources: least rays",
      .studio_help = "Fewer near sources make every light move faster (one shadow ray each) "
                     "at a little accuracy next to sunlit ledges",
      .stage = BakeStage::Patches,
      .get = get_int<&S::final_gather_near_min_rays>,
      .set = set_int<&S::final_gather_near_min_rays>,
  });
  rows.push_back({
      .name = "final_gather_spots",
      .manifest_key = "final_gather_spots",
      .flag = "--final-gather-spots",
      .type = SettingType::Int,
      .min = 0,
      .max = 64,
      .range_note = "0: samples lit at their centres",
      .help_shows_default = true,
      .help = "Points per sample, where the vertices' gather rays beyond the near sources "
              "landed on it most (cells of 1/8 voxel), lit every frame (one shadow ray per "
              "light each) and weighted by those rays: a sample's light is then that of the "
              "parts of it the vertices see (the sunlit top of a ledge more than its shaded "
              "front) instead of its centre's. On Sponza (sun, 8192 patches) 2 brings the "
              "mean indirect level from 3.5-5% low to within 1.5% of the reference (1 leaves "
              "the picture 9% worse than 2, 3 is 1% better) and costs about 0.55 ms a light "
              "move per spot at 4096 patches on 2 cores. 0: none",
      .label = "Spots per sample",
      .studio_help = "Each sample lit where the vertices' rays land on it (the parts of it "
                     "that are seen) instead of at its centre; each spot costs a shadow ray "
                     "every light move",
      .stage = BakeStage::Patches,
      .get = get_int<&S::final_gather_spots>,
      .set = set_int<&S::final_gather_spots>,
  });
  rows.push_back({
      .name = "light_probes",
      .manifest_key = "light_probes",
      .flag = "--light-probes",
      .type = SettingType::Choice,
      .choices = {{"auto", "auto"},
                  {"on", "next to surfaces and in volumes"},
                  {"volumes", "in volumes only"},
                  {"off", "off"}},
      .help_shows_default = true,
      .help = "Light probes for objects that move, each frame every probe's irradiance as SH "
              "L2, lit by the same solution as the vertices (probe_*.npy): on (in the empty "
              "voxels next to surfaces, and in every probe volume), volumes (only in the "
              "probe volumes), off, or auto (the scene's bake block, else on; a grid with more "
              "candidates than --light-probes-max then places none next to the surfaces and "
              "says so, where on refuses the bake)",
      .label = "Light probes",
      .studio_help = "Points in the empty space that light moving objects with the same "
                     "bounced light as the walls around them",
      .stage = BakeStage::Patches,
      .get = [](const S& s) -> SettingValue { return std::string(name_of(s.light_probes)); },
      .set = [](S& s, const SettingValue& v) { s.light_probes = named(kProbeModes, v); },
  });
  rows.push_back({
      .name = "light_probe_volumes",
      .manifest_key = "light_probe_volumes",
      .flag = "--light-probe-volumes",
      .type = SettingType::Text,
      .help = "Boxes filled with light probes at a spacing of their own, beside those next to "
              "surfaces: x0,y0,z0,x1,y1,z1,spacing per box (two corners in scene units, the "
              "distance between neighbouring probes), boxes separated by ';', e.g. "
              "'-1,0,-1,1,2,1,0.25'. Default: the scene's bake block's, else none",
      .stage = BakeStage::Patches,
      .get = [](const S& s) -> SettingValue { return s.light_probe_volumes; },
      .set = [](S& s, const SettingValue& v) { s.light_probe_volumes = std::get<std::string>(v); },
  });
  rows.push_back({
      .name = "light_probes_max",
      .manifest_key = "light_probes_max",
      .flag = "--light-probes-max",
      .type = SettingType::Int,
      .min = 1,
      .max = 16777216,
      .help_shows_default = true,
      .help = "Most light probes a bake may place: more candidates (empty voxels next to "
              "surfaces and the probe volumes' lattice points) are refused before any probe is "
              "traced (a probe holds about 2000 gather entries, some 25 KB while baking and "
              "15 KB in the folder)",
      .stage = BakeStage::Patches,
      .get = get_int<&S::light_probes_max>,
      .set = set_int<&S::light_probes_max>,
  });
  rows.push_back({
      .name = "seed",
      .manifest_key = "seed",
      .flag = "--seed",
      .type = SettingType::Seed,
      .help_shows_default = true,
      .help = "Seed of every random stream (results are reproducible)",
      .stage = BakeStage::Geometry,
      .get = [](const S& s) -> SettingValue { return s.seed; },
      .set = [](S& s, const SettingValue& v) { s.seed = std::get<std::uint64_t>(v); },
  });
  rows.push_back({
      .name = "bounces",
      .manifest_key = "bounces",
      .flag = "--bounces",
      .type = SettingType::Int,
      .min = 1,
      .max = TransportSettings::kMaxBounces,
      .named = {{"auto", TransportSettings::kAutoBounces, "auto"},
                {"inf", TransportSettings::kInfiniteBounces, "infinite (exact)"},
                {"infinity", TransportSettings::kInfiniteBounces}},
      .help_shows_default = true,
      .help = "Light bounces folded into the transport matrix: auto (stop when the next bounce "
              "adds less than 0.1% of the light), inf (the exact limit, by LU), or 1..64",
      .label = "Bounces",
      .studio_help = "How many times light bounces between surfaces. auto: until the next "
                     "bounce adds less than 0.1%; infinite: the exact limit",
      .stage = BakeStage::Transport,
      .get = [](const S& s) -> SettingValue {
        return static_cast<std::int64_t>(s.transport.bounces);
      },
      .set =
          [](S& s, const SettingValue& v) {
            s.transport.bounces = static_cast<int>(std::get<std::int64_t>(v));
          },
  });
  // The backends round differently: the matrices are not bit-identical.
  rows.push_back({
      .name = "gemm",
      .manifest_key = "gemm",
      .flag = "--gemm",
      .type = SettingType::Choice,
      .choices = {{"auto", "auto"}, {"openblas", "OpenBLAS"}, {"clblast", "CLBlast"}},
      .help_shows_default = true,
      .help = "Matrix products on: auto (time both, keep the faster), openblas (CPU) or "
              "clblast (OpenCL)",
      .stage = BakeStage::Transport,
      .get = [](const S& s) -> SettingValue { return std::string(name_of(s.transport.backend)); },
      .set = [](S& s, const SettingValue& v) { s.transport.backend = named(kBackends, v); },
  });
  rows.push_back({
      .name = "out_of_core",
      .manifest_key = "out_of_core",
      .flag = "--out-of-core",
      .type = SettingType::Choice,
      .choices = {{"auto", "auto"}, {"on", "on"}, {"off", "off"}},
      .help_shows_default = true,
      .help = "Keep the finished N x N matrices (form factors, transport) in memory-mapped "
              "temporary files the kernel can page out: auto (when the dense matrices would "
              "take more than half the machine's memory), on, off. Same result either way",
      .get = [](const S& s) -> SettingValue { return std::string(name_of(s.out_of_core)); },
      .set = [](S& s, const SettingValue& v) { s.out_of_core = named(kOutOfCore, v); },
  });
  rows.push_back({
      .name = "out_of_core_dir",
      .manifest_key = "out_of_core_dir",
      .flag = "--out-of-core-dir",
      .type = SettingType::Text,
      .help = "Folder of the temporary matrix files (default: $TMPDIR, else /tmp); they are "
              "deleted as soon as they are created and vanish with the process",
      .get = [](const S& s) -> SettingValue { return s.out_of_core_dir; },
      .set = [](S& s, const SettingValue& v) { s.out_of_core_dir = std::get<std::string>(v); },
  });
  rows.push_back({
      .name = "codec",
      .manifest_key = "codec",
      .flag = "--codec",
      .type = SettingType::Choice,
      .choices = {{"auto", "auto"},
                  {"dense", "dense (exact)"},
                  {"paper", "paper (published BC1)"},
                  {"ours", "ours"}},
      .help_shows_default = true,
      .help = "How the transport matrix is stored: auto (ours, or dense when it is under "
              "1 MiB and compression would not pay), dense (exact float32), paper (the "
              "published pipeline: 4% kept, greedy L1 reordering, libsquish BC1), ours "
              "(entries kept and blocks weighted by the light they carry, better "
              "reordering, kept fraction from the error budget)",
      .label = "Codec",
      .studio_help = "How the light-transport matrix is stored. dense: exact and large; paper: "
                     "the published DXT1 pipeline; ours: smaller for the same error; auto: ours, "
                     "or dense when the matrix is too small for compression to pay",
      .stage = BakeStage::Compress,
      .get = [](const S& s) -> SettingValue { return std::string(name_of(s.codec)); },
      .set = [](S& s, const SettingValue& v) { s.codec = named(kCodecs, v); },
  });
  rows.push_back({
      .name = "ordering",
      .manifest_key = "ordering",
      .flag = "--ordering",
      .type = SettingType::Choice,
      .optional = true,
      .unset = "auto",
      .unset_label = "codec's own",
      .choices = {{"none", "none (patch order)"},
                  {"paper-1-pass", "paper, 1 pass"},
                  {"paper-2-passes", "paper, 2 passes"},
                  {"ours", "ours"}},
      .help_shows_default = true,
      .help = "Row/column ordering before block encoding (paper and ours): auto (the codec's "
              "own: paper-2-passes for paper, ours for ours), none, paper-1-pass, "
              "paper-2-passes (the published greedy L1 tour) or ours (sketch + tour + 4-row "
              "refinement)",
      .label = "Ordering",
      .studio_help =
          "The order of the matrix rows and columns before they are cut into 4x4 blocks: "
          "similar rows side by side make smoother blocks and less compression error (see the "
          "Matrix view's right half). codec's own: paper's 2-pass tour for paper, ours for ours; "
          "paper: the published greedy tour (slow on large matrices); none: patch order. "
          "Changing it re-runs only the compression",
      .stage = BakeStage::Compress,
      .get = [](const S& s) -> SettingValue {
        return s.ordering ? SettingValue(std::string(name_of(*s.ordering))) : SettingValue();
      },
      .set =
          [](S& s, const SettingValue& v) {
            if (std::holds_alternative<std::monostate>(v))
              s.ordering.reset();
            else
              s.ordering = named(kOrderings, v);
          },
  });
  rows.push_back({
      .name = "kept_fraction",
      .manifest_key = "kept_fraction",
      .flag = "--kept-fraction",
      .type = SettingType::Real,
      .optional = true,
      .unset = "default",
      .min = 0.0,
      .max = 1.0,
      .help = "Share of each channel's largest entries kept exactly (default: the paper's 0.04 "
              "for --codec paper; chosen from --error-budget for ours)",
      .label = "Kept fraction",
      .studio_help = "Share of each colour's matrix values kept exactly (the paper keeps 0.04). "
                     "More: less error, larger bake",
      .stage = BakeStage::Compress,
      .get = get_optional_real<&S::kept_fraction>,
      .set = set_optional_real<&S::kept_fraction>,
  });
  rows.push_back({
      .name = "error_budget",
      .manifest_key = "error_budget",
      .flag = "--error-budget",
      .type = SettingType::Real,
      .optional = true,
      .unset = "default",
      .unset_value = BakeSettings::kDefaultErrorBudget,
      .min = 0.0,
      .max = 1.0,
      .min_exclusive = true,
      .max_exclusive = true,
      .excludes = "kept_fraction",
      .help_shows_default = true,
      .help = "Relative RMS error of the indirect light the compressed matrix may cause "
              "(area-weighted over patches, on the worst of the evaluation lights: the "
              "scene's lights, four point lights, five suns); ours keeps the fewest "
              "entries that meet it (default: the scene's bake block, else 0.02)",
      .label = "Error budget",
      .studio_help = "Relative RMS error of the indirect light the compressed matrix may cause, "
                     "on the worst evaluation light (0.02 = 2%); the codec keeps the fewest "
                     "exact values that meet it",
      .stage = BakeStage::Compress,
      .get = get_optional_real<&S::error_budget>,
      .set = set_optional_real<&S::error_budget>,
  });
  rows.push_back({
      .name = "size_limit",
      .manifest_key = "size_limit",
      .flag = "--size-limit",
      .type = SettingType::Real,
      .optional = true,
      .unset = "default",
      .unset_value = BakeSettings::kDefaultSizeLimit,
      .min = 0.0,
      .max = 1.0,
      .min_exclusive = true,
      .range_note = "a share of the dense float32 RGB matrix",
      .excludes = "kept_fraction",
      .help_shows_default = true,
      .help = "Largest size the error budget's search may give the compressed matrix, as "
              "a share of dense float32 RGB (0.125: at least 8x smaller); when no kept "
              "fraction within it meets the budget, the bake keeps the largest that fits "
              "and says so",
      .label = "Size limit",
      .studio_help = "Largest size the compressed matrix may take while meeting the error "
                     "budget, as a share of the uncompressed one (0.125 = 8x smaller); when "
                     "the budget cannot be met within it, the bake keeps the most exact values "
                     "that fit and says so in its warnings",
      .stage = BakeStage::Compress,
      .get = get_optional_real<&S::size_limit>,
      .set = set_optional_real<&S::size_limit>,
  });
  rows.push_back({
      .name = "dump_matrices",
      .manifest_key = "dump_matrices",
      .flag = "--dump-matrices",
      .type = SettingType::Flag,
      .writer_only = true,
      .help = "Also write the N x N form-factor matrix as F.npy and the exact transport "
              "matrix as T.npy",
      .get = get_flag<&S::dump_matrices>,
      .set = set_flag<&S::dump_matrices>,
  });
  rows.push_back({
      .name = "pictures",
      .manifest_key = "pictures",
      .flag = "--no-pictures",
      .type = SettingType::Flag,
      .flag_negates = true,
      .writer_only = true,
      .help = "Do not write the matrix and error pictures (PNG)",
      .get = get_flag<&S::pictures>,
      .set = set_flag<&S::pictures>,
  });
  return rows;
}

std::string number_text(double v) { return text_format("%g", v); }

bool in_range(const SettingRow& row, double v) {
  return (row.min_exclusive ? v > row.min : v >= row.min) &&
         (row.max_exclusive ? v < row.max : v <= row.max);
}

// "must be between 1 and 64", "must be above 0 and at most 1", with the
// named values first: "must be auto, inf or between 1 and 64".
std::string range_text(const SettingRow& row) {
  std::string names;
  for (const NamedValue& n : row.named)
    if (n.label) names += std::string(n.name) + ", ";
  if (!names.empty()) names.replace(names.size() - 2, 2, " or ");
  const std::string lo = number_text(row.min), hi = number_text(row.max);
  std::string range;
  if (!row.min_exclusive && !row.max_exclusive)
    range = "between " + lo + " and " + hi;
  else if (row.min_exclusive && row.max_exclusive)
    range = "between " + lo + " and " + hi + " (exclusive)";
  else
    range = std::string(row.min_exclusive ? "above " : "at least ") + lo +
            (row.max_exclusive ? " and below " : " and at most ") + hi;
  std::string text = "must be " + names + range;
  if (*row.range_note) text += std::string(" (") + row.range_note + ")";
  return text;
}

// `text` read by `read` (std::stoll and kin), when it is that number and
// nothing else.
template <typename T, typename Read>
std::optional<T> whole_text_as(const std::string& text, Read read) {
  std::size_t used = 0;
  try {
    const T v = read(text, &used);
    if (used > 0 && used == text.size()) return v;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

[[noreturn]] void invalid(const SettingRow& row, const std::string& what) {
  throw BakeSettings::InvalidSetting(row.name, what);
}

}  // namespace

std::span<const SettingRow> settings_table() {
  static const std::vector<SettingRow> rows = make_rows();
  return rows;
}

const SettingRow& setting_row(std::string_view name) {
  for (const SettingRow& row : settings_table())
    if (name == row.name) return row;
  throw Error("settings", "no setting named '" + std::string(name) + "'");
}

SettingValue parse_setting(const SettingRow& row, const std::string& text) {
  if (row.optional && text == row.unset) return {};
  switch (row.type) {
    case SettingType::Int: {
      for (const NamedValue& n : row.named)
        if (text == n.name) return n.value;
      const auto v = whole_text_as<long long>(
          text, [](const std::string& t, std::size_t* used) { return std::stoll(t, used); });
      if (!v) invalid(row, range_text(row) + ", got '" + text + "'");
      if (!in_range(row, static_cast<double>(*v))) invalid(row, range_text(row) + ", got " + text);
      return static_cast<std::int64_t>(*v);
    }
    case SettingType::Seed: {
      const auto v = whole_text_as<unsigned long long>(
          text, [](const std::string& t, std::size_t* used) { return std::stoull(t, used); });
      // As CLI11 reads an unsigned number: a minus sign wraps around (-1: 2^64 - 1).
      if (!v) invalid(row, "must be a whole number, got '" + text + "'");
      return static_cast<std::uint64_t>(*v);
    }
    case SettingType::Real: {
      const auto v = whole_text_as<double>(
          text, [](const std::string& t, std::size_t* used) { return std::stod(t, used); });
      if (!v) invalid(row, "must be a number, got '" + text + "'");
      return *v;
    }
    case SettingType::Flag:
      if (text == "true" || text == "1") return true;
      if (text == "false" || text == "0") return false;
      invalid(row, "must be true or false, got '" + text + "'");
    case SettingType::Choice: {
      std::string names;
      for (const SettingChoice& c : row.choices) {
        if (text == c.name) return text;
        names += std::string(names.empty() ? "" : ", ") + c.name;
      }
      invalid(row, "must be one of " + names + ", got '" + text + "'");
    }
    case SettingType::Text:
      break;
  }
  return text;
}

std::string setting_text(const SettingRow& row, const SettingValue& value) {
  return std::visit(
      [&row](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          return row.unset;
        } else if constexpr (std::is_same_v<T, bool>) {
          return v ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
          for (const NamedValue& n : row.named)
            if (n.value == v) return n.name;
          return std::to_string(v);
        } else if constexpr (std::is_same_v<T, std::uint64_t>) {
          return std::to_string(v);
        } else if constexpr (std::is_same_v<T, double>) {
          return number_text(v);
        } else {
          return v;
        }
      },
      value);
}

void check_setting(const SettingRow& row, const SettingValue& value) {
  if (std::holds_alternative<std::monostate>(value)) {
    if (!row.optional) invalid(row, "must be set");
    return;
  }
  if (row.type == SettingType::Int) {
    const std::int64_t v = std::get<std::int64_t>(value);
    const bool is_named = std::any_of(row.named.begin(), row.named.end(),
                                      [v](const NamedValue& n) { return n.value == v; });
    if (!is_named && !in_range(row, static_cast<double>(v)))
      invalid(row, range_text(row) + ", got " + std::to_string(v));
  } else if (row.type == SettingType::Real) {
    const double v = std::get<double>(value);
    if (!in_range(row, v)) invalid(row, range_text(row) + ", got " + number_text(v));
  } else if (row.type == SettingType::Choice) {
    const std::string& v = std::get<std::string>(value);
    if (std::none_of(row.choices.begin(), row.choices.end(),
                     [&v](const SettingChoice& c) { return v == c.name; }))
      invalid(row, "has no choice '" + v + "'");
  }
}

}  // namespace bounce
