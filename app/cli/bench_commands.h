#pragma once
// The `bounce bench` subcommands beyond `bench bake`, one file each
// (command_bench_<name>.cpp). register_bench (command_bench.cpp) adds them
// under `bench`.
#include <CLI/CLI.hpp>
#include <vector>

namespace bounce::cli {

struct BakeOptions;
// `bench bake --scaling N1,N2,...` (command_bench_bake_scaling.cpp): time and
// peak memory per stage at each patch count, fitted exponents, and with
// extrapolate_to > 0 a prediction (labelled as such) at that N.
void run_bench_bake_scaling(const BakeOptions& opt, const std::vector<int>& sizes,
                            int extrapolate_to);

// `bench transport`: sgemm on OpenBLAS, CLBlast and a plain loop, and LU.
void register_bench_transport(CLI::App& bench);
// `bench compress`: every BC1 encoder x every ordering on a real transport
// matrix, against the published pipeline.
void register_bench_compress(CLI::App& bench);
// `bench ordering`: our ordering on a large synthetic matrix (N = 16384).
void register_bench_ordering(CLI::App& bench);
// `bench runtime`: ms per light update, compressed (OpenCL, C++) vs dense vs classic.
void register_bench_runtime(CLI::App& bench);
// `bench dynamic`: local matrix, temporal radiosity, frame-graph aliasing.
void register_bench_dynamic(CLI::App& bench);

}  // namespace bounce::cli
