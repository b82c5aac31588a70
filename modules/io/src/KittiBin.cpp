// SPDX-License-Identifier: BSD-3-Clause
// readKittiBin: the file is nothing but N records of 4 float32 (x y z reflectance).
#include "dynobj/io/KittiBin.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <vector>

namespace dynobj::io {

CloudFile readKittiBin(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throwFormatError(path, "cannot open KITTI .bin file");
  const std::streamoff end = in.tellg();
  if (end < 0) throwFormatError(path, "cannot read KITTI .bin file");
  const auto size = static_cast<std::size_t>(end);
  if (size % 16 != 0)
    throwFormatError(path, "size " + std::to_string(size) +
                               " bytes is not a multiple of 16 (float32 x y z intensity records)");
  std::vector<float> v(size / 4);
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(size)))
    throwFormatError(path, "read error");
  CloudFile out;
  out.intensity_field = "intensity";
  out.width = size / 16;
  core::PointCloud& c = out.cloud;
  c.reserve(size / 16, true, false);
  for (std::size_t k = 0; k < v.size(); k += 4) {
    if (!std::isfinite(v[k]) || !std::isfinite(v[k + 1]) || !std::isfinite(v[k + 2])) {
      out.dropped_nonfinite++;
      continue;
    }
    c.push_back(v[k], v[k + 1], v[k + 2], v[k + 3]);
  }
  return out;
}

}  // namespace dynobj::io
