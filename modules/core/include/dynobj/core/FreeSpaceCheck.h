// SPDX-License-Identifier: BSD-3-Clause
// Beyond the paper (docs/algorithm.md): a visibility test for moving candidates. The candidate's
// points are carried back into the frame where its sliding window starts (through the same
// accumulated transforms as Eq. 16) and projected with Eq. (1). Where that old frame saw farther
// along the same ray, the space the object occupies now was free then: it moved in. Where the old
// frame saw a surface at the same range, the object was already there: the apparent motion of its
// centroid came from viewpoint changes (the visible faces of a pillar turn as the robot walks by).
#pragma once

#include <algorithm>
#include <deque>
#include <opencv2/core.hpp>
#include <optional>
#include <utility>

#include "dynobj/core/Clusterer.h"
#include "dynobj/core/FrameChain.h"
#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/MovementAnalyzer.h"
#include "dynobj/core/Params.h"
#include "dynobj/core/SphericalProjection.h"

namespace dynobj::core {

struct FreeSpaceParams : public StageParams {
  bool enabled = true;
  double margin = 0.3;  ///< [m] ranges closer than margin + range_factor x range agree
  double range_factor = 0.02;
  double min_free_ratio = 0.5;  ///< free / (free + occupied) needed to stay a moving candidate
  int min_evidence = 3;         ///< fewer decisive points: no verdict ...
  /// ... and then the candidate is not a mover: every candidate must show that the space it
  /// occupies was free (false: only rigid movers and young tracks must; any other candidate is
  /// kept unless the evidence refutes it). Beyond the paper (docs/algorithm.md 7b).
  bool require_proof = true;
  int lookback = 10;  ///< compare with the frame this many frames back (or the oldest kept) ...
  /// ... and, when that refutes a slow candidate, further back, up to this many frames: until it
  /// has moved clear_tolerances x the range tolerance at its range (<= lookback or 0 = off).
  /// Beyond the paper (docs/algorithm.md 7b).
  int max_lookback = 20;
  double clear_tolerances = 2.0;
  double max_travel = 3.0;  ///< [m] ... and only while the sensor moved less than this since then
  /// Frames kept: the most review() may look back.
  int history() const { return std::max(lookback, max_lookback); }
  /// [columns] a point is in free space only if the rays this many columns either side of its own
  /// also passed beyond it: an occluding edge (a shelf's end, a pole) shifts by a fraction of a
  /// column between sweeps, and its own ray then grazes past it (0 = its own ray only). Beyond
  /// the paper (docs/algorithm.md 7b).
  int side_rays = 1;
  /// [rows] ... and only if the rays this many rows above and below it did too: a point lies
  /// between two beams, and where a beam grazes a horizontal surface (a car's roof or bonnet, a
  /// table) the range it meets changes a lot with its elevation; the beam nearest the point then
  /// passes over the surface the point is on (0 = its own row only). Beyond the paper
  /// (docs/algorithm.md 7b).
  int side_rows = 1;
  /// A candidate fewer of whose pixels than this lie on a solid surface (at least half of their
  /// returning 8-neighbours within margin + range_factor x range) is seen through: foliage, not
  /// a mover (0 = off). Beyond the paper (docs/algorithm.md 7b).
  double min_solid_ratio = 0.3;
  /// A rigid cluster moving along its own axis where the viewpoint moved (MovementDecision::slides:
  /// what a wall's visible part does) must show at least this share of free points instead of
  /// min_free_ratio: a see-through fence beside the path slides with the sensor and shows
  /// 0.4-0.67, a car driving along 0.9 (<= min_free_ratio = off). Beyond the paper (7b).
  double slide_free_ratio = 0.75;
  /// [m] a point more than this above a ground return beside it (side_rays, side_rows) is not on
  /// that ground: the ray does not count against it. The row below a car's bumper meets the road
  /// at about the bumper's range; a kerb, lower than this, stays on it. Beyond the paper (7b).
  double clearance = 0.25;
  /// A candidate refuted with a free share below this (and at least min_evidence decisive points)
  /// was clearly there already: a dynamic track is released at once, as at a stop, not held by
  /// hysteresis (MovementDecision::refuted; 0 = off). Beyond the paper (7b).
  double release_free_ratio = 0.05;
  /// For a rigid mover (MovementDecision::rigid), a point its own body covered in the past frame
  /// is no evidence either way: one less than its travel (+ margin) behind its front, along its
  /// motion. A car driving along at 3 m/s covers in a second only 3 m of its 4.4: its rear was
  /// itself then, and counted as a surface already there. Beyond the paper (docs/algorithm.md 7b).
  bool exclude_own_past = true;
  /// A point whose surface the rays do not resolve (resolved(): no ray beside it in its row, or
  /// none in its column, met it) may be thinner than the angle between two rays: a fence's bar or
  /// wire, which a past sweep's rays miss about as often as they hit it. Seen through in the past
  /// frame, such a point is free only where the frames up to this many either side of it saw
  /// through it too; where one of them met it, it is no evidence either way (unknown). A mover is
  /// in none of them; a thin bar is hit in some (0 = the past frame alone). Beyond the paper (7b).
  int thin_frames = 2;

  /// [m] two ranges near `range` agree within this: margin + range_factor x range.
  double tolerance(double range) const { return margin + range_factor * range; }

  void visit(ParamVisitor& v) override;
};

struct FreeSpaceEvidence {
  int free = 0, occupied = 0, unknown = 0;
  /// Not contradicted: enough free evidence, or too little evidence either way.
  bool supportsMotion(const FreeSpaceParams& p, bool slides = false) const;
  /// Positively shown: at least min_evidence decisive points, enough of them free (a share of
  /// min_free_ratio, or of slide_free_ratio for a cluster that `slides`).
  bool provesMotion(const FreeSpaceParams& p, bool slides = false) const;
};

/// Share of `cluster`'s pixels that lie on a solid surface of `frame`'s range image: at least half
/// of their returning 8-neighbours (columns wrap) within margin + range_factor x range. A person or
/// a car is solid but at its outline; porous foliage, seen into and through, is not. A cluster
/// fewer than 3 columns wide has no inside to judge: 1.
double solidRatio(const LidarFrame& frame, const Cluster& cluster, const FreeSpaceParams& p);

class FreeSpaceCheck {
 public:
  explicit FreeSpaceCheck(const FreeSpaceParams& p = {}, std::size_t history = 16);

  /// Keeps this frame's range image (bounded history).
  void remember(long index, const LidarFrame& frame, const cv::Mat_<std::uint8_t>& ground = {});
  /// Evidence for `cluster` (pixels of `frame`, frame index `current`) against frame `past`.
  /// When that gives no verdict and `shift` (the cluster's displacement from `past` to
  /// `current`, in the current frame [m]) is given, the space it left is tested instead: its
  /// points moved back by `shift` should lie where the current frame sees through. An object
  /// moving away from the sensor hid, in the old frame, the space it occupies now; the space it
  /// left is free now.
  /// `ground`: the current frame's ground pixels (clearance, for that second test), if known.
  /// `own_past` (with `shift`): the points the object's own body covered in frame `past` — less
  /// than |shift| (+ margin) behind its front along `shift` — are unknown, not occupied.
  FreeSpaceEvidence evidence(const LidarFrame& frame, long current, const Cluster& cluster,
                             long past, const FrameChain& chain,
                             const std::optional<Eigen::Vector3d>& shift = std::nullopt,
                             const cv::Mat_<std::uint8_t>& ground = {},
                             bool own_past = false) const;
  /// The rule the detector applies to a cluster the movement stage calls moving (`d.moving()`):
  /// sets `d.static_surface` when the space the cluster occupies was not free `lookback` frames
  /// before (or in the oldest frame the chain keeps), nor, for a slow candidate, lookbackFor()
  /// frames before. A rigid mover (a long object exempted from Eq. 23) must prove its motion,
  /// since a background strip framed by moving occluders also "moves" rigidly but no free space
  /// was ever seen where it is; other candidates must only not contradict it. A rigid mover's own
  /// past body is left out of the evidence (exclude_own_past). A plain refutation
  /// (release_free_ratio) also sets `d.refuted`. `dt`: seconds between frames (for the
  /// vacated-space fallback); `ground`: the current frame's ground pixels.
  void review(const LidarFrame& frame, long current, const Cluster& cluster,
              const FrameChain& chain, double dt, MovementDecision& d,
              const cv::Mat_<std::uint8_t>& ground = {}) const;
  const FreeSpaceParams& params() const { return p_; }
  /// How many frames back review() compares `cluster` (a candidate moving at d.velocity):
  /// lookback, or more for a slow one (max_lookback, clear_tolerances).
  long lookbackFor(const Cluster& cluster, const MovementDecision& d, const FrameChain& chain,
                   long current, double dt) const;

  /// The range image of frame `past` and the transform T_{past<-current} of frame `current`'s
  /// points into it, when both are kept and the sizes agree.
  struct PastView {
    const cv::Mat_<float>* ranges = nullptr;
    const cv::Mat_<std::uint8_t>* ground = nullptr;  ///< its ground pixels, if remembered
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  };
  std::optional<PastView> pastView(const LidarFrame& frame, long current, long past,
                                   const FrameChain& chain) const;
  /// Is the surface of `frame`'s pixel `px` resolved: does a ray beside it in its row, and one
  /// in its column, meet it within the tolerance (thin_frames)?
  bool resolved(const LidarFrame& frame, int px) const;
  /// Did that past frame see a surface other than the ground at the current frame's point `p`?
  bool sawSurfaceThen(const PastView& view, const cv::Vec3f& p) const {
    return sawSurfaceIn(*proj_, p_, view, p);
  }
  /// The same for any view (hindsight asks a later frame): did `view`'s range image, projected by
  /// `proj`, see a surface at the point `p` (carried in by view.T) within half of `params`'
  /// tolerance — the same surface, not one a walker passes 0.3 m in front of — at a pixel that
  /// is not the view's ground (the ground under a foot is not it)?
  static bool sawSurfaceIn(const SphericalProjection& proj, const FreeSpaceParams& params,
                           const PastView& view, const cv::Vec3f& p);

 private:
  /// The range the ray test of a point in pixel (r, c) reads from `seen`: its own ray's, unless
  /// that went `through` (beyond the point's range plus tolerance); then the nearest of it and
  /// the returning rays up to side_rays columns beside it and side_rows rows above and below it
  /// (at the point: occupied; nearer: hidden). A `ground` ray beside it (when given) counts only
  /// if the point, `height` [m] up in `seen`'s frame, lies within clearance above its return.
  double rayBeside(const cv::Mat_<float>& seen, int r, int c, double through, double height,
                   const cv::Mat_<std::uint8_t>* ground) const;
  /// Did the range image `seen` meet a surface at `q` (its own frame), within tolerance_scale x
  /// the tolerance, at a pixel that is not `ground` (when given)?
  bool sawSurface(const cv::Mat_<float>& seen, const Eigen::Vector3d& q,
                  double tolerance_scale = 1.0,
                  const cv::Mat_<std::uint8_t>* ground = nullptr) const;
  /// The same with a given projection and tolerance [m].
  static bool surfaceAt(const SphericalProjection& proj, const cv::Mat_<float>& seen,
                        const cv::Mat_<std::uint8_t>* ground, const Eigen::Vector3d& q,
                        double tolerance);

  FreeSpaceParams p_;
  std::size_t history_;
  /// A remembered frame: its index, range image and ground pixels (empty when not given).
  struct Remembered {
    long index = 0;
    cv::Mat_<float> range;
    cv::Mat_<std::uint8_t> ground;
  };
  std::deque<Remembered> frames_;
  std::optional<SphericalProjection> proj_;  ///< Eq. (1) for the remembered frames' sensor
};

}  // namespace dynobj::core
