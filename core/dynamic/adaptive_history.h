#pragma once
// How many past frames a temporal estimate keeps averaging after the light
// changed. The history counts k frames (a real number): the new frame's
// estimate gets weight 1 / (k + 1), the history k / (k + 1) -- a running mean
// while k grows by one per frame, capped at `max_frames` (then an
// exponential blend of weight max_frames / (max_frames + 1)). A change of
// relative size `change` (dynamic/light_temporal_radiosity.h: an upper bound
// of the relative L1 change of T b) multiplies the history's weight by
//   keep = max(0, 1 - change / change_scale),
// so the share of light from before the change in the next result is at
// most keep, and its error there at most change * keep <= change_scale / 4
// of the light (the ghosting bound; a change of change_scale or more is
// forgotten at once). For a light that moves by `change` every frame, the
// history settles near change_scale / change frames: the faster the light,
// the shorter the history.
#include <cmath>

namespace bounce {

struct AdaptiveHistorySettings {
  double change_scale = 0.25;  // a relative change this large drops the history
  int max_frames = 64;
};

// k after a change (0 <= change; any k >= 0): the k' whose weight
// k' / (k' + 1) is keep * k / (k + 1).
inline double history_frames_after_change(double frames, double change, double change_scale) {
  if (!(change > 0.0)) return frames;
  const double keep = 1.0 - change / change_scale;
  if (!(keep > 0.0)) return 0.0;
  const double weight = keep * frames / (frames + 1.0);
  return weight / (1.0 - weight);
}

// The weight of the history when it averages `frames` frames.
inline float history_weight(double frames) { return static_cast<float>(frames / (frames + 1.0)); }

// The ghosting bound above: the largest error, relative to the light, that
// the light from before a change of size `change` can leave in the next
// result.
inline double ghosting_bound(double change, double change_scale) {
  const double keep = 1.0 - change / change_scale;
  return keep > 0.0 ? change * keep : 0.0;
}

}  // namespace bounce
