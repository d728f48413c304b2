#include <cstdio>
#include <iostream>
#include <memory>

#include <nlohmann/json.hpp>

#include "bounce/scene.h"
#include "commands.h"

namespace bounce::cli {

namespace {

struct InfoOptions {
  std::string scene;
  bool json = false;
};

void run_info(const InfoOptions& opt) {
  Diagnostics diagnostics;
  const Scene scene = SceneLoader(diagnostics).load(opt.scene);
  const Bounds b = scene.bounds();
  std::size_t emissive = 0, textured = 0;
  double area = 0.0;
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    area += scene.triangle_area(t);
    if (scene.material_of(t).is_emissive()) ++emissive;
    if (scene.textured(t) || scene.emission_textured(t)) ++textured;
  }
  if (opt.json) {
    nlohmann::json j;
    j["name"] = scene.name;
    j["path"] = scene.path;
    j["triangles"] = scene.triangle_count();
    j["vertices"] = scene.positions.size();
    j["surface_area"] = area;
    j["emissive_triangles"] = emissive;
    j["textured_triangles"] = textured;
    j["vertex_colours"] = scene.has_vertex_colours();
    j["bounds"] = {{"min", {b.lo.x, b.lo.y, b.lo.z}}, {"max", {b.hi.x, b.hi.y, b.hi.z}}};
    for (const Material& m : scene.materials)
      j["materials"].push_back({{"name", m.name},
                                {"albedo", {m.albedo.r, m.albedo.g, m.albedo.b}},
                                {"emission", {m.emission.r, m.emission.g, m.emission.b}}});
    for (const MeshInfo& m : scene.meshes)
      j["meshes"].push_back({{"name", m.name},
                             {"source", m.source},
                             {"triangles", m.triangle_count},
                             {"two_sided", m.two_sided}});
    j["lights"] = nlohmann::json::array();
    for (const Light& l : scene.lights)
      j["lights"].push_back({{"name", l.name},
                             {"type", light_type_name(l.type)},
                             {"position", {l.position.x, l.position.y, l.position.z}}});
    j["warnings"] = nlohmann::json::array();
    for (const Diagnostic& d : diagnostics.warnings())
      j["warnings"].push_back(d.where + ": " + d.message);
    std::cout << j.dump(2) << '\n';
    return;
  }
  std::printf("Scene '%s' (%s)\n", scene.name.c_str(), scene.path.c_str());
  std::printf("  triangles   %zu (%zu emissive), %zu vertices, surface area %.4g\n",
              scene.triangle_count(), emissive, scene.positions.size(), area);
  // Where the samples' albedo comes from beyond the materials' flat colours:
  // what the bake's "texture" step looks up.
  std::printf("  surface     %zu of %zu triangles textured, %s\n", textured, scene.triangle_count(),
              scene.has_vertex_colours() ? "vertex colours" : "no vertex colours");
  std::printf("  bounds      (%.4g, %.4g, %.4g) - (%.4g, %.4g, %.4g)\n", b.lo.x, b.lo.y, b.lo.z,
              b.hi.x, b.hi.y, b.hi.z);
  std::printf("  meshes      %zu\n", scene.meshes.size());
  for (const MeshInfo& m : scene.meshes)
    std::printf("    %-20s %8u triangles%s  (%s)\n", m.name.c_str(), m.triangle_count,
                m.two_sided ? ", two-sided" : "", m.source.c_str());
  std::printf("  materials   %zu\n", scene.materials.size());
  for (const Material& m : scene.materials)
    std::printf("    %-20s albedo (%.3f, %.3f, %.3f)  emission (%.3g, %.3g, %.3g)\n",
                m.name.c_str(), m.albedo.r, m.albedo.g, m.albedo.b, m.emission.r, m.emission.g,
                m.emission.b);
  std::printf("  lights      %zu\n", scene.lights.size());
  for (const Light& l : scene.lights)
    std::printf("    %-20s %-11s at (%.3g, %.3g, %.3g)\n", l.name.c_str(), light_type_name(l.type),
                l.position.x, l.position.y, l.position.z);
  const auto warnings = diagnostics.warnings();
  std::printf("  warnings    %zu\n", warnings.size());
  for (const Diagnostic& d : warnings)
    std::printf("    - %s: %s\n", d.where.c_str(), d.message.c_str());
}

}  // namespace

void register_info(CLI::App& app) {
  auto opt = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info", "Show what a scene holds: triangles, meshes, materials, lights, bounds, warnings");
  cmd->add_option("scene", opt->scene, "A scene folder, a scene.json, or a mesh file")->required();
  cmd->add_flag("--json", opt->json, "Print as JSON on stdout");
  cmd->callback([opt]() { run_info(*opt); });
}

}  // namespace bounce::cli
