// SPDX-License-Identifier: BSD-3-Clause
// TUM and KITTI pose files (io::readPoseFile, format detected from the content).
#include <dynobj/io/PoseFile.h>

#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = dynobj::fuzz::asFile(data, size, ".poses");
  for (const auto fmt :
       {dynobj::io::PoseFormat::Auto, dynobj::io::PoseFormat::Tum, dynobj::io::PoseFormat::Kitti}) {
    try {
      const auto poses = dynobj::io::readPoseFile(path, fmt);
      if (!poses.empty()) dynobj::io::findPose(poses, poses.front().timestamp_ns, 1000);
    } catch (const std::exception&) {
    }
  }
  return 0;
}
