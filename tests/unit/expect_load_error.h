#pragma once
// For tests of the scene loader's refusals: loading `file` must end in one
// SceneLoader::LoadError that names the file and whose message holds
// `reason`.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "base/diagnostics.h"
#include "scene/scene_loader.h"

namespace bounce::test {

inline void expect_load_error(const std::filesystem::path& file, const std::string& reason) {
  Diagnostics diagnostics;
  try {
    (void)SceneLoader(diagnostics).load(file);
    ADD_FAILURE() << "loaded " << file << " without an error";
  } catch (const SceneLoader::LoadError& e) {
    EXPECT_EQ(e.where(), file.string());
    EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
  }
}

}  // namespace bounce::test
