// SPDX-License-Identifier: BSD-3-Clause
// icp-slam-dynobj: MRPT's stock icp-slam (same command line, same .ini) with the dynamic-object
// filter applied to every observation before the map builder sees it. Configured by a
// [DynamicObjects] section of the .ini; without that section it behaves exactly like icp-slam.
// An unknown key in its sections, or a run that filtered no LiDAR frame, is an error.
#include <dynobj/core/Config.h>
#include <dynobj/io/IniFile.h>
#include <dynobj/io/SensorFile.h>
#include <dynobj/mrptio/DynamicObjectFilter.h>
#include <mrpt/apps/ICP_SLAM_App.h>

#include <filesystem>
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

/// [DynamicObjects] enabled, mode (drop | mark), sensor_label, sensor (preset path), allow_none;
/// detector parameters in sections [DynamicObjects_foreground], [DynamicObjects_movement], ...
/// Only these sections of the (stock icp-slam) file are checked for unknown keys.
struct FilterConfig {
  std::optional<dynobj::mrptio::DynamicObjectFilter> filter;
  bool allow_none = false;  ///< a run that filters no LiDAR frame is no error
};

FilterConfig filterFrom(const std::string& ini_path) {
  const std::string s = "DynamicObjects";
  dynobj::io::IniFile ini(ini_path);
  ini.expect(s, {"enabled", "mode", "sensor_label", "sensor", "allow_none"});
  ini.expectDetector(s + "_");
  ini.check(s);
  const mrpt::config::CConfigFileBase& c = ini.config();
  FilterConfig out;
  if (!c.sectionExists(s) || !dynobj::core::readBool(c, s, "enabled", true)) return out;
  dynobj::mrptio::DynamicObjectFilter::Options o;
  o.mode = dynobj::mrptio::parseFilterMode(dynobj::core::readString(c, s, "mode", "drop"));
  if (o.mode != dynobj::mrptio::FilterMode::Drop && o.mode != dynobj::mrptio::FilterMode::Mark)
    throw dynobj::core::ParameterError(
        "[DynamicObjects] mode: only 'drop' and 'mark' make sense inside icp-slam");
  o.sensor_label = dynobj::core::readString(c, s, "sensor_label", "");
  const std::string preset = dynobj::core::readString(c, s, "sensor", "");
  if (!preset.empty()) o.sensor = dynobj::io::readSensorModel(preset);
  o.detector.load(c, "DynamicObjects_");
  out.allow_none = dynobj::core::readBool(c, s, "allow_none", false);
  out.filter.emplace(std::move(o));
  return out;
}

/// Stock icp-slam's command line; MRPT throws (with a backtrace) on anything else, so it is
/// checked here first. Returns an exit code when the app must stop now.
std::optional<int> checkCommandLine(int argc, char** argv) {
  const std::string first = argc > 1 ? argv[1] : "";
  if (first == "-h" || first == "--help" || first == "--version" || argc < 2 || argc > 3) {
    const bool help = first == "-h" || first == "--help" || first == "--version";
    (help ? std::cout : std::cerr)
        << "USAGE: icp-slam-dynobj <config.ini> [<dataset.rawlog>]\n\n"
           "MRPT's stock icp-slam (same command line, same .ini) with the dynamic-object filter\n"
           "applied to every observation before the map builder sees it. Configured by the\n"
           "[DynamicObjects] section of the .ini (enabled, mode = drop | mark, sensor_label,\n"
           "sensor, allow_none) and [DynamicObjects_<stage>] sections with the keys of\n"
           "dynobj.ini; without [DynamicObjects] it is stock icp-slam. docs/usage.md.\n";
    return help ? 0 : 2;
  }
  if (argc == 3 && !std::filesystem::is_regular_file(argv[2]))
    throw std::runtime_error(std::string("rawlog '") + argv[2] + "' does not exist");
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("icp-slam-dynobj", [&] {
    if (const auto stop = checkCommandLine(argc, argv)) return *stop;
    FilterConfig config = filterFrom(argv[1]);  // the .ini checked before icp-slam reads it
    IcpSlamDynobj app;
    app.initialize(argc, argv);
    app.filter = std::move(config.filter);
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
      if (s.lidar == 0 && !config.allow_none)
        throw std::runtime_error(s.nothingFiltered(app.filter->options().sensor_label) +
                                 "; in the .ini: [DynamicObjects] allow_none = true");
    }
    return 0;
  });
}
