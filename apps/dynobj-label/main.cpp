// SPDX-License-Identifier: BSD-3-Clause
// dynobj-label: label the moving objects of a rawlog in the browser (docs/usage.md). Serves the
// page of share/dynobj/label/ on 127.0.0.1; labels are saved (every few seconds and on exit) as
// <output>.labels, <output>.instances and <output>.session.json; an existing output is resumed.
#include <dynobj/io/AtomicFile.h>
#include <dynobj/label/LabelServer.h>
#include <dynobj/label/SweepSource.h>
#include <signal.h>

#include <iostream>
#include <thread>

#include "../common/AppOptions.h"

namespace {

using namespace dynobj;

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("dynobj-label: label moving objects in a rawlog, in the browser", ' ', "0.1");
  TCLAP::ValueArg<std::string> in("i", "input", "Input rawlog (never written)", true, "",
                                  "file.rawlog", cmd);
  const apps::OutputArg out(cmd,
                            "Output base name: writes <base>.labels, .instances, "
                            ".session.json (resumed when they exist)",
                            true, "base", "");
  TCLAP::ValueArg<int> port("p", "port", "Port on 127.0.0.1 (0 = any free one)", false, 8080, "N",
                            cmd);
  TCLAP::ValueArg<std::string> pre("", "prelabels",
                                   "Detector output (label file v1, dynobj-detect -o) to load as "
                                   "pre-labels, marked until confirmed",
                                   false, "", "file.labels", cmd);
  TCLAP::ValueArg<std::string> config("c", "config",
                                      "Detector parameters (INI): region growing, ground, "
                                      "ego-motion",
                                      false, "", "file.ini", cmd);
  TCLAP::ValueArg<double> autosave("", "autosave", "Save every N seconds when changed (0 = off)",
                                   false, 2.0, "s", cmd);
  TCLAP::SwitchArg fresh("w", "overwrite", "Start afresh: ignore (and later replace) the output",
                         cmd);
  apps::SensorArgs sensor(cmd);
  if (const auto stop = apps::parseCommandLine(cmd, argc, argv)) return *stop;
  sigset_t stop_signals;       // Ctrl+C / kill: stop serving, then the final save (every thread
  sigemptyset(&stop_signals);  // started from here on inherits the mask)
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  std::string base = out.getValue();
  for (const char* ext : {".labels", ".instances"})
    if (base.size() > std::string(ext).size() &&
        base.compare(base.size() - std::string(ext).size(), std::string::npos, ext) == 0)
      base.resize(base.size() - std::string(ext).size());
  { io::AtomicFile probe(base + ".instances"); }  // unwritable output: fail now, not after work

  const core::DetectorParams det = apps::loadDetectorParams(config.getValue());
  label::LabelParams params;
  params.growing = det.region_growing;
  params.ground = det.ground;
  params.ego_motion = det.ego_motion;
  params.distance = det.region_growing.distance;
  params.max_extent = det.region_growing.max_extent;

  std::cerr << "[dynobj-label] indexing " << in.getValue() << " ...\n";
  label::RawlogSweeps sweeps(in.getValue(), sensor.converter(), sensor.label(),
                             [](std::size_t entries, std::uint64_t bytes) {
                               if (entries % 2000 == 0)
                                 std::cerr << "[dynobj-label] " << entries << " entries, "
                                           << bytes / 1000000 << " MB\n";
                             });
  label::LabelEditor session(sweeps, params);
  std::cerr << "[dynobj-label] " << session.size() << " sweeps of '" << sweeps.sensorLabel()
            << "', " << session.rows() << "x" << session.cols() << "\n";
  if (!fresh.isSet() && std::filesystem::exists(base + ".instances")) {
    session.load(base);
    std::cerr << "[dynobj-label] resumed " << base << ".instances: " << session.reviewedCount()
              << " of " << session.size() << " sweeps reviewed, " << session.objects().size()
              << " objects\n";
  }
  if (pre.isSet())
    std::cerr << "[dynobj-label] " << session.loadPrelabels(pre.getValue()) << " pre-labels from "
              << pre.getValue() << "\n";

  label::ServerOptions so;
  so.port = port.getValue();
  so.page_dir = apps::shareDir() + "/label";
  so.output = base;
  so.rawlog = in.getValue();
  so.autosave_s = autosave.getValue();
  label::LabelServer server(session, so);
  const int bound = server.bind();
  std::cout << "dynobj-label: open http://127.0.0.1:" << bound << "/ (Ctrl+C to stop)" << std::endl;
  std::thread waiter([&] {
    int sig = 0;
    sigwait(&stop_signals, &sig);
    server.stop();
  });
  server.run();
  pthread_kill(waiter.native_handle(), SIGTERM);  // wakes the waiter if nothing else did
  waiter.join();
  std::string error;
  if (!server.save(error, true)) {
    std::cerr << "dynobj-label: error: the last changes were NOT saved: " << error << "\n";
    return 1;
  }
  std::cerr << "[dynobj-label] saved " << base << ".labels, .instances, .session.json ("
            << session.reviewedCount() << " of " << session.size() << " sweeps reviewed)\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-label", [&] { return run(argc, argv); });
}
