#include "flag_spelling.h"

#include "bounce/settings.h"

namespace bounce::cli {

std::string with_flag_spellings(std::string message) {
  for (const SettingRow& row : settings_table()) {
    // A negating option (--no-pictures) says the opposite of the setting.
    if (*row.flag == '\0' || row.flag_negates) continue;
    const std::string quoted = std::string("'") + row.name + "'";
    for (std::size_t at = message.find(quoted); at != std::string::npos;
         at = message.find(quoted, at)) {
      message.replace(at, quoted.size(), row.flag);
      at += std::char_traits<char>::length(row.flag);
    }
  }
  return message;
}

}  // namespace bounce::cli
