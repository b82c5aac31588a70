// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/sim/TopView.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace dynobj::sim {

cv::Mat topView(const SimulatedSweep& sw, const std::vector<Eigen::Vector3d>& path,
                double metres_per_pixel, double half_extent) {
  const int n = static_cast<int>(std::ceil(2 * half_extent / metres_per_pixel));
  cv::Mat img(n, n, CV_8UC3, cv::Scalar(0, 0, 0));
  const Eigen::Vector3d o = sw.sensor_pose.translation();
  auto pixel = [&](const Eigen::Vector3d& p, cv::Point& px) {
    px.x = static_cast<int>(std::floor((p.x() - o.x() + half_extent) / metres_per_pixel));
    px.y = static_cast<int>(std::floor((o.y() - p.y() + half_extent) / metres_per_pixel));
    return px.x >= 0 && px.y >= 0 && px.x < n && px.y < n;
  };
  cv::Point px;
  for (int pass = 0; pass < 2; pass++)  // actors drawn last, over the static scene
    for (int r = 0; r < sw.frame.rows(); r++)
      for (int c = 0; c < sw.frame.cols(); c++) {
        if (!sw.frame.isValid(r, c)) continue;
        const bool actor = sw.actor(r, c) >= 0;
        if (actor != (pass == 1)) continue;
        const cv::Vec3f q = sw.frame.xyz(r, c);
        const Eigen::Vector3d p = sw.sensor_pose * Eigen::Vector3d(q[0], q[1], q[2]);
        if (!pixel(p, px)) continue;
        if (sw.dynamic(r, c)) {
          cv::circle(img, px, 1, cv::Scalar(40, 40, 255), cv::FILLED);
        } else if (actor) {
          cv::circle(img, px, 1, cv::Scalar(255, 160, 40), cv::FILLED);
        } else {
          const auto g = static_cast<std::uint8_t>(std::clamp(70.0 + 40.0 * p.z(), 60.0, 255.0));
          auto& v = img.at<cv::Vec3b>(px);
          v = cv::Vec3b(std::max(v[0], g), std::max(v[1], g), std::max(v[2], g));
        }
      }
  for (const Eigen::Vector3d& p : path)
    if (pixel(p, px)) cv::circle(img, px, 1, cv::Scalar(60, 220, 60), cv::FILLED);
  if (pixel(o, px)) cv::circle(img, px, 4, cv::Scalar(60, 255, 60), 2);
  return img;
}

}  // namespace dynobj::sim
