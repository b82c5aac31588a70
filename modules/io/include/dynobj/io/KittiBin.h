// SPDX-License-Identifier: BSD-3-Clause
// KITTI Velodyne sweeps (velodyne_points/data/*.bin): packed little-endian float32 records
// x y z reflectance, sensor frame, no header.
#pragma once

#include <string>

#include "dynobj/io/CloudFile.h"
#include "dynobj/io/FormatError.h"

namespace dynobj::io {

/// Reads a KITTI .bin sweep: intensity = the stored reflectance (0..1, intensity_field
/// "intensity"); NaN/inf points dropped and counted. Throws FormatError when the file cannot be
/// read or its size is not a multiple of 16 bytes.
CloudFile readKittiBin(const std::string& path);

}  // namespace dynobj::io
