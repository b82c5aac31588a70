// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/EgoMotionCheck.h"

#include <dynobj/mrptio/PoseConversion.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPose3DPDF.h>
#include <mrpt/slam/CICP.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unordered_set>

#include "dynobj/eval/EgoMotionError.h"

namespace dynobj::eval {
namespace {

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

struct EgoMotionCheck::Impl {
  double voxel;
  mrpt::slam::CICP icp;
  std::unique_ptr<mrpt::maps::CSimplePointsMap> previous;
  Eigen::Isometry3d velocity = Eigen::Isometry3d::Identity();  ///< ICP's last motion (the seed)
  bool first_pair = true;

  /// One point per voxel (the first met), valid pixels only.
  std::unique_ptr<mrpt::maps::CSimplePointsMap> thin(const core::LidarFrame& f) const {
    auto map = std::make_unique<mrpt::maps::CSimplePointsMap>();
    std::unordered_set<std::uint64_t> seen;
    for (int r = 0; r < f.rows(); r++)
      for (int c = 0; c < f.cols(); c++) {
        if (!f.isValid(r, c)) continue;
        const cv::Vec3f& p = f.xyz(r, c);
        auto key = [&](float v) {
          return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v / voxel)) &
                                            0x1FFFFF);
        };
        if (seen.insert(key(p[0]) | key(p[1]) << 21 | key(p[2]) << 42).second)
          map->insertPointFast(p[0], p[1], p[2]);
      }
    return map;
  }
};

EgoMotionCheck::EgoMotionCheck(double voxel) : impl_(std::make_unique<Impl>()) {
  impl_->voxel = voxel;
  auto& o = impl_->icp.options;
  o.maxIterations = 100;
  o.thresholdDist = 1.0;  // [m] first correspondence gate, shrunk by ALFA down to ...
  o.thresholdAng = 0.0;
  o.ALFA = 0.5;
  o.smallestThresholdDist = 0.2;  // ... 20 cm (the clouds are thinned to voxel-size spacing)
  o.onlyUniqueRobust = false;
  o.doRANSAC = false;
}

EgoMotionCheck::~EgoMotionCheck() = default;

void EgoMotionCheck::add(const core::LidarFrame& frame, const core::EgoMotion& ego) {
  auto current = impl_->thin(frame);
  if (!impl_->previous) {
    impl_->previous = std::move(current);
    return;
  }
  EgoMotionAgreement& s = summary_;
  s.pairs++;
  if (ego.ok) s.ego_ok++;
  // Seed: ICP's own previous motion (constant velocity); a wide first gate on the first pair.
  impl_->icp.options.thresholdDist = impl_->first_pair ? 2.0 : 1.0;
  mrpt::slam::CICP::TReturnInfo info;
  const auto pdf = impl_->icp.Align3D(impl_->previous.get(), current.get(),
                                      mrptio::toCPose3D(impl_->velocity), info);
  const bool icp_ok = pdf && info.goodness >= 0.3;
  if (icp_ok) {
    const Eigen::Isometry3d icp_motion = mrptio::toIsometry(pdf->getMeanVal());
    impl_->velocity = icp_motion;
    impl_->first_pair = false;
    s.icp_ok++;
    s.icp_speed.push_back(icp_motion.translation().norm());
    if (ego.ok) {
      const auto [dt, dr] = motionDifference(icp_motion, ego.motion);
      s.compared++;
      s.translation_diff.push_back(dt);
      s.rotation_diff.push_back(dr);
      if (dt <= s.max_translation && dr <= s.max_rotation) s.agree++;
    }
  }
  impl_->previous = std::move(current);
}

std::string EgoMotionAgreement::toString() const {
  char buf[512];
  const auto pct = [](int a, int b) { return b > 0 ? 100.0 * a / b : 0.0; };
  std::snprintf(buf, sizeof buf,
                "ego-motion succeeded on %d of %d pairs (%.1f %%); ICP registered %d; both: %d, "
                "agree within %.2f m / %.1f deg on %d (%.1f %%); difference translation median "
                "%.3f m p95 %.3f m, rotation median %.3f deg p95 %.3f deg; ICP speed median "
                "%.2f m/frame",
                ego_ok, pairs, pct(ego_ok, pairs), icp_ok, compared, max_translation, max_rotation,
                agree, pct(agree, compared), quantile(translation_diff, 0.5),
                quantile(translation_diff, 0.95), quantile(rotation_diff, 0.5),
                quantile(rotation_diff, 0.95), quantile(icp_speed, 0.5));
  return buf;
}

}  // namespace dynobj::eval
