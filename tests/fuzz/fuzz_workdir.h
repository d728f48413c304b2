#pragma once
// A private temporary folder for one fuzzing process: the scene loader and
// Assimp read files by path (mesh import picks the format by extension), so
// each input is written to a file here and loaded the way the CLI loads it.
#include <stdlib.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace bounce::fuzz {

class WorkDir {
 public:
  WorkDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "bounce-fuzz-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) std::abort();
    path_ = pattern;
  }
  ~WorkDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  WorkDir(const WorkDir&) = delete;
  WorkDir& operator=(const WorkDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

  // Writes `size` bytes to <folder>/<name>, replacing what was there.
  std::filesystem::path write(const std::string& name, const std::uint8_t* data,
                              std::size_t size) const {
    const std::filesystem::path file = path_ / name;
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) std::abort();  // the fuzzer's own temp folder must be writable
    return file;
  }

 private:
  std::filesystem::path path_;
};

// One per process; removed when libFuzzer exits normally.
inline WorkDir& work_dir() {
  static WorkDir dir;
  return dir;
}

}  // namespace bounce::fuzz
