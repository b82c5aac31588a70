// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/EgoMotionRefiner.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "dynobj/core/Config.h"
#include "dynobj/core/Se3.h"

namespace dynobj::core {

void EgoRefinementParams::visit(ParamVisitor& v) {
  v.value("enabled", enabled);
  v.value("points", points, {10, 10000000});
  v.value("iterations", iterations, {1, 100});
  v.value("coarse_iterations", coarse_iterations, {0, 100});
  v.value("max_distance", max_distance, kPositive);
  v.value("final_distance", final_distance, kPositive);
  v.value("max_offset", max_offset, {0, 1000});
  v.value("huber", huber, kPositive);
  v.value("damping", damping, {0, 1e6});
  v.value("normal_baseline", normal_baseline, {0, 10});
  v.value("ground_chain", ground_chain, {0, 1000});
  v.value("ground_flatness", ground_flatness, kPositive);
  v.value("min_correspondences", min_correspondences, {6, 10000000});
  v.value("degenerate_share", degenerate_share, {0, 1.0 / 3.0});
  v.value("max_correction", max_correction, kPositive);
  v.degrees("max_correction_angle", max_correction_angle, kPositive);
}

void EgoRefinementParams::validate() const {
  StageParams::validate();
  if (final_distance > max_distance)
    throwParameterError("final_distance", "must not exceed max_distance");
}

namespace {

constexpr std::size_t kCoarseStride = 4;  ///< coarse steps use every 4th sampled point
constexpr std::size_t kAhead = 8;         ///< points between a prefetch and its look-up
/// A normal whose baseline would span more than this azimuth belongs to a point within ~1 m of
/// the sensor (the platform itself, mostly): none is computed there.
constexpr double kMaxNormalSpan = 6.0 * M_PI / 180.0;
}  // namespace

int EgoMotionRefiner::keepFeatureTranslationWhereDegenerate(const Eigen::Matrix<double, 6, 6>& H,
                                                            int partners,
                                                            const Eigen::Isometry3d& init,
                                                            Eigen::Isometry3d& T) const {
  if (p_.degenerate_share <= 0 || partners <= 0) return 0;
  // What the partners tell of the translation once the rotation is free (Schur complement of the
  // rotation block, left-increment coordinates: the previous frame's axes), per partner: a unit
  // normal facing a direction adds 1 along it. Where it is weak, the projective association only
  // pulls the estimate towards no motion (solution remapping, Zhang et al., ICRA 2016).
  const Eigen::Matrix3d S =
      H.block<3, 3>(3, 3) -
      H.block<3, 3>(3, 0) * H.block<3, 3>(0, 0).ldlt().solve(H.block<3, 3>(0, 3));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(S / partners);
  const Eigen::Vector3d change = T.translation() - init.translation();
  Eigen::Vector3d kept = change;
  int weak = 0;
  for (int k = 0; k < 3; k++)
    if (es.eigenvalues()(k) < p_.degenerate_share) {
      const Eigen::Vector3d u = es.eigenvectors().col(k);
      kept -= u * u.dot(change);
      weak++;
    }
  T.translation() = init.translation() + kept;
  return weak;
}

/// Normal of the previous range image at (r, c), or (0,0,0) where there is none. Its first
/// direction joins the returns `k` columns either side, k the fewest columns at least
/// normal_baseline apart, every step between them on the same surface (range jump below
/// 0.1 x range + 0.1 m). Its second joins the rows above and below, on the same surface; on a
/// ground pixel where they are not (a ring gap), the nearest ground returns above and below when
/// they are close and in line with it (ground_chain, ground_flatness).
cv::Vec3f EgoMotionRefiner::normalAt(int r, int c) const {
  const cv::Mat_<float>& range = prev_range_;
  const cv::Mat_<cv::Vec3f>& xyz = prev_xyz_;
  const int rows = range.rows, cols = range.cols;
  const float here = range(r, c);
  if (here <= 0) return {0, 0, 0};
  const float jump = 0.1f * here + 0.1f;
  auto sameSurface = [&](int rr, int cc) {
    const float n = range(rr, cc);
    return n > 0 && std::abs(n - here) <= jump;
  };
  const bool vertical = r > 0 && r < rows - 1 && sameSurface(r - 1, c) && sameSurface(r + 1, c);
  const bool ground = !vertical && !prev_ground_.empty() && prev_ground_(r, c);
  if (!vertical && !ground) return {0, 0, 0};

  const double step = here * 2.0 * M_PI / cols;  // [m] between adjacent columns
  const int k = std::max(1, static_cast<int>(std::ceil(p_.normal_baseline / step)));
  if (k * 2.0 * M_PI / cols > kMaxNormalSpan) return {0, 0, 0};
  for (const int dir : {-1, 1}) {
    float last = here;
    for (int j = 1; j <= k; j++) {
      const float n = range(r, (c + dir * j + cols) % cols);
      if (n <= 0 || std::abs(n - last) > jump) return {0, 0, 0};
      last = n;
    }
  }
  const cv::Vec3f across = xyz(r, (c + k) % cols) - xyz(r, (c + cols - k) % cols);

  cv::Vec3f along;
  if (vertical) {
    along = xyz(r + 1, c) - xyz(r - 1, c);
  } else {  // the ground chain
    int up = r + 1, down = r - 1;
    while (up < rows && !prev_ground_(up, c)) up++;
    while (down >= 0 && !prev_ground_(down, c)) down--;
    const cv::Vec3f a = up < rows ? xyz(up, c) : xyz(r, c);
    const cv::Vec3f b = down >= 0 ? xyz(down, c) : xyz(r, c);
    along = a - b;
    const double len = cv::norm(along);
    if (len < 1e-6 || len > p_.ground_chain) return {0, 0, 0};
    if (up < rows && down >= 0 && cv::norm(along.cross(xyz(r, c) - b)) / len > p_.ground_flatness)
      return {0, 0, 0};  // a kerb or a step between them
  }
  const cv::Vec3f n = across.cross(along);
  const float len = static_cast<float>(cv::norm(n));
  return len > 1e-9f ? n / len : cv::Vec3f(0, 0, 0);
}

void EgoMotionRefiner::prefetchPixel(int r, int c, const cv::Mat_<std::uint8_t>* exclude) const {
  __builtin_prefetch(&prev_normal_known_(r, c));
  __builtin_prefetch(&prev_normal_(r, c));
  __builtin_prefetch(&prev_xyz_(r, c));
  if (r > 0) __builtin_prefetch(&prev_range_(r - 1, c));  // normalAt's rows
  __builtin_prefetch(&prev_range_(r, c));
  if (r + 1 < prev_range_.rows) __builtin_prefetch(&prev_range_(r + 1, c));
  if (exclude) __builtin_prefetch(&(*exclude)(r, c));
}

EgoMotionRefiner::EgoMotionRefiner(const EgoRefinementParams& p) : p_(p) {
  p_.validate();
}

void EgoMotionRefiner::remember(const LidarFrame& f, const cv::Mat_<std::uint8_t>& ground) {
  if (!p_.enabled) return;
  if (p_.ground_chain > 0 && ground.size() == f.range.size())  // only the chain reads it
    ground.copyTo(prev_ground_);
  else
    prev_ground_.release();
  if (!proj_ || proj_->sensor().rows != f.rows() || proj_->sensor().cols != f.cols())
    proj_.emplace(f.sensor);
  f.range.copyTo(prev_range_);
  f.xyz.copyTo(prev_xyz_);
  prev_normal_.create(f.rows(), f.cols());  // left as it is: prev_normal_known_ says what holds
  prev_normal_known_.create(f.rows(), f.cols());
  prev_normal_known_.setTo(0);
  have_prev_ = true;
}

EgoRefinement EgoMotionRefiner::refine(const LidarFrame& f, const Eigen::Isometry3d& init,
                                       const cv::Mat_<std::uint8_t>& exclude_prev) const {
  EgoRefinement out;
  out.motion = init;
  if (!p_.enabled || !have_prev_ || prev_xyz_.size() != f.xyz.size()) return out;
  const bool use_exclude = exclude_prev.size() == f.xyz.size();

  // Evenly spaced valid pixels of the current frame.
  std::vector<Eigen::Vector3d> pts;
  const int n_valid = cv::countNonZero(f.valid);
  const int step = std::max(1, n_valid / p_.points);
  pts.reserve(static_cast<std::size_t>(n_valid / step + 1));
  int skip = 0;  // valid pixels to pass before the next sample (every step-th one is taken)
  for (int r = 0; r < f.rows(); r++) {
    const std::uint8_t* valid = f.valid.ptr<std::uint8_t>(r);
    const cv::Vec3f* xyz = f.xyz.ptr<cv::Vec3f>(r);
    for (int c = 0; c < f.cols(); c++) {
      if (!valid[c] || skip-- > 0) continue;
      pts.emplace_back(xyz[c][0], xyz[c][1], xyz[c][2]);
      skip = step - 1;
    }
  }

  // Each point's partner in the previous frame (its pixel, and there the point and normal, or
  // none): between steps a point mostly projects to the same pixel again, and this short list
  // stays in cache where the previous frame's images (MBs, read at scattered pixels) do not.
  struct Partner {
    int px = -1;      ///< previous frame's pixel, -1 = not looked up yet
    bool ok = false;  ///< a partner with a normal there, not excluded
    cv::Vec3f s, n;   ///< its point and normal
  };
  std::vector<Partner> partners(pts.size());
  std::vector<Eigen::Vector3d> moved(pts.size());       // a step's points in the previous frame ...
  std::vector<int> rows(pts.size()), cols(pts.size());  // ... and their pixels (row -1: none)
  const int W = f.cols();

  Eigen::Isometry3d T = init;
  const int iters = p_.iterations;
  const double offset2 = p_.max_offset * p_.max_offset;
  Eigen::Matrix<double, 6, 6> info = Eigen::Matrix<double, 6, 6>::Zero();  // of the last step
  for (int it = 0; it < iters; it++) {
    const double gate =
        iters == 1 ? p_.max_distance
                   : p_.max_distance + (p_.final_distance - p_.max_distance) * it / (iters - 1);
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
    int n = 0;
    // Coarse to fine: the first steps, which only bring the estimate near, use a quarter of the
    // points (and need a quarter of the partners); the last ones, which set it, use them all.
    const std::size_t stride = it < p_.coarse_iterations ? kCoarseStride : 1;
    const int needed = p_.min_correspondences / static_cast<int>(stride);
    // Every point into the previous frame first, so that the look-ups below can ask the memory
    // for the pixels a few points ahead (scattered over images of several MB).
    for (std::size_t i = 0; i < pts.size(); i += stride) {
      moved[i] = T * pts[i];
      if (!proj_->pixelOf(moved[i].x(), moved[i].y(), moved[i].z(), rows[i], cols[i])) rows[i] = -1;
    }
    for (std::size_t i = 0; i < pts.size(); i += stride) {
      if (const std::size_t j = i + kAhead * stride;
          j < pts.size() && rows[j] >= 0 && partners[j].px != rows[j] * W + cols[j])
        prefetchPixel(rows[j], cols[j], use_exclude ? &exclude_prev : nullptr);
      const Eigen::Vector3d& q = moved[i];
      const int r = rows[i], c = cols[i];
      if (r < 0) continue;
      Partner& pa = partners[i];
      if (pa.px != r * W + c) {
        pa.px = r * W + c;
        pa.ok = false;
        if (use_exclude && exclude_prev(r, c)) continue;
        cv::Vec3f& nv = prev_normal_(r, c);
        if (!prev_normal_known_(r, c)) {
          nv = normalAt(r, c);
          prev_normal_known_(r, c) = 1;
        }
        if (nv[0] == 0 && nv[1] == 0 && nv[2] == 0) continue;
        pa = {pa.px, true, prev_xyz_(r, c), nv};
      }
      if (!pa.ok) continue;
      const cv::Vec3f &sv = pa.s, &nv = pa.n;
      const Eigen::Vector3d s(sv[0], sv[1], sv[2]), nn(nv[0], nv[1], nv[2]);
      const Eigen::Vector3d d = q - s;
      const double e = nn.dot(d);
      if (p_.max_offset > 0 ? std::abs(e) > gate || d.squaredNorm() > offset2
                            : d.squaredNorm() > gate * gate)
        continue;
      const double w = std::abs(e) <= p_.huber ? 1.0 : p_.huber / std::abs(e);
      Eigen::Matrix<double, 6, 1> J;
      J.head<3>() = q.cross(nn);
      J.tail<3>() = nn;
      const Eigen::Matrix<double, 6, 1> wJ = w * J;
      for (int b = 0; b < 6; b++)  // the lower triangle of w J J^T (mirrored after the loop)
        for (int a = b; a < 6; a++) H(a, b) += wJ(a) * J(b);
      g.noalias() += w * e * J;
      n++;
    }
    out.correspondences = n;
    if (n < needed) return out;  // keep init, ok = false
    for (int b = 1; b < 6; b++)
      for (int a = 0; a < b; a++) H(a, b) = H(b, a);
    info = H;
    const double lambda = p_.damping * H.trace() / 6.0;
    H.diagonal().array() += lambda;
    const Eigen::Matrix<double, 6, 1> xi = H.ldlt().solve(-g);
    T = expSE3(xi) * T;
    if (stride == 1 && xi.head<3>().norm() < 1e-6 && xi.tail<3>().norm() < 1e-5) break;
  }
  out.degenerate = keepFeatureTranslationWhereDegenerate(info, out.correspondences, init, T);
  const Eigen::Isometry3d change = init.inverse() * T;
  if (change.translation().norm() > p_.max_correction ||
      Eigen::AngleAxisd(change.linear()).angle() > p_.max_correction_angle)
    return out;
  out.motion = T;
  out.motion.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
  out.ok = true;
  return out;
}

}  // namespace dynobj::core
