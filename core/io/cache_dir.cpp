#include "io/cache_dir.h"

#include <cstdlib>

namespace bounce {

namespace fs = std::filesystem;

fs::path user_cache_dir(const std::string& what) {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return fs::path(xdg) / "bounce" / what;
  if (const char* home = std::getenv("HOME"); home && *home)
    return fs::path(home) / ".cache" / "bounce" / what;
  return fs::temp_directory_path() / ("bounce-" + what);
}

}  // namespace bounce
