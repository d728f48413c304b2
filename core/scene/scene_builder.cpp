#include "scene/scene_builder.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <set>
#include <sstream>

#include "scene/scene_loader.h"

namespace bounce::scene_internal {

namespace {

// A triangle whose area is at most this fraction of the squared scene
// diagonal has no usable normal (and would only add noise to sampling).
constexpr double kDegenerateAreaFraction = 1e-12;
// Albedo 1 in a closed scene makes sum_h (rho F)^h diverge; keep it below.
// Balanced form factors close a room's rows to float rounding (~1e-7), and
// the multi-bounce sum amplifies a row error d into d / (1 - albedo) of the
// light: at 0.9999 that is ~0.1%, at 0.99999 ~1%. 1 itself never converges.
constexpr float kMaxAlbedo = 0.9999f;
constexpr std::uint32_t kUnmapped = std::numeric_limits<std::uint32_t>::max();

std::string format_vec(const glm::vec3& v) {
  std::ostringstream s;
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

bool same_colours(const ImportedMaterial& a, const ImportedMaterial& b) {
  return a.albedo == b.albedo && a.emission == b.emission;
}

std::string plural(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

SceneBuilder::SceneBuilder(std::string scene_file, std::map<std::string, MaterialSpec> definitions,
                           Diagnostics& diagnostics)
    : scene_file_(std::move(scene_file)),
      definitions_(std::move(definitions)),
      diagnostics_(diagnostics) {}

void SceneBuilder::add(ImportedFile file, bool two_sided, std::optional<std::string> material,
                       std::string key_path) {
  entries_.push_back({std::move(file), two_sided, std::move(material), std::move(key_path)});
}

std::uint32_t SceneBuilder::material_index(const std::string& name, const Entry& entry,
                                           const ImportedMaterial* from_file) {
  const std::string file = entry.file.path.string();
  auto it = use_index_.find(name);
  if (it == use_index_.end()) {
    Use use{name, std::nullopt, file, entry.key_path.empty() ? file : entry.key_path};
    if (from_file) use.from_file = *from_file;
    uses_.push_back(std::move(use));
    it = use_index_.emplace(name, static_cast<std::uint32_t>(uses_.size() - 1)).first;
    return it->second;
  }
  Use& use = uses_[it->second];
  if (from_file) {
    if (!use.from_file) {
      use.from_file = *from_file;
      use.file = file;
    } else if (!same_colours(*use.from_file, *from_file) && use.file != file) {
      // Materials are shared by name across files (so scene.json can override
      // them by name); a clash must not pass unnoticed.
      diagnostics_.warn(file, "material '" + name + "' is defined differently in " + use.file +
                                  "; the definition from " + use.file + " is used");
    }
  }
  return it->second;
}

Material SceneBuilder::resolve_material(const std::string& name) const {
  const Use& use = uses_[use_index_.at(name)];
  const auto def_it = definitions_.find(name);
  const MaterialSpec* def = def_it == definitions_.end() ? nullptr : &def_it->second;
  const ImportedMaterial* file = use.from_file ? &*use.from_file : nullptr;
  if (!def && !file)
    throw SceneLoader::LoadError(scene_file_, use.used_by + ".material: unknown material '" + name +
                                                  "' (define it under `materials`)");
  Material m;
  m.name = name;
  std::string albedo_from = scene_file_;
  if (def && def->albedo) {
    m.albedo = *def->albedo;
  } else if (file && file->albedo) {
    m.albedo = *file->albedo;
    albedo_from = use.file;
  } else {
    m.albedo = glm::vec3(SceneLoader::kDefaultAlbedo);
    diagnostics_.warn(file ? use.file : scene_file_,
                      "material '" + name + "' has no diffuse colour; using the default albedo " +
                          format_vec(m.albedo));
  }
  const glm::vec3 clamped = glm::clamp(m.albedo, glm::vec3(0.f), glm::vec3(kMaxAlbedo));
  if (clamped != m.albedo) {
    diagnostics_.warn(albedo_from, "material '" + name + "': albedo " + format_vec(m.albedo) +
                                       " clamped to " + format_vec(clamped) +
                                       " (albedo must lie in [0, 0.9999]; 1 or more makes the "
                                       "multi-bounce transport diverge)");
    m.albedo = clamped;
  }
  if (def && def->emission) {
    m.emission = *def->emission;
  } else if (file) {
    m.emission = file->emission;
    const glm::vec3 positive = glm::max(m.emission, glm::vec3(0.f));
    if (positive != m.emission) {
      diagnostics_.warn(use.file, "material '" + name + "': negative emission " +
                                      format_vec(m.emission) + " clamped to " +
                                      format_vec(positive));
      m.emission = positive;
    }
  }
  return m;
}

void SceneBuilder::build(Scene& scene) {
  // Material of every piece, registered in order of first use.
  std::vector<std::vector<std::uint32_t>> piece_use(entries_.size());
  for (std::size_t e = 0; e < entries_.size(); ++e) {
    const Entry& entry = entries_[e];
    for (const ImportedPiece& piece : entry.file.pieces) {
      const ImportedMaterial* from_file = piece.material < entry.file.materials.size()
                                              ? &entry.file.materials[piece.material]
                                              : nullptr;
      const std::string name = entry.material ? *entry.material
                               : from_file    ? from_file->name
                                              : entry.file.path.filename().string();
      piece_use[e].push_back(material_index(name, entry, entry.material ? nullptr : from_file));
    }
  }
  std::vector<Material> resolved;
  resolved.reserve(uses_.size());
  for (const Use& use : uses_) resolved.push_back(resolve_material(use.name));
  for (const auto& [name, def] : definitions_)
    if (!use_index_.count(name))
      diagnostics_.warn(scene_file_, def.key_path + ": no mesh uses this material; ignored");

  // The degenerate threshold is relative to the whole scene's size, so a
  // model in millimetres and one in kilometres are judged alike.
  Bounds bounds;
  for (const Entry& entry : entries_)
    for (const ImportedPiece& piece : entry.file.pieces)
      for (const glm::uvec3& t : piece.triangles)
        for (glm::length_t c = 0; c < 3; ++c) bounds.extend(piece.positions[t[c]]);
  const glm::dvec3 extent(bounds.extent());
  const double min_area = kDegenerateAreaFraction * glm::dot(extent, extent);

  std::vector<std::uint32_t> material_slot(uses_.size(), kUnmapped);
  std::size_t skipped_total = 0;
  // Exact copies of a triangle already in the scene (same corners, same
  // winding) would count the same surface twice: it would receive and send
  // twice the light. A copy with the opposite winding is the other side of a
  // thin wall and is kept.
  std::set<std::array<float, 9>> seen;
  auto canonical = [](const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::vec3 v[3] = {a, b, c};
    auto less = [](const glm::vec3& x, const glm::vec3& y) {
      return std::tie(x.x, x.y, x.z) < std::tie(y.x, y.y, y.z);
    };
    int first = 0;
    for (int k = 1; k < 3; ++k)
      if (less(v[k], v[first])) first = k;
    std::array<float, 9> key{};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) key[static_cast<std::size_t>(3 * k + d)] = v[(first + k) % 3][d];
    return key;
  };
  for (std::size_t e = 0; e < entries_.size(); ++e) {
    const Entry& entry = entries_[e];
    const std::string where = entry.file.path.string();
    const std::string label = entry.key_path.empty() ? "" : " (" + entry.key_path + ")";
    for (std::size_t p = 0; p < entry.file.pieces.size(); ++p) {
      const ImportedPiece& piece = entry.file.pieces[p];
      if (piece.non_triangles > 0)
        diagnostics_.warn(where, "mesh '" + piece.name + "'" + label + ": ignored " +
                                     plural(piece.non_triangles, "point or line primitive",
                                            "point and line primitives") +
                                     " (they have no area)");
      MeshInfo info;
      info.name = piece.name;
      info.source = where;
      info.two_sided = entry.two_sided;
      info.first_triangle = static_cast<std::uint32_t>(scene.triangles.size());

      std::vector<std::uint32_t> remap(piece.positions.size(), kUnmapped);
      std::size_t skipped = 0, duplicates = 0;
      for (const glm::uvec3& t : piece.triangles) {
        const glm::dvec3 a(piece.positions[t.x]), b(piece.positions[t.y]), c(piece.positions[t.z]);
        const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
        if (t.x == t.y || t.y == t.z || t.x == t.z || !(area > min_area)) {
          ++skipped;
          continue;
        }
        if (!seen.insert(
                     canonical(piece.positions[t.x], piece.positions[t.y], piece.positions[t.z]))
                 .second) {
          ++duplicates;
          continue;
        }
        glm::uvec3 out;
        for (glm::length_t k = 0; k < 3; ++k) {
          std::uint32_t& slot = remap[t[k]];
          if (slot == kUnmapped) {
            if (scene.positions.size() >= kUnmapped)
              throw SceneLoader::LoadError(scene_file_, "more than 2^32 - 1 vertices");
            slot = static_cast<std::uint32_t>(scene.positions.size());
            scene.positions.push_back(piece.positions[t[k]]);
          }
          out[k] = slot;
        }
        scene.triangles.push_back(out);
      }
      skipped_total += skipped + duplicates;
      if (duplicates > 0)
        diagnostics_.warn(where,
                          "mesh '" + piece.name + "'" + label + ": skipped " +
                              plural(duplicates, "duplicate triangle", "duplicate triangles") +
                              " (exact copies of triangles already in the scene, same "
                              "winding: they would count the same surface twice)");
      info.triangle_count =
          static_cast<std::uint32_t>(scene.triangles.size()) - info.first_triangle;
      if (skipped > 0)
        diagnostics_.warn(
            where, "mesh '" + piece.name + "'" + label + ": skipped " +
                       plural(skipped, "degenerate triangle", "degenerate triangles") + " of " +
                       std::to_string(piece.triangles.size()) +
                       " (repeated vertices or area <= 1e-12 x squared scene diagonal)" +
                       (info.triangle_count == 0 ? "; nothing is left of this mesh" : ""));
      if (info.triangle_count == 0) continue;

      const std::uint32_t use = piece_use[e][p];
      if (material_slot[use] == kUnmapped) {
        material_slot[use] = static_cast<std::uint32_t>(scene.materials.size());
        scene.materials.push_back(resolved[use]);
      }
      const auto mesh_index = static_cast<std::uint32_t>(scene.meshes.size());
      scene.triangle_material.insert(scene.triangle_material.end(), info.triangle_count,
                                     material_slot[use]);
      scene.triangle_mesh.insert(scene.triangle_mesh.end(), info.triangle_count, mesh_index);
      scene.meshes.push_back(std::move(info));
    }
  }
  if (scene.triangles.empty())
    throw SceneLoader::LoadError(
        scene_file_, "the scene has no geometry left" +
                         (skipped_total > 0 ? " (all " + std::to_string(skipped_total) +
                                                  " triangles are degenerate)"
                                            : std::string(" (the mesh files hold no triangles)")));
}

}  // namespace bounce::scene_internal
