// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/ForegroundExtractor.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "dynobj/core/Config.h"

namespace dynobj::core {
namespace {

/// Gaussian blur of the (2a+1) x (2b+1) kernel of Eq. (2)-(3), wrapping around horizontally
/// (the image is a 360 degree scan) and reflecting at the top and bottom. `vert`, `padded` and
/// `blurred` are scratch buffers kept by the caller (no allocation once sized).
void blurWrapped(const cv::Mat_<float>& src, const ForegroundParams& p, cv::Mat& vert,
                 cv::Mat& padded, cv::Mat& blurred, cv::Mat_<float>& dst) {
  const int a = p.kernel_half_width, b = p.kernel_half_height;
  cv::copyMakeBorder(src, vert, b, b, 0, 0, cv::BORDER_REFLECT_101);
  cv::copyMakeBorder(vert, padded, 0, 0, a, a, cv::BORDER_WRAP);
  cv::GaussianBlur(padded, blurred, cv::Size(2 * a + 1, 2 * b + 1), p.sigma_horizontal,
                   p.sigma_vertical, cv::BORDER_REFLECT_101);
  blurred(cv::Rect(a, b, src.cols, src.rows)).copyTo(dst);
}

/// A key of a float's bits that orders like the floats (negative ones reversed below positive).
std::uint32_t orderKey(float x) {
  std::uint32_t u = 0;
  std::memcpy(&u, &x, sizeof u);
  return (u & 0x80000000u) != 0 ? ~u : u | 0x80000000u;
}

}  // namespace

void ForegroundParams::visit(ParamVisitor& v) {
  v.value("kernel_half_width", kernel_half_width, {1, 200});
  v.value("kernel_half_height", kernel_half_height, {0, 50});
  v.value("sigma_horizontal", sigma_horizontal, kPositive);
  v.value("sigma_vertical", sigma_vertical, kPositive);
  v.value("threshold", threshold, {0, 255});
  v.value("absolute", absolute);
  v.value("stretch_low", stretch_low, {0, 100});
  v.value("stretch_high", stretch_high, {0, 100});
  v.value("exclude_ground", exclude_ground);
}

void ForegroundParams::validate() const {
  StageParams::validate();
  if (stretch_high <= stretch_low) throwParameterError("stretch_high", "must exceed stretch_low");
}

ForegroundExtractor::ForegroundExtractor(const ForegroundParams& p) : p_(p) {
  p_.validate();
}

const cv::Mat_<float>& ForegroundExtractor::normalize(const LidarFrame& frame) {
  const cv::Mat_<float>& src = frame.has_intensity ? frame.intensity : frame.range;
  // Percentiles from a subsample of the valid pixels (every 3rd): cheap and stable.
  sample_.clear();
  const int n = frame.rows() * frame.cols();
  const float* s = src.ptr<float>(0);
  const std::uint8_t* v = frame.valid.ptr<std::uint8_t>(0);
  for (int i = 0; i < n; i += 3)
    if (v[i]) sample_.push_back(s[i]);
  f_.create(src.size());
  if (sample_.empty()) {
    f_.setTo(0);
    return f_;
  }
  // The value of rank k, as std::nth_element finds it, from a histogram of the samples' order
  // keys (top 12 bits: sign, exponent and 3 bits of mantissa, an eighth of an octave) and a
  // selection among the samples of the bin that holds rank k.
  hist_.assign(std::size_t{1} << 12, 0);
  for (const float x : sample_) hist_[orderKey(x) >> 20]++;
  auto pct = [&](double q) {
    const auto k = static_cast<std::size_t>(q / 100.0 * static_cast<double>(sample_.size() - 1));
    std::size_t b = 0, before = 0;
    while (before + hist_[b] <= k) before += hist_[b++];
    bin_.clear();
    for (const float x : sample_)
      if ((orderKey(x) >> 20) == b) bin_.push_back(x);
    const auto rank = static_cast<std::ptrdiff_t>(k - before);
    std::nth_element(bin_.begin(), bin_.begin() + rank, bin_.end());
    return static_cast<double>(bin_[static_cast<std::size_t>(rank)]);
  };
  // Linear stretch: the low percentile maps to 32 and the high one to 223, leaving head room so
  // that objects brighter or darker than almost everything (a few pixels) still stand out. A
  // flat image (hi = lo) keeps a 1 % of hi step, so it does not degenerate.
  const double lo = pct(p_.stretch_low), hi = pct(p_.stretch_high);
  const double scale = 191.0 / std::max(hi - lo, 0.01 * std::abs(hi) + 1e-3);
  float* out = f_.ptr<float>(0);
  for (int i = 0; i < n; i++)
    out[i] = v[i] ? static_cast<float>(std::clamp(32.0 + (s[i] - lo) * scale, 0.0, 255.0)) : 0.0f;
  return f_;
}

void ForegroundExtractor::extract(const LidarFrame& frame, const cv::Mat_<std::uint8_t>& exclude,
                                  cv::Mat_<std::uint8_t>& features) {
  normalize(frame);
  extractNormalized(frame, exclude, features);
}

void ForegroundExtractor::extractNormalized(const LidarFrame& frame,
                                            const cv::Mat_<std::uint8_t>& exclude,
                                            cv::Mat_<std::uint8_t>& features) {
  if (f_.size() != frame.range.size())
    throw std::logic_error("ForegroundExtractor::extractNormalized: normalize(frame) first");
  frame.valid.convertTo(v_, CV_32F, 1.0 / 255.0);
  // Normalised convolution: h = (f * g) / (valid * g), so no-returns do not act as dark pixels.
  blurWrapped(f_, p_, vert_, padded_, scratch_, blurred_);
  blurWrapped(v_, p_, vert_, padded_, scratch_, weight_);
  features.create(frame.range.size());
  const int n = frame.rows() * frame.cols();
  const float* f = f_.ptr<float>(0);
  const float* h = blurred_.ptr<float>(0);
  const float* w = weight_.ptr<float>(0);
  const std::uint8_t* valid = frame.valid.ptr<std::uint8_t>(0);
  const std::uint8_t* ex = exclude.empty() ? nullptr : exclude.ptr<std::uint8_t>(0);
  std::uint8_t* t = features.ptr<std::uint8_t>(0);
  const auto theta = static_cast<float>(p_.threshold);
  for (int i = 0; i < n; i++) {
    if (!valid[i] || (ex && ex[i]) || w[i] < 1e-3f) {
      t[i] = 0;
      continue;
    }
    const float d = f[i] - h[i] / w[i];  // Eq. (4): f - h
    t[i] = (p_.absolute ? std::abs(d) : d) > theta ? 255 : 0;
  }
}

}  // namespace dynobj::core
