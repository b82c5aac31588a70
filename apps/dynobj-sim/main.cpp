// SPDX-License-Identifier: BSD-3-Clause
// dynobj-sim: simulates a labelled LiDAR sequence from a scenario file (docs/simulator.md).
#include <dynobj/io/FrameImages.h>
#include <dynobj/io/Png.h>
#include <dynobj/sim/LidarSimulator.h>
#include <dynobj/sim/SequenceWriter.h>
#include <dynobj/sim/TopView.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>

#include "../common/AppMain.h"

namespace {

std::map<std::string, std::string> parseSets(const std::vector<std::string>& sets) {
  std::map<std::string, std::string> out;
  for (const auto& kv : sets) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      throw std::invalid_argument("--set expects key=value, got '" + kv + "'");
    out[kv.substr(0, eq)] = kv.substr(eq + 1);
  }
  return out;
}

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("dynobj-sim: simulate a labelled LiDAR sequence", ' ', "0.1");
  TCLAP::ValueArg<std::string> scenario("s", "scenario", "Scenario YAML file", true, "",
                                        "file.yaml", cmd);
  const dynobj::apps::OutputArg out(cmd, "Output folder", true, "dir", "out");
  TCLAP::ValueArg<int> frames("n", "frames", "Number of sweeps (overrides the scenario)", false, 0,
                              "N", cmd);
  TCLAP::ValueArg<unsigned> seed("", "seed", "Random seed (overrides the scenario)", false, 0, "S",
                                 cmd);
  TCLAP::MultiArg<std::string> sets("", "set",
                                    "Override any scenario key, e.g. --set noise.range_sigma=0.03",
                                    false, "key=value", cmd);
  TCLAP::ValueArg<int> preview("", "preview",
                               "Also write <name>.preview.png: sweep K's intensity with the "
                               "ground-truth dynamic pixels in red",
                               false, -1, "K", cmd);
  TCLAP::ValueArg<int> topview("", "topview",
                               "Also write <name>.topview.png: sweep K seen from above (static "
                               "grey, standing actors blue, moving actors red, sensor path green)",
                               false, -1, "K", cmd);
  TCLAP::ValueArg<std::string> world("", "world",
                                     "Also write the generated world of a procedural scenario "
                                     "(YAML: floor, static, actors, platform) to this file",
                                     false, "", "file.yaml", cmd);
  TCLAP::ValueArg<int> compression("", "compression",
                                   "gzip level of the rawlog: 0 (plain, largest) to 3 (default 1)",
                                   false, 1, "0-3", cmd);
  TCLAP::SwitchArg quiet("q", "quiet", "No progress output", cmd);
  if (const auto stop = dynobj::apps::parseCommandLine(cmd, argc, argv)) return *stop;

  auto overrides = parseSets(sets.getValue());
  if (frames.isSet()) overrides["frames"] = std::to_string(frames.getValue());
  if (seed.isSet()) overrides["seed"] = std::to_string(seed.getValue());
  const dynobj::sim::LidarSimulator sim(dynobj::sim::Scenario::fromYamlFile(
      scenario.getValue(), dynobj::apps::shareDir(), overrides));
  const auto& s = sim.scenario();
  for (auto* arg : {&preview, &topview})
    if (arg->isSet() && (arg->getValue() < 0 || arg->getValue() >= s.frames))
      throw std::invalid_argument("--" + arg->getName() + " must be a sweep index in [0, " +
                                  std::to_string(s.frames - 1) + "]");
  if (world.isSet()) {
    if (s.world_yaml.empty())
      throw std::invalid_argument("--world: the scenario has no procedural: block");
    std::ofstream(world.getValue()) << s.world_yaml;
  }
  std::vector<Eigen::Vector3d> path;

  dynobj::sim::SequenceWriter writer(out.getValue(), s, compression.getValue());
  const bool tty = isatty(STDERR_FILENO) && !quiet.isSet();
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t points = 0, dynamic = 0;
  for (int k = 0; k < s.frames; k++) {
    const auto sweep = sim.simulate(k);
    writer.write(sweep);
    points += sweep.frame.validCount();
    dynamic += static_cast<std::size_t>(cv::countNonZero(sweep.dynamic));
    if (k == preview.getValue()) {
      const cv::Mat img =
          dynobj::io::overlayMask(dynobj::io::intensityToU8(sweep.frame), sweep.dynamic);
      dynobj::io::writePng(out.getValue() + "/" + s.name + ".preview.png",
                           dynobj::io::scaleRows(img, 2));
    }
    path.push_back(sweep.sensor_pose.translation());
    if (k == topview.getValue())
      dynobj::io::writePng(out.getValue() + "/" + s.name + ".topview.png",
                           dynobj::sim::topView(sweep, path));
    if (tty)
      std::cerr << "\r[dynobj-sim] " << s.name << ": sweep " << (k + 1) << "/" << s.frames
                << std::flush;
    else if (!quiet.isSet() && (k + 1) % std::max(1, s.frames / 10) == 0)
      std::cerr << "[dynobj-sim] " << s.name << ": sweep " << (k + 1) << "/" << s.frames << "\n";
  }
  writer.close();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (tty) std::cerr << "\n";
  std::printf(
      "dynobj-sim: %s: %d sweeps of %dx%d (%s), %d actors, %.0f points/sweep, %.2f%% dynamic, "
      "%.1f s (%.1f ms/sweep)\n  -> %s\n",
      s.name.c_str(), s.frames, s.sensor.rows, s.sensor.cols, s.sensor.model.c_str(),
      static_cast<int>(s.actors.size()), static_cast<double>(points) / s.frames,
      points ? 100.0 * static_cast<double>(dynamic) / static_cast<double>(points) : 0.0, secs,
      1000.0 * secs / s.frames, writer.rawlogPath().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-sim", [&] { return run(argc, argv); });
}
