// SPDX-License-Identifier: BSD-3-Clause
// SemanticKITTI per-point labels (`sequences/<seq>/labels/<sweep>.label`): one little-endian
// uint32 per point of the matching `.bin` sweep, in its order; the lower 16 bits are the semantic
// class, the upper 16 the instance id. The moving-object segmentation benchmark (LiDAR-MOS) reads
// 9 as static and 251 as moving; SemanticKITTI's moving classes are 252-259 (moving-car,
// -bicyclist, -person, -motorcyclist, -on-rails, -bus, -truck, -other-vehicle) and 0 is unlabeled.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace dynobj::io {

namespace semantic_kitti {
constexpr std::uint16_t kUnlabeled = 0;
constexpr std::uint16_t kStatic = 9;    ///< LiDAR-MOS: static
constexpr std::uint16_t kMoving = 251;  ///< LiDAR-MOS: moving
/// 251-259: a moving class (251 = LiDAR-MOS "moving", 252-259 the moving object classes).
inline bool isMoving(std::uint32_t label) {
  const std::uint32_t c = label & 0xFFFFu;
  return c >= 251 && c <= 259;
}
/// The SemanticKITTI name of a moving class ("car" for 252, ...; "moving" for 251).
std::string movingClassName(std::uint16_t semantic);
/// The moving class of a KITTI object type (Car, Van, Truck, Pedestrian, Cyclist, ...) or of a
/// SemanticKITTI name ("car", "person", ...); 259 (other-vehicle) for anything else.
std::uint16_t movingClassOf(const std::string& kitti_type);
}  // namespace semantic_kitti

/// Reads a .label file. Throws FormatError when it cannot be read or its size is not a multiple
/// of 4 bytes.
std::vector<std::uint32_t> readSemanticKittiLabels(const std::string& path);

/// Writes a .label file atomically (through AtomicFile). Throws std::runtime_error naming it.
void writeSemanticKittiLabels(const std::string& path, const std::vector<std::uint32_t>& labels);

}  // namespace dynobj::io
