#pragma once
// Write-to-temp-then-rename, so an interrupted write never leaves a file that
// looks complete. AtomicDirectory does the same for a whole bake folder.
#include <filesystem>
#include <fstream>

#include "base/error.h"

namespace bounce {

class IoError : public Error {
 public:
  using Error::Error;
};

class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();  // removes the temp file unless commit() succeeded
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return out_; }
  // Flushes, checks for write errors (disk full) and renames into place.
  void commit();

 private:
  std::filesystem::path target_, temp_;
  std::ofstream out_;
  bool committed_ = false;
};

// A folder built under a temporary name next to its target and renamed into
// place by commit(). An existing target is replaced only if it is a previous
// bake (holds manifest.json) or empty, so a typo never deletes user data.
class AtomicDirectory {
 public:
  explicit AtomicDirectory(std::filesystem::path target);
  ~AtomicDirectory();  // removes the temp folder unless committed
  AtomicDirectory(const AtomicDirectory&) = delete;
  AtomicDirectory& operator=(const AtomicDirectory&) = delete;

  const std::filesystem::path& path() const { return temp_; }  // write files here
  const std::filesystem::path& target() const { return target_; }
  void commit();

 private:
  std::filesystem::path target_, temp_;
  bool committed_ = false;
};

}  // namespace bounce
