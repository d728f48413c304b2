#pragma once
// Public: what the library throws.
//
//   try { ... } catch (const bounce::Cancelled&) { /* the user stopped it */ }
//   catch (const bounce::Error& e) { std::cerr << e.what(); }  // names the file or setting
//
// Every failure the library reports is a bounce::Error (a std::runtime_error)
// whose message names what it concerns; a stop requested through Progress
// is the subclass bounce::Cancelled, so a front end can tell the two apart.
#include "base/error.h"
