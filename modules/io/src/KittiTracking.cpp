// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/KittiTracking.h"

#include <fstream>
#include <map>
#include <sstream>

#include "dynobj/io/FormatError.h"

namespace dynobj::io {

std::vector<KittiBox> readKittiTrackingLabels(const std::string& path) {
  std::ifstream in(path);
  if (!in) throwFormatError(path, "cannot open KITTI tracking label file");
  std::vector<KittiBox> boxes;
  std::string line;
  for (int no = 1; std::getline(in, line); no++) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream s(line);
    KittiBox b;
    double alpha = 0, x1 = 0, y1 = 0, x2 = 0, y2 = 0;
    double truncated = 0;
    if (!(s >> b.frame >> b.track_id >> b.type >> truncated >> b.occluded >> alpha >> x1 >> y1 >>
          x2 >> y2 >> b.h >> b.w >> b.l >> b.bottom.x() >> b.bottom.y() >> b.bottom.z() >> b.ry))
      throwFormatError(path + ":" + std::to_string(no),
                       "expected 17 fields 'frame track_id type truncated occluded alpha x1 y1 "
                       "x2 y2 h w l x y z ry'");
    if (b.frame < 0) throwFormatError(path + ":" + std::to_string(no), "negative frame number");
    b.truncated = static_cast<int>(truncated);
    boxes.push_back(b);
  }
  if (boxes.empty()) throwFormatError(path, "no label row");
  return boxes;
}

Eigen::Isometry3d KittiCalib::veloToRect() const {
  Eigen::Isometry3d r = Eigen::Isometry3d::Identity();
  r.linear() = R_rect;
  return r * velo_to_cam;
}

KittiCalib readKittiCalib(const std::string& path) {
  std::ifstream in(path);
  if (!in) throwFormatError(path, "cannot open KITTI calibration file");
  std::map<std::string, std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string key;
    if (!(s >> key)) continue;
    if (key.back() == ':') key.pop_back();
    std::vector<double> v;
    for (double x; s >> x;) v.push_back(x);
    rows[key] = v;
  }
  const auto get = [&](std::initializer_list<const char*> keys, std::size_t n) {
    for (const char* k : keys) {
      const auto it = rows.find(k);
      if (it == rows.end()) continue;
      if (it->second.size() != n)
        throwFormatError(path, std::string("'") + k + "' has " + std::to_string(it->second.size()) +
                                   " numbers, expected " + std::to_string(n));
      return it->second;
    }
    throwFormatError(path, std::string("no '") + *keys.begin() + "' line");
  };
  KittiCalib c;
  const auto p2 = get({"P2", "P_rect_02"}, 12);
  const auto rr = get({"R_rect", "R0_rect", "R_rect_00"}, 9);
  const auto tr = get({"Tr_velo_cam", "Tr_velo_to_cam"}, 12);
  for (int r = 0; r < 3; r++) {
    for (int col = 0; col < 4; col++) {
      c.P2(r, col) = p2[r * 4 + col];
      if (col < 3) c.velo_to_cam.linear()(r, col) = tr[r * 4 + col];
    }
    c.velo_to_cam.translation()(r) = tr[r * 4 + 3];
    for (int col = 0; col < 3; col++) c.R_rect(r, col) = rr[r * 3 + col];
  }
  return c;
}

}  // namespace dynobj::io
