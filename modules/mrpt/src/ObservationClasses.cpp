// SPDX-License-Identifier: BSD-3-Clause
#include "ObservationClasses.h"

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRotatingScan.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

namespace dynobj::mrptio::detail {
namespace {

using mrpt::obs::CObservation;
using Scan3D = mrpt::obs::CObservation3DRangeScan;
using Velodyne = mrpt::obs::CObservationVelodyneScan;
using Cloud = mrpt::obs::CObservationPointCloud;
using Rotating = mrpt::obs::CObservationRotatingScan;

template <class T>
bool is(const CObservation& o) {
  return IS_CLASS(o, T);
}

/// The 3D scan's points flagged by the point mask (the scan's own points3D_*), for split mode.
void collect(const Scan3D& o, const std::vector<std::uint8_t>& point_mask,
             mrpt::maps::CPointsMap& removed) {
  for (std::size_t i = 0; i < point_mask.size() && i < o.points3D_x.size(); i++)
    if (point_mask[i]) removed.insertPoint(o.points3D_x[i], o.points3D_y[i], o.points3D_z[i]);
}

const std::vector<ObservationClass> kClasses{
    {"CObservation3DRangeScan", &is<Scan3D>,
     [](const CObservation& o, const ConvertContext& c, core::LidarFrame& f) {
       return convertRangeScan3D(static_cast<const Scan3D&>(o), c.sensor, f);
     },
     [](CObservation& o, const cv::Mat_<std::uint8_t>& px) {
       return markDynamic(static_cast<Scan3D&>(o), px);
     },
     [](CObservation& o, const cv::Mat_<std::uint8_t>& px, const std::vector<std::uint8_t>& pts,
        mrpt::maps::CPointsMap* removed) {
       auto& s = static_cast<Scan3D&>(o);
       if (removed) collect(s, pts, *removed);
       return dropDynamic(s, px);
     },
     [](CObservation& o) {
       auto& s = static_cast<Scan3D&>(o);
       s.load();
       return restoreDynamic(s);
     },
     [](const CObservation& o) {
       const auto& s = static_cast<const Scan3D&>(o);
       return s.points3D_isExternallyStored() || s.rangeImage_isExternallyStored();
     }},
    {"CObservationVelodyneScan", &is<Velodyne>,
     [](const CObservation& o, const ConvertContext& c, core::LidarFrame& f) {
       return convertVelodyne(static_cast<const Velodyne&>(o), c.sensor, f);
     },
     nullptr,
     [](CObservation& o, const cv::Mat_<std::uint8_t>&, const std::vector<std::uint8_t>& pts,
        mrpt::maps::CPointsMap* removed) {
       return dropDynamic(static_cast<Velodyne&>(o), pts, removed);
     },
     nullptr, nullptr},
    {"CObservationPointCloud", &is<Cloud>,
     [](const CObservation& o, const ConvertContext& c, core::LidarFrame& f) {
       return convertPointCloud(static_cast<const Cloud&>(o), c.sensor, c.learned, f);
     },
     nullptr,
     [](CObservation& o, const cv::Mat_<std::uint8_t>&, const std::vector<std::uint8_t>& pts,
        mrpt::maps::CPointsMap* removed) {
       return dropDynamic(static_cast<Cloud&>(o), pts, removed);
     },
     nullptr, nullptr},
    {"CObservationRotatingScan", &is<Rotating>,
     [](const CObservation& o, const ConvertContext& c, core::LidarFrame& f) {
       return convertRotatingScan(static_cast<const Rotating&>(o), c.sensor, f);
     },
     nullptr, nullptr, nullptr, nullptr},
};

}  // namespace

const std::vector<ObservationClass>& observationClasses() {
  return kClasses;
}

const ObservationClass* findObservationClass(const CObservation& obs) {
  for (const ObservationClass& c : kClasses)
    if (c.is(obs)) return &c;
  return nullptr;
}

}  // namespace dynobj::mrptio::detail
