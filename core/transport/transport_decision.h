#pragma once
// A choice the transport stage made, and the measurement or rule behind it,
// for the bake manifest ("what was done and why").
#include <string>

namespace bounce {

struct TransportDecision {
  std::string what;
  std::string why;
};

}  // namespace bounce
