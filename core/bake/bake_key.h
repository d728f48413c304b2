#pragma once
// The content key of a bake: what a bake folder's results depend on, hashed,
// so a bake of the same inputs already on disk is reused instead of baked
// again (`bounce bake --out DIR` on an up-to-date DIR, the studio's bake
// cache). It covers the bytes of every file the scene was read from
// (scene/scene_files.h: scene.json, mesh files with their MTL libraries and
// buffers, textures), the meshes' patch densities as the bake uses them (the
// studio's mesh list overrides scene.json's), every setting's canonical text
// after the scene's defaults, and the bake format's version. It does not
// cover file names or paths: a scene folder copied elsewhere keeps its key.
// Written to manifest.json as "key" (docs/bake-format.md).
#include <filesystem>
#include <optional>
#include <string>

#include "scene/scene.h"
#include "settings/bake_settings.h"

namespace bounce {

// The scene's part of the key: the bytes of its files as they are now, 16
// hex digits (64-bit FNV-1a, reference/reference_cache.h's ContentHash).
// nullopt for a scene not read from files (Scene::path empty) or when one of
// its files cannot be read (moved since it was loaded): such a bake gets no
// key and is never reused. Hash it when the scene is loaded: a file edited
// later must not lend its key to a bake of the scene as loaded before.
std::optional<std::string> scene_content_hash(const Scene& scene);

// The key of a bake of `scene` (read from files that hashed to `content`)
// with `settings`: 16 hex digits.
std::string bake_key(const std::string& content, const Scene& scene, const BakeSettings& settings);

// Both at once, the files hashed now.
std::optional<std::string> bake_key(const Scene& scene, const BakeSettings& settings);

// The key in `dir`'s manifest.json when `dir` holds a complete bake that
// the bake reader reads without error; nullopt when there is no bake there.
// `why` (when not null) says what is wrong with a folder that holds
// something but not a usable bake (one line naming the file), empty when
// there is no folder or manifest at all. Never throws for a bad folder.
std::optional<std::string> stored_bake_key(const std::filesystem::path& dir,
                                           std::string* why = nullptr);

}  // namespace bounce
