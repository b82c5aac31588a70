// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/SemanticKittiLabel.h"

#include <fstream>

#include "dynobj/io/AtomicFile.h"
#include "dynobj/io/FormatError.h"

namespace dynobj::io {

namespace semantic_kitti {

std::string movingClassName(std::uint16_t semantic) {
  switch (semantic) {
    case 252:
      return "car";
    case 253:
      return "bicyclist";
    case 254:
      return "person";
    case 255:
      return "motorcyclist";
    case 256:
      return "on-rails";
    case 257:
      return "bus";
    case 258:
      return "truck";
    case 259:
      return "other-vehicle";
    default:
      return "moving";
  }
}

std::uint16_t movingClassOf(const std::string& t) {
  for (std::uint16_t c = 252; c <= 259; c++)  // a SemanticKITTI name already
    if (t == movingClassName(c)) return c;
  if (t == "Car" || t == "Van") return 252;  // SemanticKITTI's car holds vans
  if (t == "Cyclist") return 253;
  if (t == "Pedestrian" || t == "Person_sitting") return 254;
  if (t == "Tram") return 256;
  if (t == "Truck") return 258;
  return 259;
}

}  // namespace semantic_kitti

std::vector<std::uint32_t> readSemanticKittiLabels(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throwFormatError(path, "cannot open SemanticKITTI .label file");
  const std::streamoff end = in.tellg();
  if (end < 0) throwFormatError(path, "cannot read SemanticKITTI .label file");
  const auto size = static_cast<std::size_t>(end);
  if (size % 4 != 0)
    throwFormatError(path, "size " + std::to_string(size) +
                               " bytes is not a multiple of 4 (one uint32 per point)");
  std::vector<std::uint32_t> v(size / 4);
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(size)))
    throwFormatError(path, "read error");
  return v;
}

void writeSemanticKittiLabels(const std::string& path, const std::vector<std::uint32_t>& labels) {
  AtomicFile f(path);
  f.stream().write(reinterpret_cast<const char*>(labels.data()),
                   static_cast<std::streamsize>(labels.size() * sizeof(std::uint32_t)));
  f.commit();
}

}  // namespace dynobj::io
