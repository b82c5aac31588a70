// SPDX-License-Identifier: BSD-3-Clause
// The paper's pipeline (Du & Beltrame, Section III), one LidarFrame at a time, with its state
// (tracks, windows, previous features) kept across frames. See docs/algorithm.md.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "dynobj/core/ClusterAssociator.h"
#include "dynobj/core/Clusterer.h"
#include "dynobj/core/DetectionResult.h"
#include "dynobj/core/EgoMotionEstimator.h"
#include "dynobj/core/EgoMotionRefiner.h"
#include "dynobj/core/ForegroundExtractor.h"
#include "dynobj/core/FrameChain.h"
#include "dynobj/core/FrameCheck.h"
#include "dynobj/core/FreeSpaceCheck.h"
#include "dynobj/core/GroundSegmenter.h"
#include "dynobj/core/Hindsight.h"
#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/MovementAnalyzer.h"
#include "dynobj/core/RegionGrower.h"
#include "dynobj/core/SettledSplit.h"
#include "dynobj/core/StageWorker.h"
#include "dynobj/core/TrackManager.h"

namespace dynobj::core {

/// How the detector runs; no effect on its results (the same masks, byte for byte).
struct PipelineParams : public StageParams {
  /// 1: every stage on the caller's thread. 2: the ego-motion (III-B-1, and its refinement) on a
  /// second thread, beside the ground, foreground and clustering stages, which do not read it.
  int threads = 2;

  void visit(ParamVisitor& v) override;
};

/// Every stage's parameters, one INI section per stage: <prefix><name> for each (name, stage) of
/// forEachStage(), the one list of the sections.
struct DetectorParams {
  ForegroundParams foreground;
  GroundParams ground;
  EgoMotionParams ego_motion;
  EgoRefinementParams ego_refinement;
  ClusteringParams clustering;
  AssociationParams association;
  MovementParams movement;
  FreeSpaceParams free_space;
  TrackingParams tracking;
  RegionGrowingParams region_growing;
  HindsightParams hindsight;  ///< used by offline runs (SequenceRunner), not by the detector
  FrameCheckParams frame_check;
  PipelineParams pipeline;

  /// Calls f(section name, stage parameters) for every stage, in pipeline order.
  template <class F>
  void forEachStage(F&& f) {
    f("foreground", foreground);
    f("ground", ground);
    f("ego_motion", ego_motion);
    f("ego_refinement", ego_refinement);
    f("clustering", clustering);
    f("association", association);
    f("movement", movement);
    f("free_space", free_space);
    f("tracking", tracking);
    f("region_growing", region_growing);
    f("hindsight", hindsight);
    f("frame_check", frame_check);
    f("pipeline", pipeline);
  }
  template <class F>
  void forEachStage(F&& f) const {
    const_cast<DetectorParams*>(this)->forEachStage(
        [&](const char* name, const StageParams& stage) { f(name, stage); });
  }

  void load(const mrpt::config::CConfigFileBase& c, const std::string& prefix = "");
  void save(mrpt::config::CConfigFileBase& c, const std::string& prefix = "") const;
  void validate() const;
};

class DynamicObjectDetector {
 public:
  explicit DynamicObjectDetector(const DetectorParams& params = {});

  /// Processes the next frame. `external_motion`: T_{prev<-cur} from odometry or SLAM, used
  /// instead of the intensity ego-motion. The returned reference is valid until the next call.
  /// Faults of the data (FrameCheck) are in its warnings: a time reversal or a duplicate is not
  /// used for tracking (the result keeps the sweep before's dynamic pixels, and no objects); a
  /// time jump starts the tracks and the motion history anew (track ids go on).
  const DetectionResult& process(
      const LidarFrame& frame,
      const std::optional<Eigen::Isometry3d>& external_motion = std::nullopt);
  void reset();

  const DetectorParams& params() const { return params_; }

 private:
  /// The frame check, then frame index, result and buffers reset for `frame`; returns the seconds
  /// since the last frame, or 0 for a sweep the check skips (its result is then final).
  double beginFrame(const LidarFrame& frame);
  /// A time jump: the tracks (their ids go on), the ego-motion and the frame chain start anew.
  void forgetMotion();
  EgoMotion egoMotion(const LidarFrame& frame, const std::optional<Eigen::Isometry3d>& external);
  /// III-A-2, III-B-1, III-B-2 on two lanes (threads = 2): the normalised intensity and then the
  /// ego-motion on the worker; the masks, the ground, the features and the clusters here.
  void egoMotionBesideClusters(const LidarFrame& frame,
                               const std::optional<Eigen::Isometry3d>& external_motion);
  /// The frame's masks cleared and the ground (III-C-3's stop) found; timed.
  void segmentGround(const LidarFrame& frame);
  /// The stages beside the ego-motion: features (III-A-2, Eq. 2-4), clusters (III-B-2,
  /// Eq. 6-7), each timed.
  void featuresAndClusters(const LidarFrame& frame);
  /// III-C-3, Eq. (24)-(25): the seeds grown into result_.dynamic (owner_); returns the pixels.
  std::vector<int> grow(const LidarFrame& frame, double dt,
                        const std::vector<std::vector<int>>& seeds);
  /// III-B-3: the tracks predicted into this frame (Eq. 8), the clusters associated with them
  /// (Eq. 9-13; the movers first), a cluster holding a mover and an object at rest split
  /// (splitSettled: returned, per cluster), the weak seeds found, the tracks updated.
  std::vector<int> associate(const LidarFrame& frame, double dt);
  /// A dynamic track that found no cluster, expected inside a cluster dropped for its size (a
  /// walker touching a hedge): the dropped features around its prediction whose space the
  /// lookback frame saw free become its cluster.
  void carveMovers(const LidarFrame& frame, const std::vector<Eigen::Vector3d>& predicted,
                   std::vector<int>& cluster_to_track);
  /// Indices of the dynamic tracks that `cluster_to_track` gave no cluster.
  std::vector<std::size_t> unmatchedMovers(const std::vector<int>& cluster_to_track) const;
  /// Beyond the paper (docs/algorithm.md §5): the dynamic tracks that `cluster_to_track` left
  /// without a cluster, associated with the weak clusters (fewer than min_points features) near
  /// their `predicted` centroids by the same gated association: weak_seeds_.
  void findWeakSeeds(const std::vector<Eigen::Vector3d>& predicted,
                     const std::vector<int>& cluster_to_track);
  /// Decides every associated track (movement, free space, hysteresis); the clusters of the
  /// dynamic ones and the weak seeds of coasting dynamic tracks, also marked in result_.seeds
  /// (their track ids in seed_track_). The objects at rest keep their points for the next
  /// sweep's split (rememberShapes, after it).
  std::vector<std::vector<int>> dynamicSeeds(const LidarFrame& frame, double dt);
  using Box2 = std::pair<Eigen::Vector2f, Eigen::Vector2f>;
  /// Beyond the paper (§8, [region_growing] past_surface_check): the test region growing asks of
  /// each pixel beyond the seeds: not a point the lookback frame saw on a surface, for an object
  /// that has travelled farther than its own extent since then. Empty when off or without it.
  /// `boxes`: the horizontal box (low, high corner) of each seed set.
  RegionGrower::Admit pastSurfaceTest(const LidarFrame& frame, double dt,
                                      const std::vector<std::vector<int>>& seeds,
                                      const std::vector<Box2>& boxes) const;
  /// Beyond the paper (§8, [region_growing] nearer_rest_radius): `then`, and a pixel nearer to
  /// the feature points of an object settled at rest beside a seed set than to its seeds (both
  /// within the radius) is refused.
  RegionGrower::Admit nearerTheMover(const LidarFrame& frame,
                                     const std::vector<std::vector<int>>& seeds,
                                     const std::vector<Box2>& boxes,
                                     RegionGrower::Admit then) const;
  /// Objects of the result, history for the next frame.
  void endFrame(const LidarFrame& frame, const std::vector<int>& grown);
  void collectObjects(const LidarFrame& frame, const std::vector<int>& grown);

  DetectorParams params_;
  ForegroundExtractor foreground_;
  GroundSegmenter ground_;
  EgoMotionEstimator ego_;
  EgoMotionRefiner refiner_;
  Clusterer clusterer_;
  ClusterAssociator associator_;
  MovementAnalyzer movement_;
  FreeSpaceCheck free_space_;
  TrackManager tracks_;
  RegionGrower grower_;
  SettledSplitParams split_;
  FrameChain chain_;
  FrameCheck check_;
  StageWorker worker_;  ///< runs egoMotion() ([pipeline] threads)

  DetectionResult result_;
  std::vector<Cluster> clusters_, weak_;  ///< this frame's clusters; weak ones (findWeakSeeds)
  std::vector<int> dropped_;              ///< feature pixels of the clusters dropped for their size
  std::vector<std::pair<int, std::size_t>> weak_seeds_;  ///< (track id, index in weak_)
  cv::Mat_<std::uint8_t> exclude_, prev_dynamic_;
  cv::Mat_<int> owner_;
  std::vector<int> seed_track_;
  std::vector<int> held_;  ///< sorted pixels of resting objects in a mover's cluster (splitSettled)
  long frame_index_ = -1;  ///< of the sweeps used (consecutive in chain_)
  long sweep_ = -1;        ///< of every sweep given to process() (FrameWarning::sweep)
  std::int64_t last_stamp_ = 0;
  Eigen::Isometry3d last_motion_ = Eigen::Isometry3d::Identity();
};

}  // namespace dynobj::core
