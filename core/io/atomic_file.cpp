#include "io/atomic_file.h"

#include <unistd.h>

#include <atomic>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

namespace bounce {

namespace fs = std::filesystem;

namespace {

fs::path temp_name(const fs::path& target, const char* tag) {
  static std::atomic<unsigned> counter{0};
  return target.parent_path() / ("." + target.filename().string() + "." + tag + "-" +
                                 std::to_string(::getpid()) + "-" + std::to_string(counter++));
}

}  // namespace

AtomicFile::AtomicFile(fs::path target)
    : target_(std::move(target)), temp_(temp_name(target_, "tmp")) {
  out_.open(temp_, std::ios::binary | std::ios::trunc);
  if (!out_)
    throw IoError(target_.string(), std::string("cannot create file: ") + std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void AtomicFile::commit() {
  out_.flush();
  const bool ok = static_cast<bool>(out_);
  out_.close();
  if (!ok || out_.fail()) throw IoError(target_.string(), "write failed (disk full or I/O error)");
  std::error_code ec;
  fs::rename(temp_, target_, ec);
  if (ec) throw IoError(target_.string(), "cannot move into place: " + ec.message());
  committed_ = true;
}

AtomicDirectory::AtomicDirectory(fs::path target) : target_(std::move(target)) {
  if (target_.filename().empty()) target_ = target_.parent_path();
  std::error_code ec;
  const fs::path parent = target_.has_parent_path() ? target_.parent_path() : fs::path(".");
  fs::create_directories(parent, ec);
  if (ec) throw IoError(parent.string(), "cannot create folder: " + ec.message());
  // error_code overloads throughout: a folder we may not read or search must
  // become an IoError naming it, not a std::filesystem_error.
  const fs::file_status status = fs::status(target_, ec);
  if (ec && status.type() != fs::file_type::not_found)
    throw IoError(target_.string(), "cannot inspect: " + ec.message());
  if (fs::exists(status) && !fs::is_directory(status))
    throw IoError(target_.string(), "exists and is not a folder");
  if (fs::is_directory(status)) {
    const bool empty = fs::is_empty(target_, ec);
    if (ec) throw IoError(target_.string(), "cannot read folder: " + ec.message());
    const bool is_bake = fs::exists(target_ / "manifest.json", ec);
    if (!empty && !is_bake)
      throw IoError(target_.string(),
                    "exists, is not empty and is not a bake folder (no manifest.json); refusing "
                    "to replace it");
  }
  temp_ = temp_name(target_, "partial");
  fs::create_directory(temp_, ec);
  // Named after the target: the temporary name means nothing to the user.
  if (ec)
    throw IoError(target_.string(), "cannot create the folder's temporary sibling " +
                                        temp_.filename().string() + " in " + parent.string() +
                                        ": " + ec.message());
}

AtomicDirectory::~AtomicDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(temp_, ec);
  }
}

void AtomicDirectory::commit() {
  std::error_code ec;
  fs::path old;
  if (fs::exists(target_, ec)) {
    old = temp_name(target_, "old");
    fs::rename(target_, old, ec);
    if (ec) throw IoError(target_.string(), "cannot move the previous bake aside: " + ec.message());
  }
  fs::rename(temp_, target_, ec);
  if (ec) {
    if (!old.empty()) fs::rename(old, target_, ec);
    throw IoError(target_.string(), "cannot move the new bake into place: " + ec.message());
  }
  committed_ = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace bounce
