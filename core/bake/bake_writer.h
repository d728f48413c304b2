#pragma once
// Writes a bake folder (docs/bake-format.md): the data files first, the
// manifest last, all inside a temporary folder renamed into place at the end,
// so a failed or cancelled bake never leaves a folder that looks complete.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "bake/bake.h"
#include "bake/bake_manifest.h"
#include "folder/bake_format.h"

namespace bounce {

// Returns the manifest as written (with "files").
nlohmann::json write_bake(const std::filesystem::path& out_dir, const Scene& scene,
                          const BakeResult& result, const Diagnostics& diagnostics);

}  // namespace bounce
