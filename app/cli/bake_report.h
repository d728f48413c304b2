#pragma once
// The human-readable bake report printed after `bounce bake`, built from the
// manifest so it shows exactly what was written.
#include <cstdio>

#include <nlohmann/json.hpp>

namespace bounce::cli {

void print_bake_report(std::FILE* out, const nlohmann::json& manifest);
void print_stage_table(std::FILE* out, const nlohmann::json& manifest);
// Transport matrix and its storage: K, method, spectral radius, sizes, errors.
void print_transport_report(std::FILE* out, const nlohmann::json& manifest);

}  // namespace bounce::cli
