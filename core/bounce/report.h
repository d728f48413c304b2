#pragma once
// Public: measure bakes against the path-traced reference (docs/reference.md).
//
//   const bounce::ReferenceCache cache(bounce::ReferenceCache::default_dir());
//   bounce::ReportSweepSettings sweep;
//   sweep.fill_defaults(/*quick=*/true);
//   const bounce::ReportData report =
//       bounce::run_report_sweep(scene, sweep, &cache, progress, diagnostics);
//
// A sweep bakes a scene with a list of settings, lights each bake with the
// same lights as the path tracer (no code shared with the solver) and
// records error against run time per bake; ReportData reads and writes the
// report.json a sweep leaves and picks its Pareto front. References are
// cached by the content hash of the scene and their settings.
// cached_reference_images renders (or finds) the reference pictures of one
// scene; baked_multiply gives the product T b of a bake still in memory;
// probe_reference_error measures light probes' SH against the path tracer.
#include "reference/probe_reference_error.h"
#include "reference/reference_cache.h"
#include "report/baked_multiply.h"
#include "report/report_data.h"
#include "report/report_sweep.h"
