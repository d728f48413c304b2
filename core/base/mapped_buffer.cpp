#include "base/mapped_buffer.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <new>
#include <string>

#include "base/error.h"

namespace bounce {

namespace {

std::string errno_text(int e) { return std::strerror(e); }

// The policy and the live mappings, process-wide.
struct Registry {
  std::mutex mutex;
  std::optional<OutOfCorePolicy> policy;
  std::map<const void*, std::size_t> mapped;  // start -> bytes
  std::size_t mapped_bytes = 0;
};

Registry& registry() {
  static Registry r;
  return r;
}

std::size_t page_size() {
  static const std::size_t size = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  return size;
}

}  // namespace

MappedFile::MappedFile(const std::filesystem::path& dir, std::size_t bytes) : bytes_(bytes) {
  const std::string where = dir.string();
  if (bytes == 0) throw Error(where, "a mapped matrix file cannot be empty");
  std::string name = (dir / "bounce-matrix-XXXXXX").string();
  const int fd = ::mkstemp(name.data());
  if (fd < 0)
    throw Error(where, "cannot create a temporary matrix file for the out-of-core bake: " +
                           errno_text(errno));
  // Unlinked at once: the file lives exactly as long as the mapping, and
  // nothing is left behind whatever way the process ends.
  ::unlink(name.c_str());
  const int reserved = ::posix_fallocate(fd, 0, static_cast<off_t>(bytes));
  if (reserved != 0) {
    ::close(fd);
    throw Error(where,
                "cannot reserve " + std::to_string(bytes >> 20) +
                    " MiB for a temporary matrix file (out-of-core bake): " + errno_text(reserved));
  }
  void* p = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  const int map_errno = errno;
  ::close(fd);  // the mapping keeps the file open
  if (p == MAP_FAILED)
    throw Error(where, "cannot map a " + std::to_string(bytes >> 20) +
                           " MiB temporary matrix file: " + errno_text(map_errno));
  data_ = p;
}

MappedFile::~MappedFile() {
  if (data_) ::munmap(data_, bytes_);
}

void* MappedFile::release() {
  void* p = data_;
  data_ = nullptr;
  return p;
}

std::filesystem::path default_out_of_core_dir() {
  const char* tmp = std::getenv("TMPDIR");
  return tmp && *tmp ? std::filesystem::path(tmp) : std::filesystem::path("/tmp");
}

OutOfCoreScope::OutOfCoreScope(std::optional<OutOfCorePolicy> policy) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  previous_ = std::move(r.policy);
  r.policy = std::move(policy);
}

OutOfCoreScope::~OutOfCoreScope() {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  r.policy = std::move(previous_);
}

std::optional<OutOfCorePolicy> out_of_core_policy() {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  return r.policy;
}

void* allocate_matrix_bytes(std::size_t bytes) {
  const std::optional<OutOfCorePolicy> policy = out_of_core_policy();
  if (!policy || bytes == 0) return ::operator new(bytes);
  MappedFile file(policy->dir, bytes);
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  r.mapped.emplace(file.data(), bytes);
  r.mapped_bytes += bytes;
  return file.release();
}

void deallocate_matrix_bytes(void* p, [[maybe_unused]] std::size_t bytes) noexcept {
  if (!p) return;
  {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    const auto it = r.mapped.find(p);
    if (it != r.mapped.end()) {
      ::munmap(p, it->second);
      r.mapped_bytes -= it->second;
      r.mapped.erase(it);
      return;
    }
  }
  // Unsized: clang does not declare the sized delete without
  // -fsized-deallocation (the fuzz build), and the heap needs no size.
  ::operator delete(p);
}

bool is_mapped_matrix(const void* p) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  return r.mapped.count(p) > 0;
}

std::size_t mapped_matrix_bytes() {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  return r.mapped_bytes;
}

void release_residency(const void* p, std::size_t bytes) {
  if (!p || bytes == 0) return;
  Registry& r = registry();
  std::unique_lock lock(r.mutex);
  // The mapping that holds p (p may point into it).
  auto it = r.mapped.upper_bound(p);
  if (it == r.mapped.begin()) return;
  --it;
  const auto* start = static_cast<const char*>(it->first);
  const auto* end = start + it->second;
  const auto* lo = static_cast<const char*>(p);
  if (lo >= end) return;
  const auto* hi = std::min(end, lo + bytes);
  lock.unlock();
  // madvise works on whole pages: the pages wholly inside [lo, hi), the
  // mapping's own end counting as a page end.
  const std::size_t page = page_size();
  const auto first = (reinterpret_cast<std::uintptr_t>(lo) + page - 1) / page * page;
  auto last = reinterpret_cast<std::uintptr_t>(hi);
  if (hi != end) last = last / page * page;
  if (last <= first) return;
  void* a = reinterpret_cast<void*>(first);
  const std::size_t n = last - first;
#ifdef MADV_PAGEOUT
  if (::madvise(a, n, MADV_PAGEOUT) == 0) return;
#endif
  // Older kernels: write the pages back, then drop them from this mapping.
  ::msync(a, n, MS_SYNC);
  ::madvise(a, n, MADV_DONTNEED);
}

std::size_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long size = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && size > 0 ? static_cast<std::size_t>(pages) * static_cast<std::size_t>(size)
                               : 0;
}

}  // namespace bounce
