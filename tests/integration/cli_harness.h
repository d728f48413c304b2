#pragma once
// Runs the real `bounce` executable as a subprocess and looks at what it left
// behind: exit code, stdout, stderr, the bake folder. Every test works in its
// own fresh temporary folder, which is also the child's working directory, so
// a bake that forgets --out cannot litter the source tree.
#include <fcntl.h>
#include <grp.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/npy.h"

extern char** environ;

namespace bounce::itest {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

// The `bounce` under test: the one this test binary was built with, or
// BOUNCE_TEST_CLI when set (a copy placed elsewhere, e.g. in a folder only its
// owner may enter, to test the harness from there).
inline fs::path cli_under_test() {
  const char* chosen = std::getenv("BOUNCE_TEST_CLI");
  return chosen != nullptr && *chosen != '\0' ? fs::path(chosen) : fs::path(BOUNCE_CLI);
}
inline const fs::path kCli = cli_under_test();

// The harness itself could not start the program (chdir, resource limit,
// dropping root, exec): a broken test set-up, never an answer of the program.
class HarnessError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
inline const fs::path kScenes = fs::path(BOUNCE_RESOURCE_DIR) / "scenes";

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) ADD_FAILURE() << "cannot write " << path;
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

inline std::vector<std::string> lines_starting_with(const std::string& text,
                                                    const std::string& prefix) {
  std::vector<std::string> out;
  for (const std::string& l : lines_of(text))
    if (l.rfind(prefix, 0) == 0) out.push_back(l);
  return out;
}

inline bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

// A fresh folder under the system temp folder, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "bounce-itest-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

struct RunResult {
  int exit_code = -1;  // the process's exit status, or 128 + signal if a signal ended it
  std::string out, err;
  bool timed_out = false;
  double seconds = 0.0;
};

inline std::ostream& operator<<(std::ostream& os, const RunResult& r) {
  return os << "exit code " << r.exit_code << (r.timed_out ? " (timed out)" : "") << " after "
            << r.seconds << " s\n--- stdout ---\n"
            << r.out.substr(0, 4000) << "\n--- stderr ---\n"
            << r.err.substr(0, 4000);
}

struct RunOptions {
  fs::path cwd;                                 // empty: the test's own working folder
  std::map<std::string, std::string> env;       // added to (or replacing in) the environment
  std::chrono::duration<double> timeout{60.0};  // killed with SIGKILL after this
  fs::path program;                             // empty: kCli
  // Confinement: drop root to the `nobody` user (uid and gid 65534, no
  // supplementary groups) so that permission bits apply, and cap the size of
  // each file the program writes (RLIMIT_FSIZE, with SIGXFSZ ignored so that
  // write() fails with EFBIG instead of killing it): a full disk without
  // mounting anything.
  bool as_nobody = false;
  rlim_t max_file_bytes = RLIM_INFINITY;
  // Caps the address space (RLIMIT_AS, as `ulimit -v` does): an allocation
  // beyond it fails inside the program instead of waking the OOM killer.
  rlim_t max_address_bytes = RLIM_INFINITY;
};

constexpr uid_t kNobody = 65534;

// What a child writes into its close-on-exec pipe when it cannot start the
// program: which step failed and errno. A successful exec closes the pipe
// with nothing written.
struct StartFailure {
  enum Step : int { kChdir, kFileSizeLimit, kAddressSpaceLimit, kDropRoot, kExec } step;
  int error;
};

inline std::string describe(const StartFailure& f, const std::string& program,
                            const std::string& cwd) {
  const std::string why = std::strerror(f.error);
  switch (f.step) {
    case StartFailure::kChdir:
      return "cannot chdir to " + cwd + ": " + why;
    case StartFailure::kFileSizeLimit:
      return "cannot set RLIMIT_FSIZE: " + why;
    case StartFailure::kAddressSpaceLimit:
      return "cannot set RLIMIT_AS: " + why;
    case StartFailure::kDropRoot:
      return "cannot drop to user nobody: " + why;
    case StartFailure::kExec:
      break;
  }
  return "cannot exec " + program + ": " + why;
}

// A running `bounce`, its stdout and stderr going to files.
class Child {
 public:
  Child(const std::vector<std::string>& args, const RunOptions& options) {
    std::string out_pattern = (fs::temp_directory_path() / "bounce-itest-out-XXXXXX").string();
    std::string err_pattern = (fs::temp_directory_path() / "bounce-itest-err-XXXXXX").string();
    const int out_fd = ::mkstemp(out_pattern.data());
    const int err_fd = ::mkstemp(err_pattern.data());
    if (out_fd < 0 || err_fd < 0) throw std::runtime_error("mkstemp failed");
    out_path_ = out_pattern;
    err_path_ = err_pattern;

    // Everything the child needs is built before fork(): after it only
    // async-signal-safe calls.
    const std::string program = options.program.empty() ? kCli.string() : options.program.string();
    std::vector<std::string> argv_strings{program};
    argv_strings.insert(argv_strings.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argv_strings) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> env_strings;
    for (char** e = environ; *e != nullptr; ++e) {
      const std::string entry(*e);
      const std::string key = entry.substr(0, entry.find('='));
      if (options.env.count(key) == 0) env_strings.push_back(entry);
    }
    for (const auto& [key, value] : options.env) env_strings.push_back(key + "=" + value);
    std::vector<char*> envp;
    for (std::string& e : env_strings) envp.push_back(e.data());
    envp.push_back(nullptr);
    const std::string cwd = options.cwd.string();
    const int null_fd = ::open("/dev/null", O_RDONLY);
    int report[2];
    if (::pipe2(report, O_CLOEXEC) != 0) throw HarnessError("pipe2 failed");

    pid_ = ::fork();
    if (pid_ < 0) throw HarnessError("fork failed");
    if (pid_ == 0) {
      const auto fail = [&report](StartFailure::Step step) {
        const StartFailure f{step, errno};
        [[maybe_unused]] const ssize_t written = ::write(report[1], &f, sizeof f);
        ::_exit(127);
      };
      ::dup2(null_fd, STDIN_FILENO);
      ::dup2(out_fd, STDOUT_FILENO);
      ::dup2(err_fd, STDERR_FILENO);
      if (!cwd.empty() && ::chdir(cwd.c_str()) != 0) fail(StartFailure::kChdir);
      if (options.max_file_bytes != RLIM_INFINITY) {
        ::signal(SIGXFSZ, SIG_IGN);  // an ignored signal stays ignored across exec
        const rlimit limit{options.max_file_bytes, options.max_file_bytes};
        if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) fail(StartFailure::kFileSizeLimit);
      }
      if (options.max_address_bytes != RLIM_INFINITY) {
        const rlimit limit{options.max_address_bytes, options.max_address_bytes};
        if (::setrlimit(RLIMIT_AS, &limit) != 0) fail(StartFailure::kAddressSpaceLimit);
      }
      if (options.as_nobody &&
          (::setgroups(0, nullptr) != 0 || ::setgid(kNobody) != 0 || ::setuid(kNobody) != 0))
        fail(StartFailure::kDropRoot);
      ::execve(argv[0], argv.data(), envp.data());
      fail(StartFailure::kExec);
    }
    ::close(report[1]);
    ::close(out_fd);
    ::close(err_fd);
    if (null_fd >= 0) ::close(null_fd);
    start_ = Clock::now();
    // Blocks until the exec closes the pipe or the child reports why it could
    // not get there; the latter is the harness's failure, not an exit code
    // of the program.
    StartFailure failure{};
    ssize_t got = 0;
    do {
      got = ::read(report[0], &failure, sizeof failure);
    } while (got < 0 && errno == EINTR);
    ::close(report[0]);
    if (got == static_cast<ssize_t>(sizeof failure)) {
      int status = 0;
      ::waitpid(pid_, &status, 0);
      finished_ = true;
      remove_outputs();
      throw HarnessError(describe(failure, program, cwd));
    }
  }

  ~Child() {
    if (pid_ > 0 && !finished_) {
      ::kill(pid_, SIGKILL);
      int status = 0;
      ::waitpid(pid_, &status, 0);
    }
    remove_outputs();
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  // True while the process has not exited (reaps it if it has).
  bool running() {
    if (finished_) return false;
    int status = 0;
    const pid_t r = ::waitpid(pid_, &status, WNOHANG);
    if (r == pid_) record(status);
    return !finished_;
  }

  void send(int signal) { ::kill(pid_, signal); }

  // What the process has written to stderr so far.
  std::string err_so_far() const { return read_text(err_path_); }

  // Waits up to `timeout`; kills the process if it is still running then.
  RunResult wait(std::chrono::duration<double> timeout) {
    const auto deadline = Clock::now() + timeout;
    while (running()) {
      if (Clock::now() >= deadline) {
        ::kill(pid_, SIGKILL);
        int status = 0;
        ::waitpid(pid_, &status, 0);
        record(status);
        result_.timed_out = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    result_.out = read_text(out_path_);
    result_.err = read_text(err_path_);
    return result_;
  }

  double seconds_since_start() const {
    return std::chrono::duration<double>(Clock::now() - start_).count();
  }

 private:
  void remove_outputs() {
    std::error_code ec;
    fs::remove(out_path_, ec);
    fs::remove(err_path_, ec);
  }

  void record(int status) {
    finished_ = true;
    result_.seconds = seconds_since_start();
    if (WIFEXITED(status))
      result_.exit_code = WEXITSTATUS(status);
    else if (WIFSIGNALED(status))
      result_.exit_code = 128 + WTERMSIG(status);
  }

  pid_t pid_ = -1;
  bool finished_ = false;
  fs::path out_path_, err_path_;
  Clock::time_point start_;
  RunResult result_;
};

inline RunResult run(const std::vector<std::string>& args, RunOptions options) {
  Child child(args, options);
  return child.wait(options.timeout);
}

// Runs `bounce args...` in `cwd`.
inline RunResult run(const std::vector<std::string>& args, const fs::path& cwd,
                     double timeout_seconds = 60.0) {
  RunOptions o;
  o.cwd = cwd;
  o.timeout = std::chrono::duration<double>(timeout_seconds);
  return run(args, o);
}

inline std::string scene(const std::string& name) { return (kScenes / name).string(); }

inline json parse_json(const std::string& text) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    ADD_FAILURE() << "not JSON (" << e.what() << "):\n" << text.substr(0, 2000);
    return json();
  }
}

inline json read_manifest(const fs::path& bake) {
  return parse_json(read_text(bake / "manifest.json"));
}

// Hidden temporary siblings of a bake folder (`.NAME.partial-*`, `.NAME.old-*`,
// `.NAME.tmp-*`) left in its parent.
inline std::vector<std::string> hidden_leftovers(const fs::path& target) {
  std::vector<std::string> found;
  const fs::path parent = target.parent_path();
  if (!fs::is_directory(parent)) return found;
  std::string prefix = ".";  // built piecewise: GCC 12 warns (-Wrestrict) on "." + string
  prefix += target.filename().string();
  prefix += '.';
  for (const auto& e : fs::directory_iterator(parent)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) == 0) found.push_back(name);
  }
  return found;
}

// Every entry name in a folder, sorted.
inline std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Column layout of patches.npy (docs/bake-format.md).
namespace patch_col {
constexpr std::size_t kPos = 0, kNormal = 3, kArea = 6, kAlbedo = 7, kVoxel = 10, kMesh = 11,
                      kEmission = 12, kCount = 15;
}
namespace voxel_col {
constexpr std::size_t kCell = 0, kCentre = 3, kArea = 6, kSamples = 7, kPatches = 8, kCount = 9;
}
namespace sample_col {
constexpr std::size_t kPos = 0, kNormal = 3, kArea = 6, kVoxel = 10, kPatch = 11, kTriangle = 12,
                      kCount = 13;
}

inline float at(const NpyArray<float>& a, std::size_t row, std::size_t col) {
  return a.data[row * a.shape[1] + col];
}

// Checks every patch row: finite values, unit normal, positive area. Reports
// the number of bad rows and the first one instead of one failure per row.
inline void expect_valid_patches(const NpyArray<float>& p, const std::string& what) {
  ASSERT_EQ(p.shape.size(), 2u) << what;
  ASSERT_EQ(p.shape[1], patch_col::kCount) << what;
  ASSERT_GT(p.shape[0], 0u) << what << ": no patches";
  std::size_t non_finite = 0, bad_normal = 0, bad_area = 0;
  std::string first;
  for (std::size_t i = 0; i < p.shape[0]; ++i) {
    bool finite = true;
    for (std::size_t c = 0; c < patch_col::kCount; ++c)
      finite = finite && std::isfinite(at(p, i, c));
    const double nx = at(p, i, patch_col::kNormal), ny = at(p, i, patch_col::kNormal + 1),
                 nz = at(p, i, patch_col::kNormal + 2);
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    const bool normal_ok = std::abs(len - 1.0) <= 1e-3;
    const bool area_ok = at(p, i, patch_col::kArea) > 0.0f;
    non_finite += finite ? 0 : 1;
    bad_normal += normal_ok ? 0 : 1;
    bad_area += area_ok ? 0 : 1;
    if (first.empty() && !(finite && normal_ok && area_ok))
      first = "row " + std::to_string(i) + ": |normal| = " + std::to_string(len) +
              ", area = " + std::to_string(at(p, i, patch_col::kArea));
  }
  EXPECT_EQ(non_finite, 0u) << what << ": patches with NaN/Inf; first bad " << first;
  EXPECT_EQ(bad_normal, 0u) << what << ": patches whose normal is not unit length; first bad "
                            << first;
  EXPECT_EQ(bad_area, 0u) << what << ": patches with area <= 0; first bad " << first;
}

inline double column_sum(const NpyArray<float>& a, std::size_t col) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.shape[0]; ++i) sum += at(a, i, col);
  return sum;
}

}  // namespace bounce::itest
