// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/ScanSource.h"

#include <dynobj/core/SphericalProjection.h>
#include <dynobj/io/CloudFolder.h>
#include <dynobj/io/PcdFile.h>
#include <dynobj/mrptio/ObservationConverter.h>
#include <dynobj/mrptio/RawlogFrameSource.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace dynobj::mapclean {
namespace {

namespace fs = std::filesystem;

class PcdFolderScans final : public ScanSource {
 public:
  PcdFolderScans(const std::string& dir, const ScanSourceOptions& o)
      : dir_(dir), folder_(checkedFolder(dir, o)) {
    projection_ = std::make_unique<core::SphericalProjection>(*o.sensor);
  }
  void rewind() override { pos_ = 0; }
  std::string describe() const override { return "PCD folder '" + dir_ + "'"; }
  double progress() const override {
    return static_cast<double>(pos_) /
           static_cast<double>(std::max<std::size_t>(1, folder_.size()));
  }

  bool next(Scan& s) override {
    if (pos_ >= folder_.size()) return false;
    const std::string& file = folder_.path(pos_);
    io::CloudFile pcd = io::readPcd(file);
    core::PointCloud& cloud = pcd.cloud;  // points in the world: back into the sensor frame
    const Eigen::Isometry3f to_sensor = pcd.viewpoint.inverse().cast<float>();
    for (std::size_t i = 0; i < cloud.size(); i++) {
      const Eigen::Vector3f q = to_sensor * Eigen::Vector3f(cloud.x[i], cloud.y[i], cloud.z[i]);
      cloud.x[i] = q.x();
      cloud.y[i] = q.y();
      cloud.z[i] = q.z();
    }
    projection_->project(cloud, s.frame);
    s.frame.timestamp_ns = timestampOf(pcd);
    s.index = s.entry = pos_++;
    s.where = "'" + file + "'";
    s.sensor_label.clear();
    s.mount = Eigen::Isometry3d::Identity();
    s.odometry.reset();
    s.viewpoint = pcd.viewpoint;
    s.observation.reset();
    return true;
  }

 private:
  static io::CloudFolder checkedFolder(const std::string& dir, const ScanSourceOptions& o) {
    if (!o.sensor)
      throw std::runtime_error("'" + dir +
                               "' is a PCD folder: give the sensor model (--sensor) to "
                               "arrange its points into LiDAR frames");
    const std::string pcd_dir = (fs::path(dir) / "pcd").string();
    io::CloudFolder folder(pcd_dir);  // FormatError when it holds no sweep
    if (folder.extension() != ".pcd")
      throw std::runtime_error("'" + pcd_dir + "' holds no .pcd file");
    return folder;
  }

  /// dynobj's exports carry "# timestamp_ns <t>"; others get index / frequency.
  std::int64_t timestampOf(const io::CloudFile& pcd) const {
    for (const std::string& c : pcd.comments)
      if (c.rfind("timestamp_ns ", 0) == 0) return std::stoll(c.substr(13));
    return static_cast<std::int64_t>(1e9 * static_cast<double>(pos_) /
                                     projection_->sensor().frequency);
  }

  std::string dir_;
  io::CloudFolder folder_;
  std::unique_ptr<core::SphericalProjection> projection_;
  std::size_t pos_ = 0;
};

}  // namespace

std::unique_ptr<ScanSource> openScanSource(const std::string& input,
                                           const ScanSourceOptions& opts) {
  if (!fs::exists(input)) throw std::runtime_error("input '" + input + "' does not exist");
  if (fs::is_directory(input)) {
    if (!fs::is_directory(fs::path(input) / "pcd"))
      throw std::runtime_error("input '" + input +
                               "': unknown format (a directory, but not a KTH "
                               "DynamicMap folder with pcd/NNNNNN.pcd)");
    return std::make_unique<PcdFolderScans>(input, opts);
  }
  const std::string ext = fs::path(input).extension().string();
  if (ext != ".rawlog" && ext != ".gz")
    throw std::runtime_error("input '" + input +
                             "': unknown format (expected a .rawlog file or a "
                             "KTH DynamicMap folder with pcd/NNNNNN.pcd)");
  return std::make_unique<mrptio::RawlogFrameSource>(
      input, mrptio::ObservationConverter(opts.sensor),
      mrptio::RawlogFrameSource::Options{opts.sensor_label});
}

std::int64_t firstScanTime(ScanSource& source) {
  std::int64_t t = 0;
  if (!source.nextTime(t))
    throw std::runtime_error("no LiDAR scan in " + source.describe() + source.noFramesDetail());
  source.rewind();
  return t;
}

TimeWindowSource::TimeWindowSource(std::unique_ptr<ScanSource> source, std::int64_t begin_ns,
                                   std::int64_t end_ns)
    : source_(std::move(source)), begin_ns_(begin_ns), end_ns_(end_ns) {
  source_->skipBefore(begin_ns_);
}

void TimeWindowSource::rewind() {
  source_->rewind();
  source_->skipBefore(begin_ns_);
  reached_end_ = done_ = false;
}

bool TimeWindowSource::next(Scan& s) {
  while (!done_) {
    if (!source_->next(s)) {
      reached_end_ = done_ = true;
      break;
    }
    if (s.frame.timestamp_ns >= end_ns_) {
      done_ = true;
      break;
    }
    if (s.frame.timestamp_ns >= begin_ns_) return true;
  }
  return false;
}

}  // namespace dynobj::mapclean
