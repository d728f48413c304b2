#pragma once
// Where Bounce keeps what it can compute again (references, bakes): the
// user's cache folder, as the XDG base directory rules place it.
#include <filesystem>
#include <string>

namespace bounce {

// $XDG_CACHE_HOME/bounce/<what>, else $HOME/.cache/bounce/<what>, else
// <temp>/bounce-<what>. Not created.
std::filesystem::path user_cache_dir(const std::string& what);

}  // namespace bounce
