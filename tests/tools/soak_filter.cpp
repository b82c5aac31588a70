// SPDX-License-Identifier: BSD-3-Clause
// Soak test of the observation filter path (mrptio::DynamicObjectFilter: what rawlog-dynobj and
// icp-slam-dynobj run per observation): a long simulated recording, generated sweep by sweep in
// process (nothing kept), each sweep converted to the organized CObservation3DRangeScan and
// filtered in drop mode. Resident memory (/proc/self/statm) is printed every --every sweeps as
// CSV: sweep, seconds of data, RSS MiB, ms per sweep in the last window, dynamic-point share.
//   soak_filter [--scenario file.yaml] [--sensor sensors/x.ini] [--sweeps 36000] [--every 600]
#include <dynobj/mrptio/DynamicObjectFilter.h>
#include <dynobj/mrptio/RangeScanLayout.h>
#include <dynobj/mrptio/TimeConversion.h>
#include <dynobj/sim/LidarSimulator.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>

namespace {

double residentMiB() {
  std::ifstream f("/proc/self/statm");
  long size = 0, resident = 0;
  f >> size >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1048576.0;
}

}  // namespace

int main(int argc, char** argv) {
  std::map<std::string, std::string> opt{{"scenario", DYNOBJ_SHARE_DIR "/scenarios/hall.yaml"},
                                         {"sensor", "sensors/os0-64-512.ini"},
                                         {"sweeps", "36000"},
                                         {"every", "600"}};
  for (int i = 1; i + 1 < argc; i += 2) opt[std::string(argv[i]).substr(2)] = argv[i + 1];
  try {
    const int sweeps = std::stoi(opt["sweeps"]), every = std::stoi(opt["every"]);
    const dynobj::sim::LidarSimulator sim(dynobj::sim::Scenario::fromYamlFile(
        opt["scenario"], DYNOBJ_SHARE_DIR,
        {{"frames", std::to_string(sweeps)}, {"sensor", opt["sensor"]}}));
    const auto& s = sim.scenario();
    dynobj::mrptio::DynamicObjectFilter::Options fo;
    fo.mode = dynobj::mrptio::FilterMode::Drop;
    dynobj::mrptio::DynamicObjectFilter filter(fo);
    std::printf("# soak: scenario %s, %dx%d %s, %d sweeps at %.0f Hz, drop mode, pid %d\n",
                s.name.c_str(), s.sensor.rows, s.sensor.cols, s.sensor.model.c_str(), sweeps,
                s.sensor.frequency, static_cast<int>(getpid()));
    std::printf("sweep,data_s,rss_mib,ms_per_sweep,dynamic_pct\n");
    std::printf("0,0,%.1f,0,0\n", residentMiB());
    std::fflush(stdout);
    auto t0 = std::chrono::steady_clock::now();
    std::size_t points0 = 0, dyn0 = 0;
    for (int i = 0; i < sweeps; i++) {
      const auto sweep = sim.simulate(i);
      auto obs = std::make_shared<mrpt::obs::CObservation3DRangeScan>();
      dynobj::mrptio::frameToRangeScan(sweep.frame, *obs);
      obs->sensorLabel = s.sensor_label;
      obs->timestamp = dynobj::mrptio::fromUnixNs(sweep.timestamp_ns);
      obs->sensorPose = mrpt::poses::CPose3D(s.mount.x(), s.mount.y(), s.mount.z(), 0, 0, 0);
      filter.filter(obs);
      if ((i + 1) % every == 0) {
        const auto t1 = std::chrono::steady_clock::now();
        const auto& sm = filter.summary();
        const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count() / every;
        const double dyn = sm.points > points0
                               ? 100.0 * static_cast<double>(sm.dynamic_points - dyn0) /
                                     static_cast<double>(sm.points - points0)
                               : 0.0;
        std::printf("%d,%.0f,%.1f,%.1f,%.2f\n", i + 1, (i + 1) * sim.scenario().period(),
                    residentMiB(), ms, dyn);
        std::fflush(stdout);
        points0 = sm.points, dyn0 = sm.dynamic_points;
        t0 = std::chrono::steady_clock::now();
      }
    }
    for (const auto& [msg, n] : filter.summary().warnings)
      std::printf("# warning (%zux): %s\n", n, msg.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "soak_filter: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
