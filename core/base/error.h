#pragma once
// The one exception type of the core. Every error a user can cause carries the
// file (or setting) it concerns and a sentence saying what is wrong, so the CLI
// can print exactly one clear line and exit non-zero. Modules nest their own
// subclasses (e.g. SceneLoader::LoadError) so callers can catch by origin.
#include <stdexcept>
#include <string>

namespace bounce {

class Error : public std::runtime_error {
 public:
  // `where` names the file, setting or stage the error is about; may be empty.
  Error(std::string where, const std::string& what)
      : std::runtime_error(where.empty() ? what : where + ": " + what), where_(std::move(where)) {}
  const std::string& where() const noexcept { return where_; }

 private:
  std::string where_;
};

// Thrown from inside long work when the user asked to stop (Ctrl-C, Cancel).
class Cancelled : public Error {
 public:
  Cancelled() : Error("", "cancelled by the user") {}
};

}  // namespace bounce
