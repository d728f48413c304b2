#include "folder/bake_description.h"

#include <algorithm>

#include "base/error.h"

namespace bounce {

namespace {

using nlohmann::json;

glm::vec3 vec3_of(const json& a) {
  return {a.at(0).get<float>(), a.at(1).get<float>(), a.at(2).get<float>()};
}

Light light_of(const json& l, const std::filesystem::path& manifest_path) {
  Light light;
  light.name = l.at("name").get<std::string>();
  const std::string type = l.at("type").get<std::string>();
  if (const std::optional<Light::Type> t = light_type_from_name(type))
    light.type = *t;
  else
    throw Error(manifest_path.string(), "scene.lights: unknown light type '" + type + "'");
  light.position = vec3_of(l.at("position"));
  light.direction = vec3_of(l.at("direction"));
  light.color = vec3_of(l.at("color"));
  light.intensity = l.at("intensity").get<float>();
  return light;
}

int most_bounces(const json& channels) {
  int k = 0;
  for (const json& c : channels) {
    const int fixed =
        c.contains("bounces") && c.at("bounces").is_number() ? c.at("bounces").get<int>() : 0;
    const int converged = c.value("auto_bounces", 0);
    k = std::max(k, fixed > 0 ? fixed : converged);
  }
  return k;
}

}  // namespace

BakeDescription describe_bake(const json& manifest, const std::filesystem::path& manifest_path) {
  try {
    BakeDescription d;
    const json& scene = manifest.at("scene");
    d.scene_name = scene.at("name").get<std::string>();
    d.scene_path = scene.at("path").get<std::string>();
    d.scene_triangles = scene.at("triangles").get<std::size_t>();
    for (const json& l : scene.at("lights")) d.scene_lights.push_back(light_of(l, manifest_path));
    d.grid = TransferGrid::from_manifest(manifest);
    d.key = manifest.value("key", std::string());
    d.bounces = most_bounces(manifest.at("transport").at("channels"));
    return d;
  } catch (const nlohmann::json::exception& e) {
    throw Error(manifest_path.string(),
                std::string("lacks an entry or has one of the wrong type: ") + e.what());
  } catch (const Error& e) {
    // TransferGrid names only "manifest.json": name the file itself.
    if (e.where() == manifest_path.string()) throw;
    const std::string what = e.what();
    const std::size_t prefix = e.where().empty() ? 0 : e.where().size() + 2;
    throw Error(manifest_path.string(), what.substr(std::min(prefix, what.size())));
  }
}

}  // namespace bounce
