#pragma once
// Dense matrices that can live in a file instead of anonymous memory, for
// bakes larger than memory (docs/cluster.md, "Larger than memory").
//
// MatrixBuffer<T> is a std::vector whose allocator asks the process-wide
// out-of-core policy where a matrix goes:
//  * no policy (the default): ordinary heap memory, as any std::vector;
//  * a policy (OutOfCoreScope): a temporary file in the policy's directory,
//    mapped MAP_SHARED. The file is unlinked as soon as it is mapped, so it
//    disappears with the mapping, on every exit path, crashes included. The
//    kernel can write its pages back and evict them under memory pressure
//    (this machine has no swap: anonymous memory could only grow until the
//    OOM killer), and release_residency() hands finished matrices back early.
// Both paths hold the same bytes and run the same arithmetic, so results are
// bit-identical (tests/integration/test_out_of_core_bake.cpp).
//
// Resident mapped pages count in the process's RSS (RssFile), so the peak RSS
// of a stage (stage_stats.h) includes the pages of mapped matrices the stage
// touched and the kernel has not evicted yet.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <vector>

namespace bounce {

// One temporary file of `bytes` bytes in `dir`, mapped read-write and shared.
// Disk space is reserved up front (posix_fallocate), so a full disk is an
// error here rather than a SIGBUS when a page is first written.
class MappedFile {
 public:
  // Throws bounce::Error naming `dir` when the file cannot be created,
  // sized or mapped.
  MappedFile(const std::filesystem::path& dir, std::size_t bytes);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  void* data() const { return data_; }
  std::size_t size() const { return bytes_; }
  // Detaches the mapping from this object (the caller unmaps it).
  void* release();

 private:
  void* data_ = nullptr;
  std::size_t bytes_ = 0;
};

struct OutOfCorePolicy {
  std::filesystem::path dir;  // where the temporary matrix files go
};

// The directory a bake uses when none is given: $TMPDIR, else /tmp.
std::filesystem::path default_out_of_core_dir();

// Installs `policy` for every MatrixBuffer allocated while the scope lives
// (process-wide: the matrices a bake allocates on any thread), and restores
// the previous policy when it ends. An empty policy means heap memory.
class OutOfCoreScope {
 public:
  explicit OutOfCoreScope(std::optional<OutOfCorePolicy> policy);
  ~OutOfCoreScope();
  OutOfCoreScope(const OutOfCoreScope&) = delete;
  OutOfCoreScope& operator=(const OutOfCoreScope&) = delete;

 private:
  std::optional<OutOfCorePolicy> previous_;
};

// The policy in force (empty: heap).
std::optional<OutOfCorePolicy> out_of_core_policy();

// Raw allocation behind MatrixAllocator: a mapping under a policy, else heap.
void* allocate_matrix_bytes(std::size_t bytes);
void deallocate_matrix_bytes(void* p, std::size_t bytes) noexcept;
// Whether p is the start of a live mapped matrix.
bool is_mapped_matrix(const void* p);
// Bytes of matrices currently mapped to files (for the manifest and bench).
std::size_t mapped_matrix_bytes();
// Writes a mapped matrix's dirty pages back and drops them from memory
// (MADV_PAGEOUT, else msync + MADV_DONTNEED); a later access reads them back
// from the file. Does nothing for heap memory.
void release_residency(const void* p, std::size_t bytes);

// Physical memory of the machine (sysconf), in bytes; 0 when unknown.
std::size_t physical_memory_bytes();

template <class T>
struct MatrixAllocator {
  using value_type = T;
  MatrixAllocator() = default;
  template <class U>
  MatrixAllocator(const MatrixAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_matrix_bytes(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { deallocate_matrix_bytes(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const MatrixAllocator<U>&) const noexcept {
    return true;  // any instance frees any buffer: the registry knows which is mapped
  }
};

template <class T>
using MatrixBuffer = std::vector<T, MatrixAllocator<T>>;
// Row-major n x n float32 matrix: form factors F, transport T, their work buffers.
using MatrixValues = MatrixBuffer<float>;

template <class T>
void release_residency(const MatrixBuffer<T>& m) {
  release_residency(m.data(), m.size() * sizeof(T));
}

// A finished matrix moved to a mapped file under `policy` (one sequential
// write), its pages handed back at once; the heap copy is freed. Matrices
// still being computed stay on the heap: the kernel writes dirty mapped
// pages back every few seconds, and a matrix rewritten in place (an LU, a
// scattered fill) would be written to disk over and over.
inline MatrixValues spill_to_file(MatrixValues&& m, const OutOfCorePolicy& policy) {
  if (m.empty() || is_mapped_matrix(m.data())) return std::move(m);
  const OutOfCoreScope scope(policy);
  MatrixValues mapped(m.begin(), m.end());
  m = MatrixValues();
  release_residency(mapped);
  return mapped;
}

}  // namespace bounce
