// SPDX-License-Identifier: BSD-3-Clause
// dynobj-bench: times the detector per stage on synthetic frames (the simulator, in process, any
// sensor preset), printing median and 99th percentile. For a recorded rawlog use dynobj-detect,
// which prints the same table.
#include <dynobj/eval/SimulatedFrames.h>
#include <dynobj/eval/TimingStats.h>
#include <dynobj/mrptio/SequenceRunner.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "../common/AppOptions.h"

namespace {

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("dynobj-bench: time the detector on simulated frames", ' ', "0.1");
  TCLAP::ValueArg<std::string> scenario(
      "s", "scenario", "Scenario YAML (default: the shipped hall)", false, "", "file.yaml", cmd);
  TCLAP::ValueArg<std::string> sensor("", "sensor",
                                      "Sensor preset INI, or its path in share/dynobj (default: "
                                      "the scenario's, OS0-64 1024 x 10)",
                                      false, "", "file.ini", cmd);
  TCLAP::ValueArg<int> frames("n", "frames", "Frames to time", false, 100, "N", cmd);
  TCLAP::ValueArg<int> warmup("", "warmup", "Frames run before timing starts", false, 10, "N", cmd);
  TCLAP::ValueArg<std::string> config("c", "config", "Detector parameters (INI)", false, "",
                                      "file.ini", cmd);
  const dynobj::apps::ThreadsArg threads(cmd);
  if (const auto stop = dynobj::apps::parseCommandLine(cmd, argc, argv)) return *stop;
  if (frames.getValue() < 1 || warmup.getValue() < 0) {
    std::cerr << "dynobj-bench: error: --frames must be >= 1 and --warmup >= 0\n";
    return 2;
  }

  const std::string share = dynobj::apps::shareDir();
  std::map<std::string, std::string> overrides{
      {"frames", std::to_string(frames.getValue() + warmup.getValue())}};
  if (sensor.isSet())  // a file here, else a path in share/dynobj (sensors/x.ini)
    overrides["sensor"] = std::filesystem::exists(sensor.getValue())
                              ? std::filesystem::absolute(sensor.getValue()).string()
                              : sensor.getValue();
  const dynobj::sim::LidarSimulator sim(dynobj::sim::Scenario::fromYamlFile(
      scenario.isSet() ? scenario.getValue() : share + "/scenarios/hall.yaml", share, overrides));
  dynobj::eval::SimulatedFrames frames_in(sim);  // simulated in next(): not timed
  dynobj::mrptio::SequenceOptions so;
  so.detector = dynobj::apps::loadDetectorParams(config.getValue());
  threads.apply(so.detector);
  dynobj::eval::TimingStats stats;
  dynobj::mrptio::SequenceRunner(frames_in, so).run([&](const dynobj::mrptio::FrameResult& fr) {
    if (fr.frame.index >= static_cast<std::size_t>(warmup.getValue()))
      stats.add(fr.detection->timings);  // only the detector's own stage timings count
  });
  const auto& s = sim.scenario();
  std::printf("dynobj-bench: %s, %dx%d (%s), %zu frames after %d warm-up frames, %d thread%s\n",
              s.name.c_str(), s.sensor.rows, s.sensor.cols, s.sensor.model.c_str(), stats.frames(),
              warmup.getValue(), so.detector.pipeline.threads,
              so.detector.pipeline.threads > 1 ? "s" : "");
  std::fflush(stdout);
  stats.print(std::cout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-bench", [&] { return run(argc, argv); });
}
