#include "scene/scene_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <sstream>

#include "scene/alpha_mask.h"
#include "scene/scene_loader.h"
#include "scene/texture.h"

namespace bounce::scene_internal {

namespace {

// A triangle whose area is at most this fraction of the squared scene
// diagonal has no usable normal (and would only add noise to sampling).
constexpr double kDegenerateAreaFraction = 1e-12;
constexpr std::uint32_t kUnmapped = std::numeric_limits<std::uint32_t>::max();

std::string format_vec(const glm::vec3& v) {
  std::ostringstream s;
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

bool same_colours(const ImportedMaterial& a, const ImportedMaterial& b) {
  return a.albedo == b.albedo && a.emission == b.emission && a.texture == b.texture &&
         a.masked == b.masked && a.mask == b.mask && a.alpha_factor == b.alpha_factor &&
         a.alpha_cutoff == b.alpha_cutoff && a.emission_texture == b.emission_texture &&
         a.normal_map == b.normal_map && a.normal_scale == b.normal_scale;
}

std::string plural(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// The first three of `items`, and how many more there are: one warning line
// stays short however many it stands for (its detail lists them all).
std::string first_few(const std::vector<std::string>& items) {
  constexpr std::size_t kFirstFew = 3;
  std::string listed;
  for (std::size_t i = 0; i < std::min(kFirstFew, items.size()); ++i)
    listed += (i ? ", " : "") + items[i];
  if (items.size() > kFirstFew)
    listed += " and " + std::to_string(items.size() - kFirstFew) + " more";
  return listed;
}

// Meshes of one file with the same problem, reported as one line: the
// count, how many meshes and the first few of them; the diagnostic's detail
// (kept in the bake manifest) names them all. A big model would otherwise
// print one line per mesh and bury the warnings that matter.
class WarningGroup {
 public:
  // `one`/`many`: the thing counted ("duplicate triangle"); `why` ends the line.
  WarningGroup(std::string verb, const char* one, const char* many, std::string why)
      : verb_(std::move(verb)), one_(one), many_(many), why_(std::move(why)) {}

  void add(const std::string& mesh, std::size_t count, const std::string& note) {
    total_ += count;
    items_.push_back("'" + mesh + "' (" + std::to_string(count) + note + ")");
  }

  void emit(Diagnostics& diagnostics, const std::string& where, const std::string& label) {
    if (items_.empty()) return;
    diagnostics.warn(where,
                     verb_ + " " + plural(total_, one_, many_) + " in " +
                         plural(items_.size(), "mesh", "meshes") + label + ": " +
                         first_few(items_) + " (" + why_ + ")",
                     items_);
    items_.clear();
    total_ = 0;
  }

 private:
  std::string verb_;
  const char* one_;
  const char* many_;
  std::string why_;
  std::vector<std::string> items_;
  std::size_t total_ = 0;
};

// Whether an image holds tangent-space normals: its texels c decode to
// directions 2 c - 1 of about unit length (8-bit rounding and lossy
// compression allow some slack) pointing out of the surface (z > 0), nine
// in ten of them at least, leaning on average less than 45 degrees from the
// surface normal (a relief tilts the normal here and there, not all over),
// and it is not grey. OBJ files name height maps (grey, one value per texel;
// a light grey decodes to (1, 1, 1) / sqrt(3), 55 degrees off) and even
// colour images in the same bump slot; neither passes.
bool holds_normals(const Texture& t) {
  const std::vector<glm::vec3>& texels = t.levels.front().texels;
  std::size_t unit = 0;
  double z_sum = 0.0;
  bool grey = true;
  for (const glm::vec3& c : texels) {
    grey = grey && c.r == c.g && c.g == c.b;
    const glm::vec3 n = 2.0f * c - 1.0f;
    const float length = glm::length(n);
    if (n.z > 0.0f && length > 0.75f && length < 1.25f) {
      ++unit;
      z_sum += static_cast<double>(n.z / length);
    }
  }
  return !grey && 10 * unit >= 9 * texels.size() &&
         z_sum >= std::sqrt(0.5) * static_cast<double>(texels.size());
}

}  // namespace

SceneBuilder::SceneBuilder(std::string scene_file, std::map<std::string, MaterialSpec> definitions,
                           Diagnostics& diagnostics)
    : scene_file_(std::move(scene_file)),
      definitions_(std::move(definitions)),
      diagnostics_(diagnostics) {}

void SceneBuilder::add(ImportedFile file, bool two_sided, std::optional<std::string> material,
                       std::string key_path, float patch_density,
                       std::map<std::string, float> object_density) {
  entries_.push_back({std::move(file), two_sided, std::move(material), std::move(key_path),
                      patch_density, std::move(object_density)});
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

Material SceneBuilder::resolve_material(const std::string& name, MaterialImages images) const {
  std::shared_ptr<const Texture>& texture = images.texture;
  std::shared_ptr<const AlphaMask>& mask = images.mask;
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
  } else if (texture) {
    m.albedo = glm::vec3(1.0f);  // a texture without a colour: the texture alone
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
  if (texture) {
    m.texture_factor = m.albedo;
    m.albedo = glm::clamp(m.albedo * texture->mean, glm::vec3(0.f), glm::vec3(kMaxAlbedo));
    m.texture = std::move(texture);
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
  if (images.emission) {
    // As the colour texture: the factor stays, the flat value is the mean.
    m.emission_factor = m.emission;
    m.emission = m.emission * images.emission->mean;
    m.emission_texture = std::move(images.emission);
  }
  if (images.normal_map) {
    m.normal_map = std::move(images.normal_map);
    m.normal_scale = file->normal_scale;
  }
  if (mask && m.is_emissive()) {
    // Emitters are sampled over whole triangles (area lights, the
    // reference's light picking); a holed emitter would shine from its holes.
    diagnostics_.warn(file ? use.file : scene_file_,
                      "material '" + name + "' is emissive: its alpha mask (" +
                          (mask->is_constant() ? "constant" : mask->source.name()) +
                          ") is ignored and the surface is kept whole");
  } else if (mask) {
    m.alpha_mask = std::move(mask);
    m.alpha_factor = file->alpha_factor;
    m.alpha_cutoff = file->alpha_cutoff;
    if (m.texture && !m.alpha_mask->is_constant()) {
      // The surface is the solid part: its mean is the flat albedo.
      m.solid_texture = solid_part(*m.texture, *m.alpha_mask, m.alpha_factor, m.alpha_cutoff);
      m.albedo = glm::clamp(m.texture_factor * m.solid_texture->mean, glm::vec3(0.f),
                            glm::vec3(kMaxAlbedo));
    }
  }
  return m;
}

void SceneBuilder::build(Scene& scene) {
  // Every object given a density of its own must be in its file.
  for (const Entry& entry : entries_)
    for (const auto& [name, density] : entry.object_density) {
      std::string names;
      bool found = false;
      for (std::size_t p = 0; p < entry.file.pieces.size(); ++p) {
        found = found || entry.file.pieces[p].name == name;
        if (p < 8) names += (p > 0 ? ", '" : "'") + entry.file.pieces[p].name + "'";
      }
      if (entry.file.pieces.size() > 8)
        names += " and " + std::to_string(entry.file.pieces.size() - 8) + " more";
      if (!found)
        throw SceneLoader::LoadError(scene_file_, entry.key_path + ".object_density." + name +
                                                      ": " + entry.file.path.string() +
                                                      " holds no object named '" + name +
                                                      "' (its objects: " + names + ")");
    }
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
  // Each texture image (a file, or one embedded in a mesh file) is read once
  // per use (colour, emission, normal map), however many materials use it,
  // and the images in parallel (decoding dominates).
  enum Role { kColour, kEmission, kNormal, kRoles };
  const auto file_of = [](const ImportedMaterial& m, int role) {
    return role == kColour ? m.texture : role == kEmission ? m.emission_texture : m.normal_map;
  };
  std::vector<std::pair<ImageSource, int>> files;
  std::vector<std::array<std::size_t, kRoles>> use_file(uses_.size());
  for (std::size_t u = 0; u < uses_.size(); ++u)
    for (int role = 0; role < kRoles; ++role) {
      use_file[u][static_cast<std::size_t>(role)] = SIZE_MAX;
      if (!uses_[u].from_file || !file_of(*uses_[u].from_file, role)) continue;
      const std::pair key(*file_of(*uses_[u].from_file, role), role);
      const auto at = std::find(files.begin(), files.end(), key);
      use_file[u][static_cast<std::size_t>(role)] = static_cast<std::size_t>(at - files.begin());
      if (at == files.end()) files.push_back(key);
    }
  std::vector<std::shared_ptr<const Texture>> textures(files.size());
  std::vector<std::string> errors(files.size());
  std::vector<std::string> not_normals;  // normal map files that hold none
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t f = 0; f < static_cast<std::int64_t>(files.size()); ++f) {
    const auto i = static_cast<std::size_t>(f);
    textures[i] =
        load_texture(files[i].first, errors[i],
                     files[i].second == kNormal ? TexelKind::Direction : TexelKind::Colour);
  }
  // The materials that use image f, for its warning: an embedded image's
  // name says only which file holds it.
  const auto users = [&](std::size_t f) {
    std::string names;
    for (std::size_t u = 0; u < uses_.size(); ++u)
      if (use_file[u][static_cast<std::size_t>(files[f].second)] == f)
        names += (names.empty() ? "'" : ", '") + uses_[u].name + "'";
    return names;
  };
  for (std::size_t f = 0; f < files.size(); ++f) {
    const std::string where = files[f].first.name();
    const int role = files[f].second;
    if (!textures[f]) {
      // A glTF mask is its colour texture's alpha: the one warning says so.
      bool masks_too = false;
      for (std::size_t u = 0; u < uses_.size(); ++u)
        masks_too |= role == kColour && use_file[u][kColour] == f && uses_[u].from_file &&
                     uses_[u].from_file->masked && uses_[u].from_file->mask == files[f].first;
      diagnostics_.warn(where, "cannot read this " +
                                   std::string(role == kColour     ? "texture"
                                               : role == kEmission ? "emissive texture"
                                                                   : "normal map") +
                                   " (" + errors[f] + "); " +
                                   (role == kColour     ? "its materials use their diffuse colour"
                                    : role == kEmission ? "its materials emit their emissive "
                                                          "colour alone"
                                                        : "its materials are drawn without it") +
                                   (masks_too ? " and their surfaces are kept whole" : "") +
                                   " (used by " + users(f) + ")");
    } else if (role == kNormal && !holds_normals(*textures[f])) {
      // A height map's normals would come from its slopes, and a colour
      // image has none: neither is read, rather than misread as directions.
      not_normals.push_back(where);
      textures[f] = nullptr;
    }
  }
  if (!not_normals.empty()) {
    // One line for them all (models such as Sponza name a dozen height
    // maps), naming the first few; the detail names every file.
    diagnostics_.warn(
        not_normals.size() == 1 ? not_normals.front() : scene_file_,
        plural(not_normals.size(), "normal (bump) map holds", "normal (bump) maps hold") +
            " no tangent-space normals (RGB texels decoding to unit vectors facing "
            "out): grey height maps and colour images are not read as normal maps, "
            "their materials are drawn without them: " +
            first_few(not_normals),
        not_normals);
  }
  // Alpha masks likewise, once per file and channel rule; a glTF mask
  // without a texture is its constant factor.
  std::vector<std::pair<ImageSource, AlphaSource>> mask_files;
  std::vector<std::size_t> use_mask(uses_.size(), SIZE_MAX);
  for (std::size_t u = 0; u < uses_.size(); ++u) {
    if (!uses_[u].from_file || !uses_[u].from_file->masked || !uses_[u].from_file->mask) continue;
    const std::pair key(*uses_[u].from_file->mask, uses_[u].from_file->mask_source);
    const auto at = std::find(mask_files.begin(), mask_files.end(), key);
    use_mask[u] = static_cast<std::size_t>(at - mask_files.begin());
    if (at == mask_files.end()) mask_files.push_back(key);
  }
  std::vector<std::shared_ptr<const AlphaMask>> masks(mask_files.size());
  std::vector<std::string> mask_errors(mask_files.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t f = 0; f < static_cast<std::int64_t>(mask_files.size()); ++f) {
    const auto i = static_cast<std::size_t>(f);
    masks[i] = load_alpha_mask(mask_files[i].first, mask_files[i].second, mask_errors[i]);
  }
  for (std::size_t f = 0; f < mask_files.size(); ++f) {
    if (masks[f]) continue;
    // A mask that is an unreadable colour texture's alpha was warned about
    // with the texture.
    bool warned = false;
    for (std::size_t t = 0; t < files.size(); ++t)
      warned |= !textures[t] && files[t].second == kColour && files[t].first == mask_files[f].first;
    if (!warned)
      diagnostics_.warn(mask_files[f].first.name(),
                        "cannot read this alpha mask (" + mask_errors[f] +
                            "); its materials' surfaces are kept whole");
  }
  std::vector<Material> resolved;
  resolved.reserve(uses_.size());
  for (std::size_t u = 0; u < uses_.size(); ++u) {
    std::shared_ptr<const AlphaMask> mask;
    if (use_mask[u] != SIZE_MAX)
      mask = masks[use_mask[u]];
    else if (uses_[u].from_file && uses_[u].from_file->masked &&
             uses_[u].from_file->alpha_factor < uses_[u].from_file->alpha_cutoff)
      mask = AlphaMask::constant(1.0f);  // wholly cut away
    const auto image = [&](int role) {
      const std::size_t f = use_file[u][static_cast<std::size_t>(role)];
      return f == SIZE_MAX ? nullptr : textures[f];
    };
    resolved.push_back(resolve_material(
        uses_[u].name, {image(kColour), image(kEmission), image(kNormal), std::move(mask)}));
  }
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
  bool any_colours = false;
  for (std::size_t e = 0; e < entries_.size(); ++e) {
    const Entry& entry = entries_[e];
    const std::string where = entry.file.path.string();
    const std::string label = entry.key_path.empty() ? "" : " (" + entry.key_path + ")";
    WarningGroup lines("ignored", "point or line primitive", "point and line primitives",
                       "they have no area");
    WarningGroup degenerate("skipped", "degenerate triangle", "degenerate triangles",
                            "repeated vertices or area <= 1e-12 x squared scene diagonal");
    WarningGroup duplicate("skipped", "duplicate triangle", "duplicate triangles",
                           "exact copies of triangles already in the scene, same winding: they "
                           "would count the same surface twice");
    WarningGroup no_uvs("found no texture coordinates for", "triangle", "triangles",
                        "their material's textures are applied as their mean colours, an "
                        "alpha mask keeps them whole and a normal map is not drawn");
    for (std::size_t p = 0; p < entry.file.pieces.size(); ++p) {
      const ImportedPiece& piece = entry.file.pieces[p];
      if (piece.non_triangles > 0) lines.add(piece.name, piece.non_triangles, "");
      MeshInfo info;
      info.name = piece.name;
      info.source = where;
      info.two_sided = entry.two_sided;
      const auto named = entry.object_density.find(piece.name);
      info.patch_density =
          named != entry.object_density.end() ? named->second : entry.patch_density;
      info.first_triangle = static_cast<std::uint32_t>(scene.triangles.size());

      const bool has_uvs = piece.uvs.size() == piece.positions.size();
      const bool has_colours = piece.colours.size() == piece.positions.size();
      any_colours = any_colours || has_colours;
      const Material& mat = resolved[piece_use[e][p]];
      if ((mat.texture || mat.emission_texture || mat.normal_map ||
           (mat.alpha_mask && !mat.alpha_mask->is_constant())) &&
          !has_uvs)
        no_uvs.add(piece.name, piece.triangles.size(), "");
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
        // No coordinates: NaN, which texture lookups answer with the mean.
        const glm::vec2 none(std::numeric_limits<float>::quiet_NaN());
        scene.triangle_uv.push_back({has_uvs ? piece.uvs[t.x] : none,
                                     has_uvs ? piece.uvs[t.y] : none,
                                     has_uvs ? piece.uvs[t.z] : none});
        // No colours: white, which leaves the material's albedo as it is.
        const glm::vec3 white(1.0f);
        scene.triangle_colour.push_back({has_colours ? piece.colours[t.x] : white,
                                         has_colours ? piece.colours[t.y] : white,
                                         has_colours ? piece.colours[t.z] : white});
      }
      skipped_total += skipped + duplicates;
      if (duplicates > 0) duplicate.add(piece.name, duplicates, "");
      info.triangle_count =
          static_cast<std::uint32_t>(scene.triangles.size()) - info.first_triangle;
      if (skipped > 0)
        degenerate.add(piece.name, skipped,
                       " of " + std::to_string(piece.triangles.size()) +
                           (info.triangle_count == 0 ? ", nothing is left of this mesh" : ""));
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
    for (WarningGroup* group : {&lines, &degenerate, &duplicate, &no_uvs})
      group->emit(diagnostics_, where, label);
  }
  if (std::none_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) {
        return m.texture || m.alpha_mask || m.emission_texture || m.normal_map;
      }))
    scene.triangle_uv.clear();
  if (!any_colours) scene.triangle_colour.clear();
  if (scene.triangles.empty())
    throw SceneLoader::LoadError(
        scene_file_, "the scene has no geometry left" +
                         (skipped_total > 0 ? " (all " + std::to_string(skipped_total) +
                                                  " triangles are degenerate)"
                                            : std::string(" (the mesh files hold no triangles)")));
}

}  // namespace bounce::scene_internal
