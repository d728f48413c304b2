#include "scene/mesh_import.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>

#include <assimp/GltfMaterial.h>
#include <assimp/ObjMaterial.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/texture.h>
#include <assimp/Importer.hpp>

#include "scene/gltf_check.h"
#include "scene/mtl_scan.h"
#include "scene/ply_check.h"
#include "scene/scene_loader.h"
#include "scene/texture.h"

namespace bounce::scene_internal {

namespace {

// Triangulate polygons and merge the per-corner copies Assimp makes for OBJ.
// Deliberately not FindDegenerates/FindInvalidData: they drop or alter
// geometry without saying so; the builder reports degenerate triangles instead.
// Applied in two steps (see FileImporter::run): validation while reading, the
// rest after restate_primitive_types.
constexpr unsigned kReadFlags = aiProcess_ValidateDataStructure;
constexpr unsigned kPostProcessFlags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices;

// Sets each mesh's primitive-type flags from its faces, refusing faces with
// no index. Assimp 5.2's PLY reader turns a corrupt face list into index-less
// faces in a mesh flagged as holding polygons; ValidateDataStructure lets
// that through and Triangulate then fails an ai_assert that aborts the whole
// process (found by fuzz_mesh_ply). Flags that match the faces are what
// Triangulate assumes.
void restate_primitive_types(aiScene& scene, const std::string& where) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    aiMesh& mesh = *scene.mMeshes[m];
    unsigned types = 0;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const unsigned n = mesh.mFaces[f].mNumIndices;
      if (n == 0)
        throw SceneLoader::LoadError(where, "corrupt file: face " + std::to_string(f) +
                                                " of mesh " + std::to_string(m) +
                                                " has no vertex indices");
      types |= n == 1   ? aiPrimitiveType_POINT
               : n == 2 ? aiPrimitiveType_LINE
               : n == 3 ? aiPrimitiveType_TRIANGLE
                        : aiPrimitiveType_POLYGON;
    }
    mesh.mPrimitiveTypes = types;
  }
}

// Assimp's OBJ importer puts geometry outside any `o`/`g` into this object.
constexpr const char* kObjDefaultObject = "defaultobject";

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

glm::dmat4 to_glm(const aiMatrix4x4& a) {
  glm::dmat4 m;
  // aiMatrix4x4 is row-major (a[row][col]); glm indexes m[col][row].
  for (unsigned row = 0; row < 4; ++row)
    for (unsigned col = 0; col < 4; ++col)
      m[static_cast<glm::length_t>(col)][static_cast<glm::length_t>(row)] =
          static_cast<double>(a[row][col]);
  return m;
}

std::string format_vec(const glm::vec3& v) {
  std::ostringstream s;
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

class FileImporter {
 public:
  FileImporter(const std::filesystem::path& file, const glm::dmat4& transform,
               Diagnostics& diagnostics)
      : file_(file), where_(file.string()), transform_(transform), diagnostics_(diagnostics) {}

  ImportedFile run(const std::string& name) {
    // Assimp crashes on some truncated PLY files instead of failing; refuse
    // them first (by content too: Assimp picks a reader by signature when
    // the extension is unknown).
    if (lower(file_.extension().string()) == ".ply" || looks_like_ply(file_))
      check_ply_structure(file_);
    // Assimp asks for tens of gigabytes on a glTF primitive without
    // vertices and crashes on an image media type without a '/'.
    if (looks_like_gltf(file_)) check_gltf_structure(file_);
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(where_, kReadFlags);
    if (!scene)
      throw SceneLoader::LoadError(
          where_, std::string("Assimp cannot read this file: ") + importer.GetErrorString());
    if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode)
      throw SceneLoader::LoadError(where_,
                                   "Assimp read this file only partially (scene incomplete); "
                                   "it holds no usable meshes");
    // The importer owns a non-const scene and hands out a const pointer;
    // ApplyPostProcessing works on that same scene.
    restate_primitive_types(const_cast<aiScene&>(*scene), where_);
    scene = importer.ApplyPostProcessing(kPostProcessFlags);
    if (!scene)
      throw SceneLoader::LoadError(
          where_, std::string("Assimp cannot process this file: ") + importer.GetErrorString());
    scene_ = scene;
    out_.path = file_;
    read_materials();
    walk(scene->mRootNode, glm::dmat4(1.0));
    name_pieces(name);
    check_vertices();
    report_ignored_attributes();
    return std::move(out_);
  }

 private:
  void read_materials() {
    const bool is_obj = lower(file_.extension().string()) == ".obj";
    MtlScan scan;
    if (is_obj) {
      scan = scan_obj_materials(file_);
      for (const std::string& lib : scan.missing_libraries)
        diagnostics_.warn(where_, "material library '" + lib +
                                      "' not found; its materials get the default albedo");
    }
    for (unsigned i = 0; i < scene_->mNumMaterials; ++i) {
      const aiMaterial& m = *scene_->mMaterials[i];
      ImportedMaterial mat;
      aiString ai_name;
      if (m.Get(AI_MATKEY_NAME, ai_name) == AI_SUCCESS) mat.name = ai_name.C_Str();
      // Loaders invent unnamed or "DefaultMaterial" materials (with made-up
      // colours) when a file has none; treat those as stating no colour.
      const bool invented = mat.name.empty() || mat.name == AI_DEFAULT_MATERIAL_NAME;
      if (mat.name.empty()) mat.name = file_.filename().string() + "#" + std::to_string(i);

      aiColor3D diffuse;
      const bool has_diffuse = m.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) == AI_SUCCESS;
      const bool stated = is_obj ? scan.with_diffuse.count(mat.name) > 0 : !invented;
      if (has_diffuse && stated) mat.albedo = glm::vec3(diffuse.r, diffuse.g, diffuse.b);

      aiColor3D emissive(0.f, 0.f, 0.f);
      if (m.Get(AI_MATKEY_COLOR_EMISSIVE, emissive) == AI_SUCCESS)
        mat.emission = glm::vec3(emissive.r, emissive.g, emissive.b);
      float strength = 1.f;  // glTF KHR_materials_emissive_strength
      if (m.Get(AI_MATKEY_EMISSIVE_INTENSITY, strength) == AI_SUCCESS) mat.emission *= strength;

      read_texture(m, mat);
      read_alpha_mask(m, mat);
      read_emission_texture(m, mat, is_obj && scan.with_emissive.count(mat.name) == 0);
      read_normal_map(m, mat);

      if (mat.albedo && !finite(*mat.albedo))
        throw SceneLoader::LoadError(
            where_,
            "material '" + mat.name + "': diffuse colour is not finite " + format_vec(*mat.albedo));
      if (!finite(mat.emission))
        throw SceneLoader::LoadError(where_, "material '" + mat.name +
                                                 "': emissive colour is not finite " +
                                                 format_vec(mat.emission));
      out_.materials.push_back(std::move(mat));
    }
  }

  static constexpr const char* kKdInstead = "; the material's diffuse colour is used instead";

  // glTF's base colour texture, else the diffuse one (OBJ map_Kd); the
  // factor is the diffuse colour read above either way.
  void read_texture(const aiMaterial& m, ImportedMaterial& mat) {
    aiString name;
    if (m.GetTexture(aiTextureType_BASE_COLOR, 0, &name) != AI_SUCCESS &&
        m.GetTexture(aiTextureType_DIFFUSE, 0, &name) != AI_SUCCESS)
      return;
    mat.texture_name = name.C_Str();
    if (mat.texture_name.empty()) return;
    std::string missing;
    mat.texture = locate_image(mat.texture_name, "texture", missing);
    if (!mat.texture)
      missing_textures_.emplace_back(out_.materials.size(),
                                     "material '" + mat.name + "': " + missing + kKdInstead);
  }

  // OBJ map_d (Assimp's opacity texture), cut at 0.5; glTF alphaMode MASK,
  // cut at its alphaCutoff (0.5 unless stated). BLEND and OPAQUE are solid.
  void read_alpha_mask(const aiMaterial& m, ImportedMaterial& mat) {
    aiString mode;
    if (m.Get(AI_MATKEY_GLTF_ALPHAMODE, mode) == AI_SUCCESS) {
      if (std::string(mode.C_Str()) != "MASK") return;
      mat.masked = true;
      mat.mask_source = AlphaSource::AlphaOnly;
      aiColor4D base(1.f, 1.f, 1.f, 1.f);
      if (m.Get(AI_MATKEY_COLOR_DIFFUSE, base) == AI_SUCCESS) mat.alpha_factor = base.a;
      if (!std::isfinite(mat.alpha_factor) || mat.alpha_factor < 0.f || mat.alpha_factor > 1.f) {
        diagnostics_.warn(where_, "material '" + mat.name + "': baseColorFactor alpha " +
                                      std::to_string(mat.alpha_factor) +
                                      " is not in [0, 1]; 1 is used");
        mat.alpha_factor = 1.f;
      }
      float cutoff = 0.5f;
      if (m.Get(AI_MATKEY_GLTF_ALPHACUTOFF, cutoff) == AI_SUCCESS) {
        if (std::isfinite(cutoff) && cutoff >= 0.f && cutoff <= 1.f)
          mat.alpha_cutoff = cutoff;
        else
          diagnostics_.warn(where_, "material '" + mat.name + "': alphaCutoff " +
                                        std::to_string(cutoff) +
                                        " is not a number in [0, 1]; 0.5 is used");
      }
      // The mask is the base colour texture's alpha: found (or warned
      // about) by read_texture.
      if (mat.texture)
        mat.mask = mat.texture;
      else if (!mat.texture_name.empty()) {
        mat.masked = false;
        for (auto& [material, message] : missing_textures_)
          if (material == out_.materials.size())
            message += "; its alpha mask is that texture's alpha: the surface is kept whole";
      }
      return;
    }
    aiString name;
    if (m.GetTexture(aiTextureType_OPACITY, 0, &name) != AI_SUCCESS) return;
    const std::string file = name.C_Str();
    if (file.empty()) return;
    mat.mask_source = AlphaSource::AlphaOrGrey;
    std::string missing;
    mat.mask = locate_image(file, "alpha mask", missing);
    if (!mat.mask) {
      missing_textures_.emplace_back(
          out_.materials.size(),
          "material '" + mat.name + "': " + missing + "; the surface is kept whole");
      return;
    }
    mat.masked = true;
  }

  // The image of texture slot `type`, located as the colour texture's;
  // nullopt when the material names none, and with a warning (one per
  // material in use, ending in `fallback`) when it cannot be found.
  std::optional<ImageSource> find_texture(const aiMaterial& m, aiTextureType type,
                                          const ImportedMaterial& mat, const char* what,
                                          const char* fallback) {
    aiString name;
    if (m.GetTexture(type, 0, &name) != AI_SUCCESS) return std::nullopt;
    const std::string file = name.C_Str();
    if (file.empty()) return std::nullopt;
    std::string missing;
    std::optional<ImageSource> found = locate_image(file, what, missing);
    if (!found)
      missing_textures_.emplace_back(out_.materials.size(),
                                     "material '" + mat.name + "': " + missing + "; " + fallback);
    return found;
  }

  // Where the image a material names (`what`: "texture", "normal map", ...)
  // is: "*N" is the file's embedded image N (glTF's bufferView and data-URI
  // images); any other name a file beside the mesh file (see
  // resolve_texture_path), else an image the file embeds under that name
  // (FBX embeds its media so). nullopt with `missing` saying why when none.
  std::optional<ImageSource> locate_image(const std::string& name, const std::string& what,
                                          std::string& missing) {
    if (name.front() == '*') {
      const auto [texture, index] = scene_->GetEmbeddedTextureAndIndex(name.c_str());
      if (texture) return ImageSource(embedded_image(static_cast<unsigned>(index)));
      missing = what + " '" + name + "' names an image the file does not embed (it embeds " +
                std::to_string(scene_->mNumTextures) +
                (scene_->mNumTextures == 1 ? " image)" : " images)");
      return std::nullopt;
    }
    if (std::optional<std::filesystem::path> file = resolve_texture_path(file_.parent_path(), name))
      return ImageSource(std::move(*file));
    const auto [texture, index] = scene_->GetEmbeddedTextureAndIndex(name.c_str());
    if (texture) return ImageSource(embedded_image(static_cast<unsigned>(index)));
    missing = what + " file '" + (file_.parent_path() / name).string() + "' not found";
    return std::nullopt;
  }

  // Embedded image `index`, copied out of Assimp's scene once however many
  // materials use it (the importer frees the scene when the file is read).
  std::shared_ptr<const EmbeddedImage> embedded_image(unsigned index) {
    std::shared_ptr<const EmbeddedImage>& cached = embedded_[index];
    if (cached) return cached;
    const aiTexture& t = *scene_->mTextures[index];
    auto image = std::make_shared<EmbeddedImage>();
    image->name = where_ + "#texture " + std::to_string(index);
    if (t.pcData == nullptr) {
      // Left empty: decoding it fails with a warning, as a corrupt one does.
    } else if (t.mHeight == 0) {
      // mWidth bytes of an image file; the hint is its extension.
      const char* hint = t.achFormatHint;
      image->format_hint = std::string(hint, std::find(hint, hint + HINTMAXTEXTURELEN, '\0'));
      const auto* bytes = reinterpret_cast<const std::uint8_t*>(t.pcData);
      image->bytes.assign(bytes, bytes + t.mWidth);
    } else {
      // mWidth x mHeight texels (aiTexel: b, g, r, a), as RGBA.
      image->raw_width = static_cast<int>(t.mWidth);
      image->raw_height = static_cast<int>(t.mHeight);
      const std::size_t texels = static_cast<std::size_t>(t.mWidth) * t.mHeight;
      image->bytes.reserve(texels * 4);
      for (std::size_t i = 0; i < texels; ++i)
        image->bytes.insert(image->bytes.end(),
                            {t.pcData[i].r, t.pcData[i].g, t.pcData[i].b, t.pcData[i].a});
    }
    cached = std::move(image);
    return cached;
  }

  // OBJ map_Ke, glTF emissiveTexture; the factor is the emissive colour read
  // above. An OBJ material with map_Ke and no Ke line takes factor 1, as
  // map_Kd without Kd does (Assimp would give it 0: no light at all). glTF
  // keeps its emissiveFactor, 0 when not stated, as its specification says.
  void read_emission_texture(const aiMaterial& m, ImportedMaterial& mat, bool factor_unstated) {
    mat.emission_texture = find_texture(m, aiTextureType_EMISSIVE, mat, "emissive texture",
                                        "the emission is the emissive colour alone");
    if (mat.emission_texture && factor_unstated) mat.emission = glm::vec3(1.0f);
  }

  // glTF normalTexture and OBJ norm (Assimp's normal slot), else OBJ
  // map_bump / bump (Assimp's height slot), with the scale glTF or the -bm
  // option gives.
  void read_normal_map(const aiMaterial& m, ImportedMaterial& mat) {
    constexpr const char* kFlat = "the surface is drawn without it";
    aiTextureType type = aiTextureType_NORMALS;
    mat.normal_map = find_texture(m, type, mat, "normal map", kFlat);
    aiString name;
    if (!mat.normal_map && m.GetTexture(type, 0, &name) != AI_SUCCESS) {
      type = aiTextureType_HEIGHT;
      mat.normal_map = find_texture(m, type, mat, "bump map", kFlat);
    }
    if (!mat.normal_map) return;
    float scale = 1.0f;
    if (m.Get(AI_MATKEY_GLTF_TEXTURE_SCALE(type, 0), scale) == AI_SUCCESS ||
        m.Get(AI_MATKEY_OBJ_BUMPMULT(type, 0), scale) == AI_SUCCESS) {
      if (std::isfinite(scale))
        mat.normal_scale = scale;
      else
        diagnostics_.warn(where_, "material '" + mat.name + "': normal map scale " +
                                      std::to_string(scale) + " is not finite; 1 is used");
    }
  }

  void walk(const aiNode* node, const glm::dmat4& parent) {
    const glm::dmat4 node_global = parent * to_glm(node->mTransformation);
    const glm::dmat4 full = transform_ * node_global;
    // A mirroring transform turns counter-clockwise into clockwise; swap two
    // corners so the front side stays the side the file meant.
    const bool mirror = glm::determinant(glm::dmat3(full)) < 0.0;
    std::string node_name = node->mName.C_Str();
    if (node_name.empty() || node_name == kObjDefaultObject) node_name = file_.stem().string();

    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const aiMesh& mesh = *scene_->mMeshes[node->mMeshes[k]];
      ImportedPiece piece;
      piece.material = mesh.mMaterialIndex;
      piece.name = node_name;
      if (node->mNumMeshes > 1 && mesh.mMaterialIndex < out_.materials.size())
        piece.name += "/" + out_.materials[mesh.mMaterialIndex].name;
      piece.positions.reserve(mesh.mNumVertices);
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiVector3D& p = mesh.mVertices[v];
        const glm::dvec4 q = full * glm::dvec4(p.x, p.y, p.z, 1.0);
        piece.positions.emplace_back(static_cast<float>(q.x), static_cast<float>(q.y),
                                     static_cast<float>(q.z));
      }
      if (mesh.HasTextureCoords(0)) {
        piece.uvs.reserve(mesh.mNumVertices);
        for (unsigned v = 0; v < mesh.mNumVertices; ++v)
          piece.uvs.emplace_back(mesh.mTextureCoords[0][v].x, mesh.mTextureCoords[0][v].y);
      }
      piece.triangles.reserve(mesh.mNumFaces);
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices != 3) {
          ++piece.non_triangles;
          continue;
        }
        const unsigned* i = face.mIndices;
        piece.triangles.emplace_back(i[0], mirror ? i[2] : i[1], mirror ? i[1] : i[2]);
      }
      if (mesh.HasVertexColors(0)) read_colours(mesh, piece);
      out_.pieces.push_back(std::move(piece));
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) walk(node->mChildren[c], node_global);
  }

  // The first set of vertex colours, decoded to linear (see
  // import_mesh_file): glTF's are linear already, other formats' are sRGB.
  void read_colours(const aiMesh& mesh, ImportedPiece& piece) {
    const std::string ext = lower(file_.extension().string());
    const bool linear = ext == ".gltf" || ext == ".glb";
    std::size_t clamped = 0;
    piece.colours.reserve(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiColor4D& c = mesh.mColors[0][v];
      glm::vec3 colour(c.r, c.g, c.b);
      if (!finite(colour))
        throw SceneLoader::LoadError(where_, "mesh '" + piece.name + "': vertex " +
                                                 std::to_string(v) + " has a non-finite colour " +
                                                 format_vec(colour));
      const glm::vec3 in_range = glm::clamp(colour, glm::vec3(0.0f), glm::vec3(1.0f));
      if (in_range != colour) ++clamped;
      if (!linear)
        for (glm::length_t k = 0; k < 3; ++k) colour[k] = srgb_to_linear(in_range[k]);
      else
        colour = in_range;
      piece.colours.push_back(colour);
    }
    if (clamped > 0)
      out_of_range_colours_.push_back("'" + piece.name + "' (" + std::to_string(clamped) + ")");
  }

  void name_pieces(const std::string& name) {
    if (name.empty()) return;
    if (out_.pieces.size() == 1) {
      out_.pieces.front().name = name;
      return;
    }
    for (ImportedPiece& piece : out_.pieces) piece.name = name + "/" + piece.name;
  }

  // Only vertices that triangles use: scanned point clouds often carry NaN
  // placeholders for unused vertices, which do no harm.
  void check_vertices() const {
    for (const ImportedPiece& piece : out_.pieces) {
      std::vector<bool> bad(piece.positions.size(), false);
      std::size_t count = 0;
      for (const glm::uvec3& t : piece.triangles)
        for (glm::length_t c = 0; c < 3; ++c)
          if (!bad[t[c]] && !finite(piece.positions[t[c]])) {
            bad[t[c]] = true;
            ++count;
          }
      if (count == 0) continue;
      const std::size_t first =
          static_cast<std::size_t>(std::find(bad.begin(), bad.end(), true) - bad.begin());
      throw SceneLoader::LoadError(
          where_, "mesh '" + piece.name + "': " + std::to_string(count) +
                      (count == 1 ? " vertex has" : " vertices have") +
                      " non-finite coordinates (NaN or Inf) after the transform; the first is "
                      "vertex " +
                      std::to_string(first) + " " + format_vec(piece.positions[first]) + " of " +
                      std::to_string(piece.positions.size()));
    }
  }

  // Say what the file had that the albedo cannot follow as given: missing
  // textures of materials in use (the albedo falls back to the material's
  // colour) and vertex colours outside [0, 1].
  void report_ignored_attributes() {
    std::vector<bool> used(out_.materials.size(), false);
    for (const ImportedPiece& piece : out_.pieces)
      if (piece.material < used.size()) used[piece.material] = true;
    for (const auto& [material, message] : missing_textures_)
      if (used[material]) diagnostics_.warn(where_, message);
    if (!out_of_range_colours_.empty()) {
      // One line naming the first few meshes; the detail lists them all.
      constexpr std::size_t kFirstFew = 3;
      const std::size_t n = out_of_range_colours_.size();
      std::string names;
      for (std::size_t i = 0; i < std::min(n, kFirstFew); ++i)
        names += (i ? ", " : "") + out_of_range_colours_[i];
      if (n > kFirstFew) names += " and " + std::to_string(n - kFirstFew) + " more";
      diagnostics_.warn(where_,
                        "vertex colours outside [0, 1] clamped in " + std::to_string(n) +
                            (n == 1 ? " mesh" : " meshes") + ": " + names +
                            " (a colour multiplies the albedo, which must stay below 1)",
                        out_of_range_colours_);
    }
  }

  const std::filesystem::path& file_;
  std::string where_;
  glm::dmat4 transform_;
  Diagnostics& diagnostics_;
  const aiScene* scene_ = nullptr;
  ImportedFile out_;
  std::vector<std::string> out_of_range_colours_;  // meshes, with how many vertices
  std::vector<std::pair<std::size_t, std::string>> missing_textures_;  // material, message
  std::map<unsigned, std::shared_ptr<const EmbeddedImage>> embedded_;  // by index in the file
};

}  // namespace

ImportedFile import_mesh_file(const std::filesystem::path& file, const glm::dmat4& transform,
                              const std::string& name, Diagnostics& diagnostics) {
  return FileImporter(file, transform, diagnostics).run(name);
}

}  // namespace bounce::scene_internal
