// SPDX-License-Identifier: BSD-3-Clause
// Beyond the paper, for offline runs (a recording in, labels or a map out): the detector decides
// online, so an object is flagged only once its track has a window of observations (about 0.5 s)
// and, at the start of a recording, never in its first sweeps. An offline run can hold each
// frame's result for `lag` seconds before writing it; once a track has been dynamic for
// `min_dynamic` seconds, its clusters in the held frames before that are flagged too (grown as in
// Eq. 24-25), walking back while the object, seen from each earlier frame, covered the way to
// where it was `speed_window` later at least `min_speed` fast and its cluster was not much larger
// than the object (a walker merged with a bench) and it was not standing there (start_check),
// never over what the newest held frame still sees there (later_surface_check); sweeps where
// its track was not seen take the object's points about where it was, between two sightings
// (fill_gaps) or before its first (fill_before), where nearby held frames saw that place left
// free; before a frame is written, an object that stood there (stop_check) is unflagged.
// lag = 0 is the paper's online behaviour.
// See docs/algorithm.md §9.
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "dynobj/core/FreeSpaceCheck.h"
#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/Params.h"
#include "dynobj/core/RegionGrower.h"
#include "dynobj/core/SphericalProjection.h"

namespace dynobj::core {

struct DetectionResult;
struct TrackedObject;

struct HindsightParams : public StageParams {
  double lag = 1.0;           ///< [s] how long an offline run holds a frame; 0 = online (the paper)
  double min_speed = 0.5;     ///< [m/s] speed from an earlier sweep to the sweep speed_window later
  double speed_window = 0.3;  ///< [s] (0 = to the confirming sweep: an average that reaches back
                              ///< into a rest before the walk)
  double min_dynamic = 0.3;   ///< [s] a track dynamic this long is trusted (one sweep at least)
  /// an earlier sweep is not flagged when the object stood there: on each of the two steps from
  /// the sweeps before it, its speed was below a quarter of its speed to the next sweep that saw
  /// it (a walker who starts just after a sweep; false = flag it)
  bool start_check = true;
  double max_growth = 0.5;  ///< [m] an earlier cluster whose horizontal extent (box diagonal)
                            ///< exceeds 1.5 x the object's by more had merged: stop
  /// a flagged object is unflagged, before its frame is written, when it stood there: on each of
  /// the two steps to the next sweeps that saw it, slower than a quarter of its track's speed (a
  /// walker who stopped just before the sweep; false = keep it flagged)
  bool stop_check = true;
  /// [m/s] stop_check also unflags an object whose two steps out, taken together, moved slower
  /// than this (its centroid's jitter, 0.01-0.05 m per sweep, beats a quarter of a speed that
  /// the track's filter has already let fall after the stop); 0 = only the quarter rule
  double rest_speed = 0.3;
  /// an earlier sweep's region does not take a point that the newest held frame still sees on a
  /// surface (not ground; as [region_growing] past_surface_check, the other way in time), when the
  /// object has since travelled farther than its own extent: someone standing beside a walker
  /// when the recording starts (false = off)
  bool later_surface_check = true;
  /// ... asked point by point, of the cluster's own points too: any point outside the object's
  /// box in the newest held frame (plus [region_growing] distance) that the newest frame sees on
  /// a surface, whatever the object's travel (a walker who passed someone standing when the
  /// recording started, merged with them in one cluster; false = grown
  /// points only, once the object has travelled farther than its extent)
  bool later_surface_points = true;
  /// the way from an earlier sweep (min_speed) counts only along where the track went from
  /// there to the newest sweep: a parked car's centroid drifts sideways as the sensor drives past
  /// and its visible faces turn, before it pulls out (false = the whole way)
  bool way_along = true;
  /// a sweep inside a track's dynamic run where its track was not seen (coasting: its features
  /// fell short) takes the object's points about where it was, between the sightings before and
  /// after, at least min_speed apart, where the nearest held frames by which it had left do not
  /// see a surface there (false = off)
  bool fill_gaps = true;
  /// ... and so do the sweeps before a trusted track was first seen, back from its earliest
  /// sighting at its speed, while each finds the object there and one of those frames sees
  /// through its place (a far walker of a few points a sweep, found only as it nears; false =
  /// off)
  bool fill_before = true;

  void visit(ParamVisitor& v) override;
};

class Hindsight {
 public:
  /// One held frame of one sensor and its result, which revise() may change.
  struct Held {
    const LidarFrame* frame = nullptr;
    DetectionResult* result = nullptr;
  };

  /// `free_space`: its tolerance, for later_surface_check.
  explicit Hindsight(const HindsightParams& p = {}, const RegionGrowingParams& growing = {},
                     const FreeSpaceParams& free_space = {});

  /// `held`: one sensor's held frames, oldest first, the last one just detected. Flags in the
  /// earlier frames the clusters of the tracks whose dynamic run reaches min_dynamic in the last
  /// (see above), or, when `last` (the recording ends there), of every run still shorter; adds
  /// the time taken to the last result's timings. Returns the pixels added.
  long revise(const std::vector<Held>& held, bool last = false);

  /// `held`: one sensor's held frames, oldest first; the oldest is about to be written. Unflags
  /// there the dynamic objects that stood there (stop_check: the two steps to the next sweeps
  /// that see its track, the first of them the next held frame, each slower than a quarter of
  /// its track's speed, or both together slower than rest_speed). Returns the objects unflagged.
  int settle(const std::vector<Held>& held);

  /// Frames a run holds for a sensor at `frequency` [Hz] (0 when lag = 0).
  int heldFrames(double frequency) const;
  const HindsightParams& params() const { return p_; }

 private:
  HindsightParams p_;
  RegionGrower grower_;
  FreeSpaceParams free_space_;
  std::optional<SphericalProjection> proj_;  ///< Eq. (1) for the newest held frame's sensor
  cv::Mat_<int> owner_;
  /// later_surface_check for the growth of `then` at held frame j (T_jk as in movingAt; `here`
  /// its centroid then, in the newest frame's coordinates; `now` the object in the newest held
  /// frame): empty when it does not apply.
  RegionGrower::Admit laterSurfaceTest(const std::vector<Held>& held, std::size_t j,
                                       const TrackedObject& now, const TrackedObject& then,
                                       const Eigen::Vector3d& here, const Eigen::Isometry3d& T_jk);
  /// owner_ sized for `f` and cleared, with the settled objects of `r` (but `except_id`) and the
  /// pixels its region growing refused (`seen_static`) kept out.
  void keepOutSettled(const DetectionResult& r, const LidarFrame& f, int except_id);
  /// start_check for the track's object `then` at held frame j (position `here`, in the newest
  /// frame's coordinates, T_jk their transform into frame j), path_ holding its later positions.
  /// `out_speed`: the fastest speed out of a sweep this revision has met so far [m/s], updated.
  bool movingAt(const std::vector<Held>& held, std::size_t j, const TrackedObject& then,
                const Eigen::Vector3d& here, const Eigen::Isometry3d& T_jk,
                double& out_speed) const;
  /// fill_gaps / fill_before: flags in held frame j, where the track of `o` (the newest frame's
  /// object) was not seen, the points about `at` (the newest frame's coordinates; T_jk as in
  /// movingAt): the non-ground pixels within the object's reach of it, grown as its cluster would
  /// be, and adds the object there (`filled`). Returns the pixels added; 0 (and no change) when
  /// fewer than 2 points lie there, no held frame can judge the place (judgesOf), one refutes it
  /// or, with `need_proof`, none proves it (verdict), or they spread wider than the object + the
  /// growth's step, or are porous. Points a judge sees on a surface are neither seeds nor grown.
  int fillUnseen(const std::vector<Held>& held, std::size_t j, const TrackedObject& o,
                 const Eigen::Vector3d& at, const Eigen::Isometry3d& T_jk, bool need_proof);
  /// fill_gaps for the newest frame's dynamic object `o`: when its track was last seen dynamic
  /// before one or more sweeps where it was not, those sweeps are filled between the two.
  long fillGap(const std::vector<Held>& held, const TrackedObject& o);
  /// fill_gaps / fill_before: the views that judge held frame j's points (T: frame j into the
  /// view's frame): the nearest held frame on either side by which an object moving at `speed`
  /// [m/s] was `clearance` [m] away from there.
  std::vector<FreeSpaceCheck::PastView> judgesOf(const std::vector<Held>& held, std::size_t j,
                                                 double speed, double clearance) const;
  /// Did those views see the place of `pixels` (`f`'s) left free? Refuted when one sees a surface
  /// at half of them or more (a bench beside a cyclist's path); proved when one sees through
  /// half of them or more and none refutes.
  enum class Gone { kRefuted, kUnknown, kProved };
  Gone verdict(const LidarFrame& f, const std::vector<FreeSpaceCheck::PastView>& views,
               const std::vector<int>& pixels);
  /// fill_before: where the track of `o` was at held frame j (the newest frame's coordinates),
  /// back from its earliest place met going back (path_) at its speed out of there; none when
  /// slower than min_speed.
  std::optional<Eigen::Vector3d> backAt(const std::vector<Held>& held, std::size_t j,
                                        const TrackedObject& o) const;
  /// The projection of Eq. (1) for `f`'s sensor.
  const SphericalProjection& projectionFor(const LidarFrame& f);
  /// stop_check for the object `o` of the first held frame, path_ holding where its track was seen
  /// from then on (frames 0, ...; positions in frame 0's coordinates).
  bool stoppedAt(const std::vector<Held>& held, const TrackedObject& o) const;
  std::vector<std::pair<std::size_t, Eigen::Vector3d>> path_;  ///< frame, position
};

}  // namespace dynobj::core
