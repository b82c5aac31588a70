// SPDX-License-Identifier: BSD-3-Clause
// Glue of the Python module: a sweep handed in as a numpy array -> an mrptio::Frame, through the
// library's one conversion of each input kind (no algorithm here):
//  - (N, 4) x y z intensity, unordered: core::SweepProjector, as a folder of PCD / .bin sweeps is
//    read (CloudFolderFrameSource: intensity scale of the first sweep, rows recovered);
//  - (rows, cols, 4), organized: one point per pixel with a finite, non-zero position, organized
//    with the sensor preset or, without one, core::organizedModel, as a rawlog's 3D range scan
//    (ConvertRangeScan3D).
// And back: a frame's dynamic pixels -> the per-point (N,) or per-pixel (rows, cols) mask.
#pragma once

#include <dynobj/core/SensorModel.h>
#include <dynobj/core/SweepProjector.h>
#include <dynobj/mrptio/FrameSource.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace dynobj::python {

/// A sweep's points as given: `rows` x `cols` x 4 (organized) or `rows` points x 4 (cols = 0),
/// float32 or float64, C order. The data must stay valid while convert() runs.
struct ArrayView {
  const void* data = nullptr;
  bool is_double = false;
  std::size_t rows = 0, cols = 0;
  bool organized() const { return cols > 0; }
};

/// What process() returns for one frame: 0/1 per input point (N) or per pixel (rows x cols).
struct Mask {
  std::vector<std::uint8_t> values;
  std::size_t rows = 0, cols = 0;  ///< cols = 0: one value per input point
};

class ArraySweeps {
 public:
  explicit ArraySweeps(std::optional<core::SensorModel> sensor);

  /// The next sweep of the sequence into `f` (its buffers are reused). `timestamp_ns` must be
  /// after the previous sweep's. Throws std::invalid_argument (Python: ValueError) naming what
  /// does not fit: the timestamp, an organized array whose size is not the preset's, an
  /// unordered sweep whose rows cannot be recovered without a preset.
  void convert(const ArrayView& a, std::int64_t timestamp_ns, mrptio::Frame& f);

  /// The mask of `f`'s `dynamic` pixels in the input's layout.
  static Mask maskOf(const mrptio::Frame& f, const cv::Mat_<std::uint8_t>& dynamic);

 private:
  std::optional<core::SensorModel> sensor_;
  core::SweepProjector projector_;
  std::int64_t last_ns_ = 0;
  std::size_t index_ = 0;
};

}  // namespace dynobj::python
