#include "base/diagnostics.h"

namespace bounce {

void Diagnostics::warn(std::string where, std::string message, std::vector<std::string> detail) {
  add({Diagnostic::Kind::Warning, std::move(where), std::move(message), std::move(detail)});
}

void Diagnostics::left_out(std::string where, std::string message) {
  add({Diagnostic::Kind::LeftOut, std::move(where), std::move(message), {}});
}

void Diagnostics::add(Diagnostic d) {
  std::lock_guard lock(mutex_);
  entries_.push_back(std::move(d));
  if (listener_) listener_(entries_.back());
}

std::vector<Diagnostic> Diagnostics::all() const {
  std::lock_guard lock(mutex_);
  return entries_;
}

static std::vector<Diagnostic> filter(const std::vector<Diagnostic>& all, Diagnostic::Kind kind) {
  std::vector<Diagnostic> out;
  for (const auto& d : all)
    if (d.kind == kind) out.push_back(d);
  return out;
}

std::vector<Diagnostic> Diagnostics::warnings() const {
  return filter(all(), Diagnostic::Kind::Warning);
}

std::vector<Diagnostic> Diagnostics::left_outs() const {
  return filter(all(), Diagnostic::Kind::LeftOut);
}

void Diagnostics::set_listener(Listener listener) {
  std::lock_guard lock(mutex_);
  listener_ = std::move(listener);
}

}  // namespace bounce
