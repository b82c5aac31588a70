// SPDX-License-Identifier: BSD-3-Clause
// icp-slam-dynobj: MRPT's stock icp-slam (same command line, same .ini) with the dynamic-object
// filter applied to every observation before the map builder sees it. Configured by a
// [DynamicObjects] section of the .ini; without that section it behaves exactly like icp-slam.
#include <dynobj/core/Config.h>
#include <dynobj/io/SensorFile.h>
#include <dynobj/mrptio/DynamicObjectFilter.h>
#include <mrpt/apps/ICP_SLAM_App.h>

#include <iostream>
#include <optional>

#include "../common/AppMain.h"

namespace {

class IcpSlamDynobj : public mrpt::apps::ICP_SLAM_App_Rawlog {
 public:
  std::optional<dynobj::mrptio::DynamicObjectFilter> filter;

 protected:
  bool impl_get_next_observations(mrpt::obs::CActionCollection::Ptr& actions,
                                  mrpt::obs::CSensoryFrame::Ptr& sf,
                                  mrpt::obs::CObservation::Ptr& obs) override {
    const bool more = mrpt::apps::DataSourceRawlog::impl_get_next_observations(actions, sf, obs);
    if (more && filter) {
      if (sf) filter->filter(*sf);
      if (obs) filter->filter(obs);
    }
    return more;
  }
};

/// [DynamicObjects] enabled, mode (drop | mark), sensor_label, sensor (preset path); detector
/// parameters in sections [DynamicObjects_foreground], [DynamicObjects_movement], ...
std::optional<dynobj::mrptio::DynamicObjectFilter> filterFrom(
    const mrpt::config::CConfigFileBase& c) {
  const std::string s = "DynamicObjects";
  if (!c.sectionExists(s) || !dynobj::core::readBool(c, s, "enabled", true)) return std::nullopt;
  dynobj::mrptio::DynamicObjectFilter::Options o;
  o.mode = dynobj::mrptio::parseFilterMode(dynobj::core::readString(c, s, "mode", "drop"));
  if (o.mode != dynobj::mrptio::FilterMode::Drop && o.mode != dynobj::mrptio::FilterMode::Mark)
    throw dynobj::core::ParameterError(
        "[DynamicObjects] mode: only 'drop' and 'mark' make sense inside icp-slam");
  o.sensor_label = dynobj::core::readString(c, s, "sensor_label", "");
  const std::string preset = dynobj::core::readString(c, s, "sensor", "");
  if (!preset.empty()) o.sensor = dynobj::io::readSensorModel(preset);
  o.detector.load(c, "DynamicObjects_");
  return dynobj::mrptio::DynamicObjectFilter(std::move(o));
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("icp-slam-dynobj", [&] {
    IcpSlamDynobj app;
    app.initialize(argc, argv);
    app.filter = filterFrom(app.params);
    std::cout << "icp-slam-dynobj: dynamic-object filter "
              << (app.filter ? std::string("on (mode ") +
                                   dynobj::mrptio::toString(app.filter->options().mode) + ")"
                             : std::string("off (no [DynamicObjects] section): stock icp-slam"))
              << std::endl;
    app.run();
    if (app.filter) {
      const auto& s = app.filter->summary();
      std::cout << "icp-slam-dynobj: " << s.lidar << " LiDAR frames filtered, " << s.dynamic_points
                << " of " << s.points << " points dynamic, " << s.passed_through
                << " passed through" << std::endl;
      for (const auto& [msg, n] : s.warnings)
        std::cout << "  warning (" << n << "x): " << msg << "\n";
    }
    return 0;
  });
}
