// The lighting session over a bake read back (relight/lighting_session.h):
// its typed view of the manifest says what the scene says; it refuses
// another scene; it moves lights by name only; its lit mesh through the
// frame's own gather equals the one through an explicit T b; a moved light
// moves the direct light as a Relighter lit by hand does; the camera's
// direct picture follows the session's lights.
#include <gtest/gtest.h>

#include "bake/bake.h"
#include "bake/bake_writer.h"
#include "bake/stored_transport.h"
#include "base/error.h"
#include "folder/bake_reader.h"
#include "relight/lighting_session.h"
#include "runtime/area_lights.h"
#include "scene/scene_loader.h"
#include "scratch_dir.h"

namespace bounce {
namespace {

const std::string kScenes = std::string(BOUNCE_RESOURCE_DIR) + "/scenes/";

struct Fixture {
  std::shared_ptr<const Scene> scene;
  BakeResult bake;
  test::ScratchDir dir{"bounce-lighting-session"};

  Fixture() {
    Diagnostics d;
    scene = std::make_shared<const Scene>(SceneLoader(d).load(kScenes + "cornell-box"));
    BakeSettings s;
    s.voxel_resolution = 6;
    s.codec = CodecChoice::Dense;
    s.pictures = false;
    Progress progress;
    bake = Baker(*scene, s, d).run(progress);
    write_bake(dir / "bake", *scene, bake, d);
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

std::unique_ptr<LightingSession> open_session(const LightingSessionSettings& settings = {}) {
  const Fixture& f = fixture();
  auto bake = std::make_shared<const LoadedBake>(BakeReader::read(f.dir / "bake"));
  return std::make_unique<LightingSession>(bake, f.scene, settings);
}

TEST(LightingSession, DescriptionSaysWhatTheSceneSays) {
  const Fixture& f = fixture();
  const LoadedBake bake = BakeReader::read(f.dir / "bake");
  const BakeDescription& d = bake.description;
  EXPECT_EQ(d.scene_name, f.scene->name);
  EXPECT_EQ(d.scene_triangles, f.scene->triangle_count());
  ASSERT_EQ(d.scene_lights.size(), f.scene->lights.size());
  for (std::size_t i = 0; i < d.scene_lights.size(); ++i) {
    EXPECT_EQ(d.scene_lights[i].name, f.scene->lights[i].name);
    EXPECT_EQ(d.scene_lights[i].type, f.scene->lights[i].type);
    EXPECT_EQ(d.scene_lights[i].position, f.scene->lights[i].position);
    EXPECT_EQ(d.scene_lights[i].intensity, f.scene->lights[i].intensity);
  }
  const TransferGrid grid = TransferGrid::from(f.bake.voxels.grid);
  EXPECT_EQ(d.grid.dims, grid.dims);
  EXPECT_FLOAT_EQ(d.grid.cell_size, grid.cell_size);
  EXPECT_GT(d.bounces, 0);
}

TEST(LightingSession, RefusesAnotherSceneNamingIt) {
  const Fixture& f = fixture();
  auto bake = std::make_shared<const LoadedBake>(BakeReader::read(f.dir / "bake"));
  Diagnostics d;
  auto other = std::make_shared<const Scene>(SceneLoader(d).load(kScenes + "cornell-bunny"));
  try {
    LightingSession session(bake, other);
    FAIL() << "a session over another scene opened";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), other->path);
    EXPECT_NE(std::string(e.what()).find("not the same scene"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_baked_scene(*bake, kScenes + "cornell-bunny", d), Error);
  EXPECT_EQ(load_baked_scene(*bake, "", d).triangle_count(), f.scene->triangle_count());
}

TEST(LightingSession, MovesLightsByNameOnly) {
  std::vector<Light> lights(2);
  lights[0].name = "lamp";
  lights[1].name = "sun";
  lights[1].type = Light::Type::Directional;
  move_named_light(lights, "lamp", {1.0f, 2.0f, 3.0f});
  EXPECT_EQ(lights[0].position, glm::vec3(1.0f, 2.0f, 3.0f));
  try {
    move_named_light(lights, "candle", {});
    FAIL() << "moved a light the scene lacks";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "lights");
    EXPECT_NE(std::string(e.what()).find("lamp, sun"), std::string::npos) << e.what();
  }
  EXPECT_THROW(move_named_light(lights, "sun", {}), Error);
}

TEST(LightingSession, MovedLightLightsThePatchesAsARelighterLitByHand) {
  const Fixture& f = fixture();
  auto session = open_session();
  const Light& lamp = f.scene->lights.front();
  const glm::vec3 moved = lamp.position + glm::vec3(0.3f, -0.5f, 0.2f);
  session->move_light(lamp.name, moved);
  session->light();

  const LoadedBake bake = BakeReader::read(f.dir / "bake");
  const RayTracer tracer(*f.scene);
  Relighter by_hand(tracer, bake.samples, bake.patches, stored_transport(bake));
  std::vector<Light> lights = f.scene->lights;
  lights.front().position = moved;
  by_hand.light(lights, area_lights(*f.scene));
  std::vector<glm::vec3> b, tb, expected_b, expected_tb;
  session->relighter().first_hit_and_indirect(b, tb);
  by_hand.first_hit_and_indirect(expected_b, expected_tb);
  ASSERT_EQ(b.size(), expected_b.size());
  for (std::size_t p = 0; p < b.size(); ++p) {
    ASSERT_EQ(b[p], expected_b[p]) << "patch " << p;
    ASSERT_EQ(tb[p], expected_tb[p]) << "patch " << p;
  }
}

// The samples' and near sources' shadow rays spread over k frames
// (runtime/shadow_budget.h): a k-th of the batches traced per frame while the
// lamp moves, none while nothing moves, and k frames after the lamp stops
// the light on the patches and at the vertices is, to the bit, what tracing
// every ray gives.
TEST(LightingSession, ShadowRaysSpreadOverFramesAreExactKFramesAfterTheLightStops) {
  const Fixture& f = fixture();
  constexpr int kFrames = 4;
  LightingSessionSettings spread_settings;
  spread_settings.relighter.shadow_frames = kFrames;
  auto every = open_session();
  auto spread = open_session(spread_settings);
  ASSERT_TRUE(every->final_gather().has_value());
  const std::size_t near = every->final_gather()->near.size();
  ASSERT_GT(near, 256u * kFrames) << "batches of near sources to spread";
  const std::size_t batches = (near + 255) / 256;
  const std::size_t patches = every->bake().size();
  ASSERT_GT(patches, std::size_t{kFrames});
  const auto patch_light = [](const auto& s) { return s->relighter().frame().record(); };
  std::vector<glm::vec3> e_every, e_spread;
  const auto frame = [&] {
    every->light();
    every->vertex_irradiance(e_every);
    spread->light();
    spread->vertex_irradiance(e_spread);
  };
  frame();
  ASSERT_EQ(f.scene->lights.size(), 1u);
  EXPECT_EQ(every->relighter().near_traced_batches(), batches) << "the first frame: all";
  EXPECT_EQ(e_spread, e_every) << "the first frame traces every ray";
  EXPECT_EQ(spread->relighter().frame().traced_shadow_batches(), patches) << "the first frame";
  EXPECT_FALSE(patch_light(every).empty());
  EXPECT_EQ(patch_light(spread), patch_light(every));
  const Light& lamp = f.scene->lights.front();
  ASSERT_EQ(lamp.type, Light::Type::Point);
  bool differed = false, patches_differed = false;
  std::vector<glm::vec3> e_before;
  for (int m = 1; m <= 3; ++m) {
    const glm::vec3 moved = lamp.position + 0.15f * static_cast<float>(m) * glm::vec3(1, 0, 0);
    every->move_light(lamp.name, moved);
    spread->move_light(lamp.name, moved);
    e_before = e_spread;
    frame();
    EXPECT_EQ(every->relighter().near_traced_batches(), batches) << "every ray of the lamp";
    const std::size_t traced = spread->relighter().near_traced_batches();
    EXPECT_GE(traced, batches / kFrames);
    EXPECT_LE(traced, batches / kFrames + 1);
    const std::size_t traced_patches = spread->relighter().frame().traced_shadow_batches();
    EXPECT_GE(traced_patches, patches / kFrames);
    EXPECT_LE(traced_patches, patches / kFrames + 1);
    differed = differed || e_spread != e_every;
    patches_differed = patches_differed || patch_light(spread) != patch_light(every);
    // The gather summed a k-th of the vertices' rows; the others kept the
    // last frame's light.
    const RowSlice rows = spread->relighter().gather_rows().last();
    ASSERT_FALSE(rows.all()) << "a k-th of the rows while the lamp moves";
    ASSERT_EQ(e_spread.size(), e_before.size());
    for (std::size_t v = 0; v < e_spread.size(); ++v) {
      if (!rows.sums_band(v / kRowBand)) {
        ASSERT_EQ(e_spread[v], e_before[v]) << "vertex " << v;
      }
    }
  }
  EXPECT_TRUE(differed) << "stale shadows while the lamp moves";
  EXPECT_TRUE(patches_differed) << "stale sample shadows while the lamp moves";
  for (int still = 1; still <= kFrames; ++still) {
    frame();
    EXPECT_EQ(every->relighter().near_traced_batches(), 0u) << "nothing moved";
  }
  EXPECT_EQ(spread->relighter().frame().traced_shadow_batches(), 0u) << "every slice traced";
  EXPECT_TRUE(spread->relighter().shadows_settled());
  EXPECT_TRUE(spread->relighter().gather_rows().last().all()) << "every row once exact";
  EXPECT_EQ(e_spread, e_every) << kFrames << " frames after the lamp stopped";
  EXPECT_EQ(patch_light(spread), patch_light(every)) << kFrames << " frames after it stopped";
}

TEST(LightingSession, LitMeshThroughTheFrameEqualsLitMeshThroughItsTb) {
  auto session = open_session();
  ASSERT_TRUE(session->final_gather().has_value());
  session->light();
  const LitMesh frame = session->lit_mesh();
  std::vector<glm::vec3> b, tb;
  session->relighter().first_hit_and_indirect(b, tb);
  const LitMesh explicit_tb = session->lit_mesh(tb);
  ASSERT_EQ(frame.radiosity.size(), explicit_tb.radiosity.size());
  double total = 0.0;
  for (std::size_t v = 0; v < frame.radiosity.size(); ++v) {
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(frame.radiosity[v][c], explicit_tb.radiosity[v][c],
                  1e-5f * (1.0f + explicit_tb.radiosity[v][c]))
          << "vertex " << v;
    total += frame.radiosity[v].g;
  }
  EXPECT_GT(total, 0.0);
  // Without its T b the mesh is darker: the indirect light is there.
  const LitMesh no_tb = session->lit_mesh(std::vector<glm::vec3>(tb.size(), glm::vec3(0.0f)));
  double dimmer = 0.0;
  for (const glm::vec3& v : no_tb.radiosity) dimmer += v.g;
  EXPECT_LT(dimmer, total);
}

TEST(LightingSession, CameraDirectLightFollowsTheSessionsLights) {
  const Fixture& f = fixture();
  auto session = open_session();
  const Light& lamp = f.scene->lights.front();
  const glm::vec3 moved = lamp.position + glm::vec3(0.4f, -0.6f, 0.0f);
  session->move_light(lamp.name, moved);
  session->light();
  CameraImageSettings cs;
  cs.width = 32;
  cs.height = 24;
  const CameraImages images = session->camera(cs, 0).images();

  Scene by_hand = *f.scene;
  by_hand.lights.front().position = moved;
  const RayTracer tracer(by_hand);
  std::vector<CameraHit> hits;
  const CameraImages expected = render_camera_direct(tracer, cs, hits);
  ASSERT_EQ(images.direct.pixels.size(), expected.direct.pixels.size());
  for (std::size_t i = 0; i < expected.direct.pixels.size(); ++i)
    ASSERT_EQ(images.direct.pixels[i], expected.direct.pixels[i]) << "pixel " << i;
  EXPECT_THROW(session->camera(cs, -1), Error);
}

}  // namespace
}  // namespace bounce
