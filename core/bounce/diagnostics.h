#pragma once
// Public: the warnings a library call collects instead of failing.
//
//   bounce::Diagnostics diagnostics;
//   const bounce::Scene scene = bounce::SceneLoader(diagnostics).load(path);
//   for (const bounce::Diagnostic& d : diagnostics.warnings()) show(d.where, d.message);
//
// What the library repairs or leaves out (a degenerate triangle dropped, a
// setting clamped) is recorded here with where it came from, so a front end
// can show it and a bake can store it in its manifest.
#include "base/diagnostics.h"
