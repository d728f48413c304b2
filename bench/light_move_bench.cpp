#include "light_move_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "bounce/error.h"
#include "bounce/relight.h"

namespace bounce {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The light at frame f of its path: a point or spot light around a circle
// of radius 2% of the scene's diagonal through its start, a sun turned 1
// degree per frame about the camera's up axis.
Light light_at_frame(const Light& start, const Scene& scene, int f, int frames) {
  Light l = start;
  const glm::vec3 up = glm::normalize(scene.camera.up);
  if (l.type == Light::Type::Directional) {
    const float a = glm::radians(static_cast<float>(f));
    const glm::vec3 d = start.direction, along = glm::dot(d, up) * up, across = d - along;
    l.direction = along + std::cos(a) * across + std::sin(a) * glm::cross(up, across);
    return l;
  }
  const glm::vec3 side = std::abs(up.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 u = glm::normalize(glm::cross(up, side)), v = glm::cross(up, u);
  const float r = 0.02f * glm::length(scene.bounds().extent());
  const float a =
      2.0f * std::numbers::pi_v<float> * static_cast<float>(f) / static_cast<float>(frames);
  l.position = start.position + r * ((std::cos(a) - 1.0f) * u + std::sin(a) * v);
  return l;
}

// One frame of `session`, timed step by step, its vertices' irradiance in `e`.
LightMoveSteps timed_frame(LightingSession& session, std::vector<glm::vec3>& e) {
  LightMoveSteps s;
  const auto t0 = Clock::now();
  session.light();
  const auto t1 = Clock::now();
  session.vertex_irradiance(e);
  const double gather = ms_since(t1);
  if (session.light_probes()) {
    thread_local std::vector<glm::vec3> sh;
    const auto t2 = Clock::now();
    session.probe_sh(sh);
    s.probes = ms_since(t2);
  }
  s.whole = ms_since(t0);
  const RuntimeFrame& frame = session.frame();
  bool after_product = false;
  for (std::size_t i = 0; i < frame.graph().passes().size(); ++i) {
    after_product = after_product || frame.graph().passes()[i].name == "indirect product";
    (after_product ? s.indirect : s.direct) += 1e3 * frame.pass_seconds()[i];
  }
  s.near = 1e3 * session.relighter().near_seconds();
  s.product = gather - s.near;
  return s;
}

double relative_rms(const std::vector<glm::vec3>& e, const std::vector<glm::vec3>& reference) {
  double err = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    const glm::dvec3 d = glm::dvec3(e[i]) - glm::dvec3(reference[i]);
    err += glm::dot(d, d);
    norm += glm::dot(glm::dvec3(reference[i]), glm::dvec3(reference[i]));
  }
  return norm > 0.0 ? std::sqrt(err / norm) : std::sqrt(err);
}

LightMoveSteps median_steps(const std::vector<LightMoveSteps>& frames) {
  const auto of = [&frames](double LightMoveSteps::*field) {
    std::vector<double> v;
    for (const LightMoveSteps& f : frames) v.push_back(f.*field);
    return median(v);
  };
  return {of(&LightMoveSteps::direct), of(&LightMoveSteps::indirect), of(&LightMoveSteps::product),
          of(&LightMoveSteps::near),   of(&LightMoveSteps::whole),    of(&LightMoveSteps::probes)};
}

// Moves one light in both sessions, then holds it still until the spread
// rays give what every ray gives.
LightMoveRow move_one_light(LightingSession& every, LightingSession& spread, const Light& start,
                            const LightMoveSettings& settings) {
  LightMoveRow row{start.name, light_type_name(start.type), {}, {}, {}, -1};
  std::vector<glm::vec3> e_every, e_spread;
  // The start, in both exact: every ray traced, the spread rays given the
  // frames they take to catch up with the other lights' reset.
  every.reset_lights();
  timed_frame(every, e_every);
  spread.reset_lights();
  for (int f = 0; f <= settings.shadow_frames; ++f) timed_frame(spread, e_spread);
  std::vector<LightMoveSteps> every_frames, spread_frames;
  for (int f = 1; f <= settings.moves + settings.shadow_frames + 1; ++f) {
    const bool moving = f <= settings.moves;
    if (moving) {
      const Light l = light_at_frame(start, every.scene(), f, settings.moves);
      every.set_light(l);
      spread.set_light(l);
    }
    const LightMoveSteps a = timed_frame(every, e_every);
    const LightMoveSteps b = timed_frame(spread, e_spread);
    row.difference.push_back(relative_rms(e_spread, e_every));
    if (moving) {
      every_frames.push_back(a);
      spread_frames.push_back(b);
    } else if (row.difference.back() == 0.0) {
      row.frames_to_exact = f - settings.moves;
      break;
    }
  }
  row.every_ray = median_steps(every_frames);
  row.spread = median_steps(spread_frames);
  return row;
}

// The emitters do not move: frames after the first, with their light kept.
LightMoveRow still_area_lights(LightingSession& every, const LightMoveSettings& settings) {
  LightMoveRow row{"emissive triangles", "area", {}, {}, {}, 0};
  every.reset_lights();
  std::vector<glm::vec3> e;
  timed_frame(every, e);
  std::vector<LightMoveSteps> frames;
  for (int f = 0; f < settings.moves; ++f) frames.push_back(timed_frame(every, e));
  row.every_ray = row.spread = median_steps(frames);
  return row;
}

}  // namespace

LightMoveBench run_light_move_bench(const std::filesystem::path& bake,
                                    const LightMoveSettings& settings) {
  if (settings.moves < 1 || settings.moves > 1000)
    throw Error("light move bench", "moves must be 1..1000");
  if (settings.shadow_frames < 1 || settings.shadow_frames > 64)
    throw Error("light move bench", "shadow frames must be 1..64");
  LightingSessionSettings s;
  s.scene = settings.scene;
  s.relighter.loop = CppLoop::kFloat32;
  LightingSession every(bake, s);
  s.relighter.shadow_frames = settings.shadow_frames;
  LightingSession spread(bake, s);
  if (!every.final_gather())
    throw Error(bake.string(), "has no final gather: the light move is timed through it");
  LightMoveBench out;
  out.scene = every.description().scene_name;
  out.patches = every.bake().size();
  out.vertices = every.final_gather()->points();
  out.near_sources = every.final_gather()->near.size();
  out.probes = every.light_probes() ? every.light_probes()->size() : 0;
  out.shadow_frames = settings.shadow_frames;
  const std::vector<Light> lights = every.scene().lights;
  for (const Light& light : lights)
    out.rows.push_back(move_one_light(every, spread, light, settings));
  if (!every.area_lights().empty()) out.rows.push_back(still_area_lights(every, settings));
  return out;
}

}  // namespace bounce
