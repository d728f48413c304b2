#pragma once
// Warnings and "left out" decisions gathered while working, so that nothing is
// dropped silently: the CLI prints them and the bake manifest records them.
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace bounce {

struct Diagnostic {
  enum class Kind { Warning, LeftOut };
  Kind kind;
  std::string where;    // file, stage or setting
  std::string message;  // what happened and why
  // A warning that sums up many cases (one line per kind, naming the first
  // few) lists every case here; the bake manifest keeps the list.
  std::vector<std::string> detail;
};

class Diagnostics {
 public:
  using Listener = std::function<void(const Diagnostic&)>;

  void warn(std::string where, std::string message, std::vector<std::string> detail = {});
  // Records something the bake chose not to do / not to keep, with the reason.
  void left_out(std::string where, std::string message);

  std::vector<Diagnostic> all() const;
  std::vector<Diagnostic> warnings() const;
  std::vector<Diagnostic> left_outs() const;
  // Called (under a lock) for each new entry, e.g. to print it at once.
  void set_listener(Listener listener);

 private:
  void add(Diagnostic d);
  mutable std::mutex mutex_;
  std::vector<Diagnostic> entries_;
  Listener listener_;
};

}  // namespace bounce
