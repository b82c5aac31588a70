// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/TopDownImage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace dynobj::mapclean {

TopDownView TopDownView::fit(const std::vector<MapPoint>& a, const std::vector<MapPoint>& b,
                             double resolution, int max_pixels) {
  TopDownView v;
  double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  double hi[2] = {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  std::vector<float> z;
  z.reserve(a.size() + b.size());
  for (const auto* set : {&a, &b})
    for (const MapPoint& p : *set) {
      lo[0] = std::min(lo[0], double{p.x});
      lo[1] = std::min(lo[1], double{p.y});
      hi[0] = std::max(hi[0], double{p.x});
      hi[1] = std::max(hi[1], double{p.y});
      z.push_back(p.z);
    }
  if (z.empty()) {
    lo[0] = lo[1] = -1;
    hi[0] = hi[1] = 1;
    z.push_back(0.f);
  }
  const double margin = 1.0;
  v.min_x = lo[0] - margin;
  v.min_y = lo[1] - margin;
  const double w = hi[0] - lo[0] + 2 * margin, h = hi[1] - lo[1] + 2 * margin;
  v.resolution = std::max(resolution, std::max(w, h) / max_pixels);
  v.width = static_cast<int>(std::ceil(w / v.resolution));
  v.height = static_cast<int>(std::ceil(h / v.resolution));
  const auto k = z.size() / 50;
  std::nth_element(z.begin(), z.begin() + static_cast<std::ptrdiff_t>(k), z.end());
  v.z_ground = z[k];
  return v;
}

cv::Mat renderTopDown(const TopDownView& view, const std::vector<MapPoint>& static_points,
                      const std::vector<MapPoint>& dynamic_points, int dynamic_radius) {
  cv::Mat_<float> top(view.height, view.width, std::numeric_limits<float>::lowest());
  cv::Mat_<std::uint8_t> dyn(view.height, view.width, std::uint8_t{0});
  const auto cell = [&view](const MapPoint& p, int& r, int& c) {
    c = static_cast<int>(std::floor((p.x - view.min_x) / view.resolution));
    r = view.height - 1 - static_cast<int>(std::floor((p.y - view.min_y) / view.resolution));
    return r >= 0 && r < view.height && c >= 0 && c < view.width;
  };
  int r = 0, c = 0;
  for (const MapPoint& p : static_points)
    if (cell(p, r, c)) top(r, c) = std::max(top(r, c), p.z);
  for (const MapPoint& p : dynamic_points)
    if (cell(p, r, c)) dyn(r, c) = 255;
  cv::Mat img(view.height, view.width, CV_8UC3, cv::Scalar(0, 0, 0));
  for (r = 0; r < view.height; r++)
    for (c = 0; c < view.width; c++) {
      if (dyn(r, c)) {
        img.at<cv::Vec3b>(r, c) = cv::Vec3b(0, 0, 255);
      } else if (top(r, c) > std::numeric_limits<float>::lowest()) {
        const double t = std::clamp((top(r, c) - view.z_ground) / view.z_span, 0.0, 1.0);
        const auto g = static_cast<std::uint8_t>(60 + 195 * t);
        img.at<cv::Vec3b>(r, c) = cv::Vec3b(g, g, g);
      }
    }
  if (dynamic_radius > 0)
    for (const MapPoint& p : dynamic_points)
      if (cell(p, r, c)) cv::circle(img, {c, r}, dynamic_radius, cv::Scalar(0, 0, 255), cv::FILLED);
  return img;
}

double scaleBarLength(double width_m) {
  const double target = std::max(width_m / 5.0, 0.01);
  double best = 0.01;
  for (double decade = 0.01; decade <= target; decade *= 10)
    for (const double m : {1.0, 2.0, 5.0})
      if (m * decade <= target * (1 + 1e-9)) best = std::max(best, m * decade);
  return best;
}

void drawLegendAndScale(cv::Mat& img, const TopDownView& view,
                        const std::vector<LegendEntry>& legend) {
  if (img.cols < 160 || img.rows < 80 || view.resolution <= 0) return;
  const int font = cv::FONT_HERSHEY_SIMPLEX, line = 18, pad = 6;
  const double scale = 0.45;
  const cv::Scalar white(255, 255, 255), box(40, 40, 40);
  // Legend, top left: a swatch and its text per entry.
  int text_w = 0;
  for (const LegendEntry& e : legend)
    text_w = std::max(text_w, cv::getTextSize(e.text, font, scale, 1, nullptr).width);
  if (!legend.empty()) {
    const int h = pad * 2 + line * static_cast<int>(legend.size());
    cv::rectangle(img, {0, 0}, {std::min(img.cols - 1, pad * 3 + 12 + text_w), h}, box, cv::FILLED);
    for (std::size_t i = 0; i < legend.size(); i++) {
      const int y = pad + line * static_cast<int>(i);
      cv::rectangle(img, {pad, y + 3}, {pad + 12, y + 13}, legend[i].colour, cv::FILLED);
      cv::putText(img, legend[i].text, {pad * 2 + 12, y + 13}, font, scale, white, 1, cv::LINE_AA);
    }
  }
  // Scale bar, bottom left: scaleBarLength() metres, ticks at both ends, its length above it.
  const double metres = scaleBarLength(img.cols * view.resolution);
  const int len = static_cast<int>(std::lround(metres / view.resolution));
  char label[32];
  std::snprintf(label, sizeof(label), metres >= 1 ? "%.0f m" : "%.2f m", metres);
  const int y = img.rows - 1 - pad, x0 = pad;
  const int label_w = cv::getTextSize(label, font, scale, 1, nullptr).width;
  cv::rectangle(img, {0, y - line - pad},
                {std::min(img.cols - 1, x0 + std::max(len, label_w) + pad), img.rows - 1}, box,
                cv::FILLED);
  cv::line(img, {x0, y}, {x0 + len - 1, y}, white, 1);
  cv::line(img, {x0, y - 4}, {x0, y}, white, 1);
  cv::line(img, {x0 + len - 1, y - 4}, {x0 + len - 1, y}, white, 1);
  cv::putText(img, label, {x0, y - 7}, font, scale, white, 1, cv::LINE_AA);
}

}  // namespace dynobj::mapclean
