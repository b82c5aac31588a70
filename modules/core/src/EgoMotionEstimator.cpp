// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/EgoMotionEstimator.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <opencv2/core/hal/hal.hpp>
#include <opencv2/imgproc.hpp>

#include "dynobj/core/Config.h"
#include "dynobj/core/MotionFromMatches.h"

namespace dynobj::core {
namespace {

/// ORB runs twice on one padded image (wrapped left/right, the 360 degree scan; reflected at the
/// top and bottom). Its keypoints come from a view with kFastMargin pixels of surroundings: FAST
/// needs 3 px around a pixel and its non-maximum suppression the scores one pixel further, and it
/// scans the whole view it is given, so a wider margin is only wasted work (64 rows + 2 x 16 cost
/// a third more). The descriptors come from a view with kMargin pixels of surroundings, because
/// ORB blurs only the view it is given before sampling its 31 px patches (up to 22 px from a
/// keypoint once rotated): the keypoints, their Harris scores and orientations, and the
/// descriptors are those of one call on the kMargin view, byte for byte.
constexpr int kMargin = 16;     ///< describing ORB's edgeThreshold; >= its half patch size (15)
constexpr int kFastMargin = 4;  ///< detecting ORB's edgeThreshold: FAST's 3 px + 1 for its NMS
constexpr int kPad = kMargin + kMargin + 1;  ///< + ORB's own border (edgeThreshold + 1)

/// J_u J_u^T + J_v J_v^T at pixel (r, c): J the point's step to the next pixel across the scan
/// (columns, wrapping) and along it (rows), from the neighbours on the same surface (range within
/// 10 % + 0.1 m), half the span when both are; zero in a direction with neither.
Eigen::Matrix3d pixelSpread(const LidarFrame& f, int r, int c) {
  const float here = f.range(r, c);
  const float jump = 0.1f * here + 0.1f;
  const cv::Vec3f& p = f.xyz(r, c);
  auto on = [&](int rr, int cc) {
    return rr >= 0 && rr < f.rows() && f.isValid(rr, cc) &&
           std::abs(f.range(rr, cc) - here) <= jump;
  };
  auto step = [&](int ra, int ca, int rb, int cb) -> Eigen::Vector3d {
    const bool a = on(ra, ca), b = on(rb, cb);
    cv::Vec3f d(0, 0, 0);
    if (a && b)
      d = 0.5f * (f.xyz(rb, cb) - f.xyz(ra, ca));
    else if (a)
      d = p - f.xyz(ra, ca);
    else if (b)
      d = f.xyz(rb, cb) - p;
    return {d[0], d[1], d[2]};
  };
  const int W = f.cols();
  const Eigen::Vector3d ju = step(r, (c + W - 1) % W, r, (c + 1) % W);
  const Eigen::Vector3d jv = step(r - 1, c, r + 1, c);
  return ju * ju.transpose() + jv * jv.transpose();
}

/// Hamming distance of two 32-byte ORB descriptors, inline: cv::hal::normHamming is an
/// out-of-line dispatched call, slow on the ~90,000 short pairs a frame compares. Inlined into
/// bestTwo(), of which GCC builds a POPCNT clone (every x86-64 CPU since 2008) picked at load time.
inline int hamming256(const std::uint8_t* a, const std::uint8_t* b) {
  int d = 0;
  for (int k = 0; k < 32; k += 8) {
    std::uint64_t x, y;
    std::memcpy(&x, a + k, 8);
    std::memcpy(&y, b + k, 8);
    d += __builtin_popcountll(x ^ y);
  }
  return d;
}

/// The nearest and second-nearest of the candidate rows `js` of `prev` to descriptor `a`
/// (Hamming distance): best = its row (-1 when none), d1 <= d2 their distances.
/// No clones under ThreadSanitizer: GCC instruments the clones' ifunc resolver (a call to
/// __tsan_func_entry), which the dynamic loader runs while relocating this library, before the
/// TSan runtime is set up: a crash before main (docs/performance.md, "Sanitizers").
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__)
__attribute__((target_clones("popcnt", "default")))
#endif
void bestTwo(const std::uint8_t* a, const cv::Mat& prev, const std::vector<int>& js, int& best,
             int& d1, int& d2) {
  const int bytes = prev.cols;
  for (int j : js) {
    const std::uint8_t* b = prev.ptr<std::uint8_t>(j);
    const int d = bytes == 32 ? hamming256(a, b) : cv::hal::normHamming(a, b, bytes);
    if (d < d1) {
      d2 = d1;
      d1 = d;
      best = j;
    } else if (d < d2) {
      d2 = d;
    }
  }
}

}  // namespace

void EgoMotionParams::visit(ParamVisitor& v) {
  v.value("features", features, {10, 100000});
  v.value("scale_factor", scale_factor, {1.01, 4});
  v.value("levels", levels, {1, 8});
  v.value("fast_threshold", fast_threshold, {1, 255});
  v.value("ratio", ratio, {0.1, 1.0});
  v.value("match_window", match_window, {0, 100000});
  v.value("border", border, {0, 20});
  v.value("inlier_distance", inlier_distance, kPositive);
  v.value("inlier_range_factor", inlier_range_factor, {0, 1});
  v.value("pixel_spread", pixel_spread, {0, 100});
  v.value("still_match_pixels", still_match_pixels, {0, 1000});
  v.value("iterations", iterations, {1, 100000});
  v.value("confidence", confidence, {0.5, 1});
  v.value("refinements", refinements, {0, 100});
  v.value("min_inliers", min_inliers, {3, 100000});
  v.value("min_inlier_ratio", min_inlier_ratio, {0, 1});
  v.value("seed", seed);
}

EgoMotionEstimator::EgoMotionEstimator(const EgoMotionParams& p)
    : p_(p), matcher_(cv::NORM_HAMMING), rng_(static_cast<unsigned>(p.seed)) {
  p_.validate();
  const auto orb = [&](int edge) {
    return cv::ORB::create(p_.features, static_cast<float>(p_.scale_factor), p_.levels, edge, 0, 2,
                           cv::ORB::HARRIS_SCORE, 31, p_.fast_threshold);
  };
  detector_ = orb(kFastMargin);
  describer_ = orb(kMargin);
}

void EgoMotionEstimator::reset() {
  have_prev_ = false;
  prev_ = Features{};
  rng_.seed(static_cast<unsigned>(p_.seed));
}

void EgoMotionEstimator::detect(const LidarFrame& f, const cv::Mat_<float>& intensity,
                                const cv::Mat_<std::uint8_t>& exclude, Features& out) {
  const int H = f.rows(), W = f.cols();
  intensity.convertTo(img8_, CV_8U);
  // A no-return between returns above and below (a dropout along a row) is filled with their
  // mean and does not count as a border: keypoints only on returns at least `border` px away
  // from any other no-return, and off `exclude`.
  cv::morphologyEx(f.valid, filled_, cv::MORPH_CLOSE,
                   cv::getStructuringElement(cv::MORPH_RECT, {1, 3}));
  for (int r = 1; r + 1 < H; r++)
    for (int c = 0; c < W; c++)
      if (filled_(r, c) && !f.valid(r, c))
        img8_.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(
            (img8_.at<std::uint8_t>(r - 1, c) + img8_.at<std::uint8_t>(r + 1, c) + 1) / 2);
  if (p_.border > 0)
    cv::erode(filled_, mask_,
              cv::getStructuringElement(cv::MORPH_RECT, {2 * p_.border + 1, 2 * p_.border + 1}));
  else
    filled_.copyTo(mask_);
  if (!exclude.empty()) mask_.setTo(0, exclude);
  // Room for ORB's margin, patch and border: wrap left/right (360 deg scan), reflect top/bottom.
  cv::Mat tmp;
  cv::copyMakeBorder(img8_, tmp, kPad, kPad, 0, 0, cv::BORDER_REFLECT_101);
  cv::copyMakeBorder(tmp, padded_, 0, 0, kPad, kPad, cv::BORDER_WRAP);
  cv::copyMakeBorder(mask_, mask_pad_, kPad, kPad, kPad, kPad, cv::BORDER_CONSTANT, 0);
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  const auto view = [&](int m) { return cv::Rect(kPad - m, kPad - m, W + 2 * m, H + 2 * m); };
  detector_->detect(padded_(view(kFastMargin)), kps, mask_pad_(view(kFastMargin)));
  for (cv::KeyPoint& k : kps) k.pt += cv::Point2f(kMargin - kFastMargin, kMargin - kFastMargin);
  describer_->compute(padded_(view(kMargin)), kps, desc);
  out.points.clear();
  out.pixels.clear();
  out.spread.clear();
  out.descriptors.release();
  std::vector<int> keep;
  for (std::size_t i = 0; i < kps.size(); i++) {
    const int c = static_cast<int>(std::lround(kps[i].pt.x - kMargin));
    const int r = static_cast<int>(std::floor(kps[i].pt.y - kMargin));
    if (r < 0 || r >= H || c < 0 || c >= W || !f.isValid(r, c)) continue;
    const cv::Vec3f& p = f.xyz(r, c);
    out.points.emplace_back(p[0], p[1], p[2]);
    out.pixels.push_back(r * W + c);
    if (p_.pixel_spread > 0) out.spread.push_back(pixelSpread(f, r, c));
    keep.push_back(static_cast<int>(i));
  }
  out.descriptors.create(static_cast<int>(keep.size()), desc.cols, desc.type());
  for (std::size_t k = 0; k < keep.size(); k++)
    desc.row(keep[k]).copyTo(out.descriptors.row(static_cast<int>(k)));
}

EgoMotion EgoMotionEstimator::estimate(const LidarFrame& frame, const cv::Mat_<float>& intensity,
                                       const cv::Mat_<std::uint8_t>& exclude) {
  EgoMotion em;
  detect(frame, intensity, exclude, cur_);
  pitch_ = {2 * M_PI / frame.cols(),
            frame.rows() > 1 ? frame.sensor.fovSpan() / (frame.rows() - 1) : 0.0};
  if (have_prev_ && !prev_.descriptors.empty() && !cur_.descriptors.empty()) {
    std::vector<std::pair<int, int>> pairs;
    match(frame.cols(), p_.match_window, pairs);
    solve(pairs, em);
    if (!em.ok && p_.match_window > 0) {  // a fast turn: search every pair before giving up
      match(frame.cols(), 0, pairs);
      solve(pairs, em);
    }
  }
  std::swap(prev_, cur_);
  have_prev_ = true;
  return em;
}

void EgoMotionEstimator::match(int cols, int window, std::vector<std::pair<int, int>>& out) {
  out.clear();
  if (window <= 0) {
    std::vector<std::vector<cv::DMatch>> knn;
    matcher_.knnMatch(cur_.descriptors, prev_.descriptors, knn, 2);
    for (const auto& m : knn)
      if (m.size() == 2 && m[0].distance <= p_.ratio * m[1].distance)
        out.emplace_back(m[0].queryIdx, m[0].trainIdx);
    return;
  }
  // Previous keypoints bucketed by column; each current keypoint is compared with the buckets
  // within `window` columns (wrapping around the 360 degree seam).
  constexpr int kBucket = 16;
  const int nb = (cols + kBucket - 1) / kBucket, reach = (window + kBucket - 1) / kBucket;
  buckets_.assign(static_cast<std::size_t>(nb), {});
  for (std::size_t j = 0; j < prev_.pixels.size(); j++)
    buckets_[static_cast<std::size_t>((prev_.pixels[j] % cols) / kBucket)].push_back(
        static_cast<int>(j));
  for (int i = 0; i < cur_.descriptors.rows; i++) {
    const std::uint8_t* a = cur_.descriptors.ptr<std::uint8_t>(i);
    const int b0 = (cur_.pixels[static_cast<std::size_t>(i)] % cols) / kBucket;
    int best = -1, d1 = 1 << 30, d2 = 1 << 30;
    const int span = std::min(nb, 2 * reach + 1);  // distinct buckets, even when they wrap
    for (int k = 0; k < span; k++)
      bestTwo(a, prev_.descriptors,
              buckets_[static_cast<std::size_t>(((b0 - reach + k) % nb + nb) % nb)], best, d1, d2);
    if (best >= 0 && d2 < (1 << 30) && d1 <= p_.ratio * d2) out.emplace_back(i, best);
  }
}

void EgoMotionEstimator::solve(const std::vector<std::pair<int, int>>& pairs, EgoMotion& em) {
  matches_.resize(pairs.size());
  for (std::size_t m = 0; m < pairs.size(); m++) {
    const auto i = static_cast<std::size_t>(pairs[m].first);
    const auto j = static_cast<std::size_t>(pairs[m].second);
    PointMatch& pm = matches_[m];
    pm.cur = {cur_.points[i].x, cur_.points[i].y, cur_.points[i].z};
    pm.prev = {prev_.points[j].x, prev_.points[j].y, prev_.points[j].z};
    pm.spread = p_.pixel_spread > 0 ? Eigen::Matrix3d(cur_.spread[i] + prev_.spread[j])
                                    : Eigen::Matrix3d::Zero();
    pm.still = cur_.pixels[i] == prev_.pixels[j];
  }
  em = motionFromMatches(matches_, p_, pitch_, rng_);
}

void EgoMotionEstimator::dropPreviousOn(const cv::Mat_<std::uint8_t>& dynamic) {
  if (!have_prev_ || dynamic.empty() || prev_.pixels.empty()) return;
  const std::uint8_t* d = dynamic.ptr<std::uint8_t>(0);
  cv::Mat& desc = prev_.descriptors;  // its own buffer (detect() allocates a new one per frame)
  const std::size_t row_bytes = desc.cols * desc.elemSize();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < prev_.pixels.size(); i++) {
    if (d[prev_.pixels[i]]) continue;
    if (kept != i) {  // compact in place, keeping the order
      prev_.points[kept] = prev_.points[i];
      prev_.pixels[kept] = prev_.pixels[i];
      if (!prev_.spread.empty()) prev_.spread[kept] = prev_.spread[i];
      std::memcpy(desc.ptr(static_cast<int>(kept)), desc.ptr(static_cast<int>(i)), row_bytes);
    }
    kept++;
  }
  if (kept == prev_.pixels.size()) return;
  prev_.points.resize(kept);
  prev_.pixels.resize(kept);
  if (!prev_.spread.empty()) prev_.spread.resize(kept);
  desc = desc.rowRange(0, static_cast<int>(kept));
}

}  // namespace dynobj::core
