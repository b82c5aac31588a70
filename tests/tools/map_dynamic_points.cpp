// SPDX-License-Identifier: BSD-3-Clause
// Test tool: how many points of a map (MRPT points-map text dump, world frame) lie on the moving
// actors of a simulated sequence — within 0.2 m of a ground-truth dynamic point and more than
// 0.25 m above the floor (so the floor under the actors' feet does not count). Compares a map built
// from the raw rawlog with one built from the filtered rawlog and fails unless the filtered map
// holds at most `max_ratio` times as many such points.
//   map_dynamic_points <seq.rawlog> <seq.gt.labels> <seq.gt.tum> <raw_map.txt> <filtered_map.txt>
//   <max_ratio>
#include <dynobj/io/LabelFile.h>
#include <dynobj/io/PoseFile.h>
#include <dynobj/mrptio/RawlogFrameSource.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

namespace {

/// Ground-truth dynamic points in a 0.2 m voxel hash, for "within 0.2 m" queries.
class NearSet {
 public:
  void add(const Eigen::Vector3d& p) { cells_[key(p, 0, 0, 0)].push_back(p); }
  bool near(const Eigen::Vector3d& q) const {
    for (int dx = -1; dx <= 1; dx++)
      for (int dy = -1; dy <= 1; dy++)
        for (int dz = -1; dz <= 1; dz++) {
          const auto it = cells_.find(key(q, dx, dy, dz));
          if (it == cells_.end()) continue;
          for (const auto& p : it->second)
            if ((p - q).squaredNorm() < 0.04) return true;
        }
    return false;
  }

 private:
  static long long key(const Eigen::Vector3d& p, int dx, int dy, int dz) {
    const auto c = [](double v, int d) {
      return static_cast<long long>(std::floor(v / 0.2)) + d + (1 << 20);
    };
    return (c(p.x(), dx) << 42) | (c(p.y(), dy) << 21) | c(p.z(), dz);
  }
  std::unordered_map<long long, std::vector<Eigen::Vector3d>> cells_;
};

std::size_t onActors(const std::string& map, const NearSet& dyn, std::size_t& total) {
  std::ifstream f(map);
  if (!f) throw std::runtime_error("cannot read map '" + map + "'");
  std::string line;
  std::size_t n = 0;
  total = 0;
  while (std::getline(f, line)) {
    std::istringstream ss(line);
    double x, y, z;
    if (!(ss >> x >> y >> z)) continue;
    total++;
    const Eigen::Vector3d w(
        x, y, z);  // icp-slam's map frame = the world (odometry starts at the true pose)
    n += w.z() > 0.25 && dyn.near(w);
  }
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr,
                 "usage: map_dynamic_points seq.rawlog seq.gt.labels seq.gt.tum raw_map.txt "
                 "filtered_map.txt max_ratio\n");
    return 2;
  }
  try {
    const auto gt = dynobj::io::LabelFile::read(argv[2]);
    const auto poses = dynobj::io::readPoseFile(argv[3], dynobj::io::PoseFormat::Tum);
    dynobj::mrptio::RawlogFrameSource s(argv[1], dynobj::mrptio::ObservationConverter(),
                                        {"LIDAR", 0, 1000000});
    dynobj::mrptio::Frame it;
    NearSet dyn;
    std::size_t k = 0;
    while (s.next(it)) {
      const auto* p = dynobj::io::findPose(poses, it.frame.timestamp_ns);
      if (!p || k >= gt.sweeps.size())
        throw std::runtime_error("ground truth does not match the rawlog");
      for (auto px : gt.sweeps[k].pixels) {
        const cv::Vec3f q = it.frame.xyz(static_cast<int>(px) / it.frame.cols(),
                                         static_cast<int>(px) % it.frame.cols());
        dyn.add(p->pose * Eigen::Vector3d(q[0], q[1], q[2]));
      }
      k++;
    }
    std::size_t raw_total = 0, filtered_total = 0;
    const std::size_t raw = onActors(argv[4], dyn, raw_total);
    const std::size_t filtered = onActors(argv[5], dyn, filtered_total);
    const double max_ratio = std::stod(argv[6]);
    std::printf(
        "map points on moving actors: raw map %zu (of %zu), filtered map %zu (of %zu), ratio %.2f "
        "(max %.2f)\n",
        raw, raw_total, filtered, filtered_total,
        raw ? static_cast<double>(filtered) / static_cast<double>(raw) : 0.0, max_ratio);
    return raw > 0 && static_cast<double>(filtered) <= max_ratio * static_cast<double>(raw) ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "map_dynamic_points: error: %s\n", e.what());
    return 1;
  }
}
