#pragma once
// Writing an image file through OpenImageIO atomically: into a temporary
// file next to the target (keeping the extension, from which OIIO picks the
// format), renamed into place only when complete. The PNG and EXR writers
// share it. Internal to core/io (exposes OIIO types).
#include <OpenImageIO/imageio.h>

#include <filesystem>

namespace bounce {

// `format` names the file type in errors ("PNG", "EXR"). Throws IoError.
void write_image_atomically(const std::filesystem::path& path, const OIIO::ImageSpec& spec,
                            const void* pixels, const char* format);

}  // namespace bounce
