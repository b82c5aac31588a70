// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/CloudFolderFrameSource.h"

#include <dynobj/io/FormatError.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace dynobj::mrptio {
namespace {

io::CloudFolder openFolder(const std::string& dir, const CloudFolderOptions& o) {
  if (!(o.rate > 0)) throw std::invalid_argument("the sweep rate must be > 0 Hz");
  io::CloudFolder folder(dir, o.times);
  if (o.times.empty()) folder.setPeriodNs(static_cast<std::int64_t>(std::llround(1e9 / o.rate)));
  return folder;
}

}  // namespace

CloudFolderFrameSource::CloudFolderFrameSource(const std::string& dir, CloudFolderOptions o)
    : dir_(dir), o_(std::move(o)), folder_(openFolder(dir, o_)), projector_(o_.sensor) {}

void CloudFolderFrameSource::rewind() {
  pos_ = 0;
  projector_.reset();
  row_sources_.clear();
}

std::string CloudFolderFrameSource::describe() const {
  return (folder_.extension() == ".pcd" ? "PCD folder '" : "KITTI .bin folder '") + dir_ + "' (" +
         std::to_string(folder_.size()) + " sweeps)";
}

bool CloudFolderFrameSource::next(Frame& f) {
  if (pos_ >= folder_.size()) return false;
  const std::size_t k = pos_;
  io::CloudFile file = folder_.read(k);
  core::PointCloud& cloud = file.cloud;
  if (!file.viewpoint.isApprox(Eigen::Isometry3d::Identity())) {  // points -> sensor frame
    const Eigen::Isometry3f to_sensor = file.viewpoint.inverse().cast<float>();
    for (std::size_t i = 0; i < cloud.size(); i++) {
      const Eigen::Vector3f p = to_sensor * Eigen::Vector3f(cloud.x[i], cloud.y[i], cloud.z[i]);
      cloud.x[i] = p.x();
      cloud.y[i] = p.y();
      cloud.z[i] = p.z();
    }
  }
  const bool first = projector_.intensityScale() == 0;
  try {
    f.stats = projector_.project(cloud, f.frame);
  } catch (const std::invalid_argument& e) {
    throw io::FormatError(folder_.path(k) + ": " + e.what() + "; give --sensor");
  }
  if (first)
    intensity_ =
        file.intensity_field.empty()
            ? "none (the detector uses range)"
            : "'" + file.intensity_field + "'" + (projector_.intensityScale() != 1 ? " x 255" : "");
  const core::RowSource source = projector_.lastRowSource();
  row_sources_[source]++;
  // MRPT reads a zero timestamp as 'invalid': without a times file, sweep k is at (k+1) periods.
  f.frame.timestamp_ns = folder_.timestampNs(k) + (folder_.hasTimes() ? 0 : folder_.periodNs());
  f.index = f.entry = k;
  f.where = "'" + folder_.path(k) + "'";
  f.sensor_label = o_.sensor_label;
  f.mount = Eigen::Isometry3d::Identity();
  f.odometry.reset();
  f.viewpoint = file.viewpoint;
  f.observation.reset();
  f.points = std::move(cloud);
  pos_++;
  return true;
}

std::string describeRowSources(const std::map<core::RowSource, std::size_t>& sources) {
  std::vector<std::pair<std::size_t, core::RowSource>> v;
  for (const auto& [s, n] : sources) v.emplace_back(n, s);
  std::sort(v.rbegin(), v.rend());
  std::string out;
  for (const auto& [n, s] : v)
    out += (out.empty() ? "" : ", ") + std::string(core::toString(s)) + " " + std::to_string(n);
  return out.empty() ? "none" : out;
}

}  // namespace dynobj::mrptio
