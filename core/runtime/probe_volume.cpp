#include "runtime/probe_volume.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "base/error.h"

namespace bounce {

namespace {

constexpr std::size_t kVolumeNumbers = 7;  // two corners and the spacing

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

ProbeVolume parse_volume(const std::string& text, std::size_t index, const char* setting) {
  const std::string where = std::string("setting '") + setting + "'";
  const std::string which = "volume " + std::to_string(index + 1) + " ('" + text + "')";
  const std::vector<std::string> parts = split(text, ',');
  if (parts.size() != kVolumeNumbers)
    throw Error(where, which + " has " + std::to_string(parts.size()) +
                           " numbers; a volume is x0,y0,z0,x1,y1,z1,spacing");
  float v[kVolumeNumbers];
  for (std::size_t i = 0; i < kVolumeNumbers; ++i) {
    const std::string p = trimmed(parts[i]);
    const auto [end, ec] = std::from_chars(p.data(), p.data() + p.size(), v[i]);
    if (p.empty() || ec != std::errc() || end != p.data() + p.size() || !std::isfinite(v[i]))
      throw Error(where, which + ": '" + p + "' is not a finite number");
  }
  ProbeVolume volume{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6]};
  for (int a = 0; a < 3; ++a)
    if (!(volume.lo[a] < volume.hi[a]))
      throw Error(where, which + ": its first corner must be below its second on every axis");
  if (!(volume.spacing > 0.0f))
    throw Error(where, which + ": the spacing must be positive, got " + trimmed(parts[6]));
  return volume;
}

int points_along(float extent, float spacing) {
  return static_cast<int>(std::floor(static_cast<double>(extent) / spacing)) + 1;
}

}  // namespace

TransferGrid volume_lattice(const ProbeVolume& volume) {
  TransferGrid g;
  g.cell_size = volume.spacing;
  const glm::vec3 extent = volume.hi - volume.lo;
  for (int a = 0; a < 3; ++a) {
    g.dims[a] = points_along(extent[a], volume.spacing);
    // Centred: the slack the whole spacings leave is split on both sides.
    const float slack = extent[a] - static_cast<float>(g.dims[a] - 1) * volume.spacing;
    g.origin[a] = volume.lo[a] + 0.5f * slack - 0.5f * volume.spacing;
  }
  return g;
}

double volume_point_count(const ProbeVolume& volume) {
  double n = 1.0;
  for (int a = 0; a < 3; ++a)
    n *= std::floor(static_cast<double>(volume.hi[a] - volume.lo[a]) / volume.spacing) + 1.0;
  return n;
}

std::vector<ProbeVolume> parse_probe_volumes(const std::string& text, const char* setting) {
  std::vector<ProbeVolume> volumes;
  if (trimmed(text).empty()) return volumes;
  const std::vector<std::string> parts = split(text, ';');
  for (std::size_t i = 0; i < parts.size(); ++i)
    volumes.push_back(parse_volume(parts[i], i, setting));
  return volumes;
}

std::string probe_volumes_text(const std::vector<ProbeVolume>& volumes) {
  std::string out;
  for (const ProbeVolume& v : volumes) {
    if (!out.empty()) out += ';';
    const float numbers[kVolumeNumbers] = {v.lo.x, v.lo.y, v.lo.z,   v.hi.x,
                                           v.hi.y, v.hi.z, v.spacing};
    for (std::size_t i = 0; i < kVolumeNumbers; ++i) {
      char buffer[32];
      const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, numbers[i]);
      if (i > 0) out += ',';
      out.append(buffer, end);
    }
  }
  return out;
}

}  // namespace bounce
