// SPDX-License-Identifier: BSD-3-Clause
// Image rows for an *unordered* cloud that fit the real sensor (docs/formats.md, "Row recovery").
// A nominal, evenly spaced or datasheet beam table rarely matches a real unit (HDL-64 lasers sit
// at uneven, unit-specific elevations and have vertical offsets), and Eq. (1) with such a table
// gives striped images: empty rows and rows holding two beams. The rows are recovered instead, by
// the first rule that applies:
//  1. ring field    — the cloud carries a laser id per point (PCD `ring`, Velodyne laser_id);
//                     rows = laser ids ordered by their median elevation;
//  2. firing order  — the cloud is stored laser by laser, each laser one revolution (how KITTI
//                     and most HDL recorders store a sweep): a new row starts each time the
//                     azimuth has turned a full revolution since the sweep's first point;
//  3. firing cycle  — the cloud is in the order the lasers fired (raw packet order: every laser
//                     once per firing, cycle after cycle, no-returns left out): the beams are the
//                     peaks of the points' elevations; an isolated beam's returns one firing apart
//                     give the number of lasers (their largest gap) and, over the complete
//                     cycles, each position's elevation and vertical offset; the points between
//                     its returns take the positions in order (fewest misfits); in a sweep of
//                     more than one revolution the first pass holds the pixels and the sector's
//                     second pass only fills the ones it left empty (RecoveredRows::second_pass);
//  4. estimated table — the elevation histogram of the sweep's far points has one peak per beam;
//  5. nominal table — the sensor model as given (the last resort).
// Rules 1-4 return a sensor model whose beam table is the measured elevation of each row; rules
// 1-3 need no sensor model.
#pragma once

#include <optional>
#include <string>

#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/PointCloud.h"
#include "dynobj/core/SensorModel.h"
#include "dynobj/core/SphericalProjection.h"

namespace dynobj::core {

enum class RowSource { RingField, FiringOrder, FiringCycle, EstimatedTable, NominalTable };
const char* toString(RowSource s);
/// True for the rules that find the sensor's rows in the data (1-3): later sweeps of the same
/// sensor may take the model they give as their hint.
inline bool rowsFromData(RowSource s) {
  return s == RowSource::RingField || s == RowSource::FiringOrder || s == RowSource::FiringCycle;
}

struct RecoveredRows {
  RowSource source = RowSource::NominalTable;
  SensorModel sensor;  ///< the rows found (beam_elevations = measured elevation per row)
  int lasers = 0;      ///< lasers the data shows (rules 1-3); 0 = unknown
  /// Rule 3, a sweep of more than one revolution: 1 for each point of the sector scanned a second
  /// time (empty when none); they only fill pixels the first pass left empty (organize()).
  std::vector<std::uint8_t> second_pass;
  std::size_t repeated = 0;  ///< the points marked in second_pass
};

/// Recovers the rows of `cloud` (see the file comment). `hint` gives what is known of the sensor:
/// its rows (a recovered row count must equal it), columns, range limits and rate; without a
/// hint the row count comes from the data and the columns from the azimuth step. Fills
/// cloud.row / cloud.col for rules 1-3 (the cloud becomes organized); leaves them empty for
/// rules 4-5 (project with Eq. (1) and the returned model). Throws std::invalid_argument when no
/// rule applies and there is no hint.
RecoveredRows recoverRows(PointCloud& cloud, const std::optional<SensorModel>& hint);

/// recoverRows(), then organize() or project() into `frame`. `source` (optional) receives the rule,
/// `lasers` (optional) RecoveredRows::lasers.
ProjectionStats projectUnordered(PointCloud& cloud, const std::optional<SensorModel>& hint,
                                 LidarFrame& frame, RowSource* source = nullptr,
                                 int* lasers = nullptr);

/// Measured elevation [rad] of each group of points (group[i] < groups, e.g. a row or a laser
/// id): the median over the group's far points (>= 15 m horizontally, where a laser's vertical
/// offset no longer tilts them) when it has enough, else over all its points; NaN when empty.
std::vector<double> measuredElevations(const PointCloud& cloud,
                                       const std::vector<std::uint16_t>& group, int groups);

/// The model of an organized cloud (cloud.row per point; `rows` x `cols`) that carries no beam
/// table of its own (a 3D range scan, an organized array): the table measured from its points
/// (measuredElevations per row, gaps interpolated); a least-squares line (elevation = a + b *
/// row) when the rows do not descend; else 1 degree per row around the horizon. `max_range` [m]:
/// what the input says (100 when it says nothing); `name`: the model's name in messages.
SensorModel organizedModel(const PointCloud& cloud, int rows, int cols, double max_range,
                           const std::string& name);

/// Azimuth bins per revolution estimated from the data: one per firing, from the median azimuth
/// step of the best-covered laser (`laser[i]` = row or laser id of point i).
int estimateColumns(const PointCloud& cloud, const std::vector<std::uint16_t>& laser, int lasers);

}  // namespace dynobj::core
