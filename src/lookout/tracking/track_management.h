#pragma once

// Track management of seed 004 section VII.B, shared by every tracker (the GNN baseline and the
// MHT): a new track is tentative; it is confirmed after one update when both sensors saw the
// object (Detection::sensors == 2) and after three otherwise; a scan without a detection makes
// it coast (prediction only); it is deleted after a number of consecutive misses that depends on
// its class (a tentative track, most likely clutter, goes sooner). Pure functions of a Track's
// counters: the filters (CV Kalman, IMM) are the trackers' business.
//
// Beyond the paper, the camera's evidence against ghosts. The lidar's object source (the grid's
// rigid clusters of dynamic cells) reports, besides road users, ghosts: clusters of static
// structure read as moving, which move steadily for seconds where nothing is, and which a
// tracker confirms like any object seen by one sensor. The camera sees what the lidar sees
// inside its field of view (the two look out from nearly the same place), so a lidar-only
// detection there that the camera does not report is evidence that the object is not a road
// user. Each track carries the log odds L that it is a road user rather than a ghost, from 0
// (even odds) at birth; each detection in the camera's view adds the log likelihood ratio of
// what the camera said:
//   seen:   L += log(P_D / P_G)              P_D: the camera reports a road user in its view
//   unseen: L += log((1 - P_D) / (1 - P_G))  P_G: a camera object lands on a ghost by chance
// clamped to +-existence_log_odds_limit (so that old evidence does not outweigh new for ever);
// a track whose existence probability falls below min_existence_probability is deleted.
// Detections outside the camera's view, and scans without a detection, are no evidence: a
// road user hidden from both sensors says nothing either way.
//
// Beyond the paper too, coasting through occlusion that lasts. A confirmed track that the sensors
// could not see at a scan because something nearer hid it (tracker.h, SensorView: a nearer
// road user, a parked car, a building's corner) is not missed at that scan, as long as its
// prediction is worth something: until it has travelled max_hidden_distance_m unseen, or been
// unseen for max_hidden_s. A walker hidden for four seconds behind a nearer one
// (occluded-pedestrian) was deleted after two, and came back as a new track. Distance rather
// than time: a prediction drifts sideways by its heading's error times the distance (10
// degrees over 12 m: 2.1 m, about the 2 m a track may be off its object and still be it). A
// cyclist passing behind a building at 5 m/s drifted 3.8 m in 3.5 s (intersafe-fig8) while its
// track took the centres of a car's depth; with its own class's (tracking::MeasurementFor),
// 1.7 m in 2.4 s (12 m), and at 16 m it drifted past 2 m and was a false track. Past either
// bound, a track still hidden is lost (deleted): it would only wander where the object is not. A
// track that has left the sensors' view is missed as before: it is leaving the scene. A
// tentative track, most likely clutter, is missed in any case.

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
  // How far, and how long, a hidden confirmed track coasts without misses (above): the hidden
  // walker of occluded-pedestrian goes 5.5 m in its 4.25 s.
  double max_hidden_distance_m = 12.0;
  double max_hidden_s = 5.0;
  // A track is hidden at a scan when less than this fraction of it could be seen although at
  // least this fraction of it lay in the sensors' view (ViewFraction).
  double min_visible_fraction = 0.5;
  // The camera's evidence (above). P_D: the simulated camera misses 5 % of the road users in
  // its view, and fusion can fail to pair a camera object with its lidar object; P_G: a camera
  // object within the gate of a ghost, by chance (its false objects are 0.1 a frame over the
  // whole field of view).
  double camera_detection_probability = 0.9;
  double camera_ghost_probability = 0.05;
  double min_existence_probability = 0.05;
  double existence_log_odds_limit = 5.0;
  // The velocity prior of a new walker's track (zero mean, this sigma per axis): people walk at
  // 1-1.8 m/s and seldom run, where the trackers' general prior (5 m/s, for cars) lets a new
  // walker's track take the first few scans' noise and a group's shifting centroid for 2-3 m/s
  // of speed (docs/risk.md, pushchair-group). 1.5 m/s: a Rayleigh speed prior whose mode is a
  // walking pace, a child running at 3 m/s 2 sigma out.
  double initial_speed_sigma_pedestrian_mps = 1.5;
  // A young track's velocity from its first three seen points (ThreePointVelocity, tracker.h)
  // where their two steps agree at this probability; 0: off.
  double seen_velocity_agreement_probability = 0.99;

  // Throws lookout::InputError naming the first field out of range.
  void Validate(const std::string& source = "track management options") const;
};

// The sigma per axis of a new track's velocity prior for a detection of class `c`: the walker's
// prior for pedestrians, `others_mps` (the tracker's own) for every other class. Pure.
double InitialSpeedSigma(const TrackManagementOptions& options, ObjectClass c, double others_mps);

// The consecutive misses `track` may have before it is deleted.
int MaxMisses(const TrackManagementOptions& options, const Track& track);

// The counters of a track born from `detection` at `stamp` (state, id and filter left to the
// caller): one update, tentative unless one update is enough for this many sensors.
Track BornTrack(const TrackManagementOptions& options, const Detection& detection, TimeNs stamp);

// `track` after the scan at `stamp` that brought it `detection`: one more update, no misses,
// the class learnt if it was unknown, confirmed once it has enough updates.
Track AfterDetection(const TrackManagementOptions& options, Track track, const Detection& detection,
                     TimeNs stamp);

// Whether a track `view` describes was hidden by something nearer (above). Pure.
bool Hidden(const TrackManagementOptions& options, const ViewFraction& view);

// `track` after the scan at `stamp` that brought it nothing: coasting, and one more miss unless
// it is confirmed and was hidden (`view`, SensorView); lost if hidden past the bounds above
// (the speed of `track.state` times the time since its last detection).
Track AfterMiss(const TrackManagementOptions& options, Track track, const ViewFraction& view,
                TimeNs stamp);

// The log odds of existence after the camera's evidence on one detection (above). Pure.
double ExistenceAfter(const TrackManagementOptions& options, double log_odds, CameraEvidence e);

// Whether `track` has been missed too often, lost while hidden, or the camera has spoken against
// it too often, and must go.
bool Expired(const TrackManagementOptions& options, const Track& track);

}  // namespace lookout::tracking
