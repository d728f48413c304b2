#include "io/image_file.h"

#include <unistd.h>

#include <atomic>
#include <string>
#include <system_error>

#include "io/atomic_file.h"

namespace bounce {

namespace fs = std::filesystem;

void write_image_atomically(const fs::path& path, const OIIO::ImageSpec& spec, const void* pixels,
                            const char* format) {
  static std::atomic<unsigned> counter{0};
  const fs::path temp =
      path.parent_path() / ("." + path.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                            "-" + std::to_string(counter++) + path.extension().string());
  auto out = OIIO::ImageOutput::create(temp.string());
  if (!out)
    throw IoError(path.string(), std::string("cannot write ") + format + ": " + OIIO::geterror());
  const bool ok =
      out->open(temp.string(), spec) && out->write_image(spec.format, pixels) && out->close();
  std::error_code ec;
  if (!ok) {
    const std::string why = out->geterror();
    fs::remove(temp, ec);
    throw IoError(path.string(), std::string("cannot write ") + format + ": " + why);
  }
  fs::rename(temp, path, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(temp, ec);
    throw IoError(path.string(), "cannot move into place: " + why);
  }
}

}  // namespace bounce
