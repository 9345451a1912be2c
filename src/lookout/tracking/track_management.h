#pragma once

// Track management of seed 004 section VII.B, shared by every tracker (the GNN baseline and the
// MHT): a new track is tentative; it is confirmed after one update when both sensors saw the
// object (Detection::sensors == 2) and after three otherwise; a scan without a detection makes
// it coast (prediction only); it is deleted after a number of consecutive misses that depends on
// its class (a tentative track, most likely clutter, goes sooner). Pure functions of a Track's
// counters: the filters (CV Kalman, IMM) are the trackers' business.

#include <string>

#include "lookout/core/time.h"
#include "lookout/tracking/tracker.h"

namespace lookout::tracking {

struct TrackManagementOptions {
  int confirm_updates_one_sensor = 3;
  int confirm_updates_two_sensors = 1;
  // Consecutive misses before deletion: a pedestrian hidden behind a car may reappear after
  // a second or two; an unknown object that stops being seen was most likely clutter.
  int max_misses_pedestrian = 25;
  int max_misses_cyclist = 20;
  int max_misses_vehicle = 20;
  int max_misses_unknown = 5;
  int max_misses_tentative = 2;

  // Throws lookout::InputError naming the first field out of range.
  void Validate(const std::string& source = "track management options") const;
};

// The consecutive misses `track` may have before it is deleted.
int MaxMisses(const TrackManagementOptions& options, const Track& track);

// The counters of a track born from `detection` at `stamp` (state, id and filter left to the
// caller): one update, tentative unless one update is enough for this many sensors.
Track BornTrack(const TrackManagementOptions& options, const Detection& detection, TimeNs stamp);

// `track` after a scan that brought it `detection`: one more update, no misses, the class
// learnt if it was unknown, confirmed once it has enough updates.
Track AfterDetection(const TrackManagementOptions& options, Track track,
                     const Detection& detection);

// `track` after a scan that brought it nothing: coasting, one more miss.
Track AfterMiss(Track track);

// Whether `track` has been missed too often and must go.
inline bool Expired(const TrackManagementOptions& options, const Track& track) {
  return track.misses > MaxMisses(options, track);
}

}  // namespace lookout::tracking
