#pragma once
// A fresh, empty folder for one test, removed with everything in it when the
// test ends. mkdtemp gives each one a unique name, so tests that ctest runs in
// parallel (each test is its own process) never share or delete each other's
// files, which names built from the pid or the test name alone did not
// guarantee across test binaries.
#include <stdlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace bounce::test {

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& prefix = "bounce-test") {
    std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr)
      throw std::runtime_error("cannot create a scratch folder from " + pattern);
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;  // a destructor must not throw
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace bounce::test
