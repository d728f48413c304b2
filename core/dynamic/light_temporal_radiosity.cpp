#include "dynamic/light_temporal_radiosity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/error.h"
#include "dynamic/counter_hash.h"

namespace bounce {

namespace {

// A uniform double in [0, 1) from 32 random bits.
double unit_double(std::uint32_t h) { return static_cast<double>(h) * 0x1p-32; }

// 1 / golden ratio: the offsets frac(u0 + f g) of successive frames stay
// evenly spread over [0, 1) for any number of frames.
constexpr double kGolden = 0.6180339887498948482;

}  // namespace

LightTemporalRadiosity::LightTemporalRadiosity(const CompressedTransportTables& tables,
                                               const LightTemporalSettings& settings)
    : tables_(tables), settings_(settings) {
  if (settings_.block_columns < 1)
    throw Error("light temporal radiosity", "block columns per frame must be at least 1");
  if (settings_.history.max_frames < 0)
    throw Error("light temporal radiosity", "the history length must not be negative");
  if (!(settings_.history.change_scale > 0.0))
    throw Error("light temporal radiosity", "the change scale must be positive");
  const std::size_t padded = tables_.padded;
  column_sums_ = compressed_column_abs_sums(tables_);
  column_blocks_ = blocks_by_column(tables_);
  kept_ = kept_by_column(tables_);
  b_stored_.assign(4 * padded, 0.0f);
  scaled_.assign(4 * padded, 0.0f);
  previous_.assign(4 * padded, 0.0f);
  mass_.assign(tables_.block_rows, 0.0);
  y_stored_.assign(4 * padded, 0.0f);
  offset0_ = unit_double(hash32(settings_.seed ^ 0x5bd1e995u));
}

void LightTemporalRadiosity::estimate(std::span<const glm::vec3> b, std::uint32_t frame,
                                      std::span<glm::vec3> out) {
  if (out.size() != tables_.n)
    throw Error("light temporal radiosity", "the output has " + std::to_string(out.size()) +
                                                " entries for " + std::to_string(tables_.n) +
                                                " patches");
  estimate_stored(b, frame, false);
  const float(*y)[4] = reinterpret_cast<const float(*)[4]>(y_stored_.data());
  for (std::size_t i = 0; i < tables_.n; ++i)
    out[tables_.permutation[i]] = glm::vec3(y[i][0], y[i][1], y[i][2]);
}

void LightTemporalRadiosity::estimate_stored(std::span<const glm::vec3> b, std::uint32_t frame,
                                             bool measure_change) {
  if (b.size() != tables_.n)
    throw Error("light temporal radiosity", "b has " + std::to_string(b.size()) + " entries for " +
                                                std::to_string(tables_.n) + " patches");
  // One pass: b into stored order, the mass of each block column and, when
  // asked, the change against the previous step's b (same weights).
  std::fill(mass_.begin(), mass_.end(), 0.0);
  double change = 0.0;
  for (std::size_t i = 0; i < tables_.n; ++i) {
    const glm::vec3& v = b[tables_.permutation[i]];
    float* stored = &b_stored_[4 * i];
    stored[0] = v.x;
    stored[1] = v.y;
    stored[2] = v.z;
    const float* c = &column_sums_[3 * i];
    mass_[i / 4] +=
        static_cast<double>(c[0] * std::abs(v.x) + c[1] * std::abs(v.y) + c[2] * std::abs(v.z));
    if (measure_change) {
      const float* p = &previous_[4 * i];
      change += static_cast<double>(c[0] * std::abs(v.x - p[0]) + c[1] * std::abs(v.y - p[1]) +
                                    c[2] * std::abs(v.z - p[2]));
    }
  }
  if (measure_change) {
    double total = 0.0;
    for (const double m : mass_) total += m;
    last_change_ = total > 0.0    ? change / total
                   : change > 0.0 ? std::numeric_limits<double>::infinity()
                                  : 0.0;
  }
  const double u = settings_.stratify_frames
                       ? std::fmod(offset0_ + kGolden * static_cast<double>(frame), 1.0)
                       : unit_double(hash32(hash32(settings_.seed) ^ frame));
  systematic_draw(mass_, settings_.block_columns, u, draw_);
  // Only the drawn block columns are read; their scaled b goes in and is
  // cleared again after the product, so scaled_ stays zero elsewhere.
  for (std::size_t d = 0; d < draw_.items.size(); ++d) {
    const std::size_t q0 = 4 * static_cast<std::size_t>(draw_.items[d]);
    const auto scale = static_cast<float>(draw_.scale[d]);
    for (std::size_t i = 4 * q0; i < 4 * q0 + 16; ++i) scaled_[i] = b_stored_[i] * scale;
  }
  float(*y)[4] = reinterpret_cast<float(*)[4]>(y_stored_.data());
  multiply_block_columns(tables_, column_blocks_.data(), scaled_.data(), draw_.items, y);
  last_kept_ = add_kept_columns(kept_, scaled_.data(), draw_.items, y);
  for (std::uint32_t J : draw_.items)
    std::fill_n(scaled_.begin() + 16 * static_cast<std::ptrdiff_t>(J), 16, 0.0f);
}

double LightTemporalRadiosity::light_change(std::span<const glm::vec3> b) const {
  if (!has_previous_) return 0.0;
  if (b.size() != tables_.n)
    throw Error("light temporal radiosity", "b has " + std::to_string(b.size()) + " entries for " +
                                                std::to_string(tables_.n) + " patches");
  double change = 0.0, total = 0.0;
  for (std::size_t i = 0; i < tables_.n; ++i) {
    const glm::vec3& v = b[tables_.permutation[i]];
    for (std::size_t k = 0; k < 3; ++k) {
      const double c = column_sums_[3 * i + k];
      change += c * std::abs(static_cast<double>(v[static_cast<glm::length_t>(k)]) -
                             previous_[4 * i + k]);
      total += c * std::abs(v[static_cast<glm::length_t>(k)]);
    }
  }
  if (total > 0.0) return change / total;
  return change > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

void LightTemporalRadiosity::step(std::span<const glm::vec3> b, std::span<glm::vec3> history) {
  if (history.size() != tables_.n)
    throw Error("light temporal radiosity", "the history has " + std::to_string(history.size()) +
                                                " entries for " + std::to_string(tables_.n) +
                                                " patches");
  estimate_stored(b, frame_, has_previous_);
  if (!has_previous_) last_change_ = 0.0;
  history_frames_ =
      history_frames_after_change(history_frames_, last_change_, settings_.history.change_scale);
  const float w = history_weight(history_frames_);
  const float(*y)[4] = reinterpret_cast<const float(*)[4]>(y_stored_.data());
  for (std::size_t i = 0; i < tables_.n; ++i) {
    glm::vec3& h = history[tables_.permutation[i]];
    h = w * h + (1.0f - w) * glm::vec3(y[i][0], y[i][1], y[i][2]);
  }
  last_weight_ = w;
  history_frames_ =
      std::min(history_frames_ + 1.0, static_cast<double>(settings_.history.max_frames));
  // The next gather rewrites every stored column of b_stored_ (padding
  // stays 0 in both).
  previous_.swap(b_stored_);
  has_previous_ = true;
  ++frame_;
}

void LightTemporalRadiosity::reset() {
  history_frames_ = 0.0;
  has_previous_ = false;
  last_change_ = 0.0;
}

std::size_t LightTemporalRadiosity::last_bytes_read() const {
  const std::size_t width = static_cast<std::size_t>(tables_.correction_width);
  return draw_.items.size() * (tables_.block_rows * 8 + 4 * sizeof(std::uint32_t)) +
         last_kept_ * (sizeof(std::uint32_t) + width * sizeof(float)) +
         tables_.n * (sizeof(glm::vec3) + 3 * sizeof(float));
}

std::size_t LightTemporalRadiosity::table_bytes_read() const {
  return tables_.blocks.size() +
         (tables_.palettes.size() + tables_.bc1_tables.size()) * sizeof(float);
}

std::size_t LightTemporalRadiosity::own_bytes() const {
  return kept_.bytes() +
         (column_sums_.size() + b_stored_.size() + scaled_.size() + previous_.size() +
          y_stored_.size()) *
             sizeof(float) +
         mass_.size() * sizeof(double) + draw_.items.capacity() * sizeof(std::uint32_t) +
         draw_.scale.capacity() * sizeof(double);
}

}  // namespace bounce
