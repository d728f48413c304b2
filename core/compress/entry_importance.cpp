#include "compress/entry_importance.h"

#include <algorithm>

#include "base/error.h"

namespace bounce {

namespace {

// Scales `w` to mean 1 (left alone when it is all zero).
void normalise(std::vector<double>& w) {
  double sum = 0.0;
  for (double v : w) sum += v;
  if (!(sum > 0.0)) return;
  const double scale = static_cast<double>(w.size()) / sum;
  for (double& v : w) v *= scale;
}

std::vector<float> to_float(const std::vector<double>& w) { return {w.begin(), w.end()}; }

}  // namespace

EntryImportance light_importance(const std::vector<const float*>& exact, std::size_t n,
                                 const std::vector<std::vector<glm::vec3>>& first_hit,
                                 const std::array<int, 3>& channel_of_rgb,
                                 const std::vector<float>& area,
                                 const std::vector<double>& light_factor) {
  if (!light_factor.empty() && light_factor.size() != first_hit.size())
    throw Error("light importance", "one factor per light expected");
  if (area.size() != n) throw Error("light importance", "patch areas do not match the matrix size");
  for (int c : channel_of_rgb)
    if (c < 0 || static_cast<std::size_t>(c) >= exact.size())
      throw Error("light importance", "colour channel mapped to a missing matrix");
  std::vector<double> row(area.begin(), area.end());
  normalise(row);
  std::vector<std::vector<double>> column(exact.size(), std::vector<double>(n, 0.0));
  std::vector<std::size_t> lights_used(exact.size(), 0);
  std::vector<double> indirect(n);
  for (std::size_t l = 0; l < first_hit.size(); ++l) {
    const auto& light = first_hit[l];
    const double factor = light_factor.empty() ? 1.0 : light_factor[l];
    if (light.size() != n) throw Error("light importance", "a light vector has the wrong length");
    // |I|^2 of this light over every colour channel: the relative error of
    // the light is measured against it.
    double reference = 0.0;
    for (int k = 0; k < 3; ++k) {
      const float* t = exact[static_cast<std::size_t>(channel_of_rgb[static_cast<std::size_t>(k)])];
#pragma omp parallel for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        double s = 0.0;
        for (std::size_t j = 0; j < n; ++j)
          s += static_cast<double>(t[i * n + j]) * static_cast<double>(light[j][k]);
        indirect[i] = s;
      }
      for (std::size_t i = 0; i < n; ++i) reference += area[i] * indirect[i] * indirect[i];
    }
    if (!(reference > 0.0) || !(factor > 0.0)) continue;
    for (int k = 0; k < 3; ++k) {
      const auto c = static_cast<std::size_t>(channel_of_rgb[static_cast<std::size_t>(k)]);
      for (std::size_t j = 0; j < n; ++j) {
        const double b = light[j][k];
        column[c][j] += factor * b * b / reference;
      }
      ++lights_used[c];
    }
  }
  EntryImportance w;
  w.row = to_float(row);
  for (std::size_t c = 0; c < exact.size(); ++c) {
    std::vector<double>& col = column[c];
    normalise(col);
    if (lights_used[c] == 0) std::fill(col.begin(), col.end(), 1.0);
    for (double& v : col) v = std::max(v, static_cast<double>(kColumnWeightFloor));
    normalise(col);
    w.column.push_back(to_float(col));
  }
  return w;
}

}  // namespace bounce
