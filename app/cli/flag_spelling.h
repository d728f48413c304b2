#pragma once
// The core names settings in its messages ('size_limit'), as Python and the
// studio know them; on the command line the user typed their options.
#include <string>

namespace bounce::cli {

// `message` with every quoted setting name ('closure_rays') replaced by its
// option (--closure-rays). Names of no setting, and settings without an
// option of their own, stay as they are.
std::string with_flag_spellings(std::string message);

}  // namespace bounce::cli
