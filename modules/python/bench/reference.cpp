// SPDX-License-Identifier: BSD-3-Clause
// The C++ side of binding_overhead.py (docs/performance.md, "Python binding"): the work of
// dynobj.Detector.process() without Python, on the same arrays. Reads the sweeps
// binding_overhead.py wrote (<dir>/sweeps.txt: "<file> <rows> <cols> <timestamp_ns>" per sweep,
// cols 0 for an (N, 4) sweep; each file float32 x y z intensity, C order) into memory, then for
// each line read on stdin takes the next sweep through what process() runs with the GIL released:
// ArraySweeps::convert (the library's conversion), the detector, the mask in the input's layout;
// and answers with one line: "<conversion> <detector's own> <all> <all, CPU time of the process>
// [ms] <moving points>" (binding_overhead.py alternates it sweep by sweep with process()).
//   dynobj_python_bench_reference <dir> <threads 1|2> [sensor.ini]
#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/io/SensorFile.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "../src/ArraySweeps.h"

namespace {

using Clock = std::chrono::steady_clock;

double ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

/// The process's CPU time [ms] (all its threads; what Python's time.process_time() reads).
double cpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

struct Sweep {
  std::vector<float> data;
  std::size_t rows = 0, cols = 0;
  std::int64_t ns = 0;
};

std::vector<Sweep> readSweeps(const std::string& dir) {
  std::ifstream list(dir + "/sweeps.txt");
  if (!list) throw std::runtime_error("cannot read '" + dir + "/sweeps.txt'");
  std::vector<Sweep> out;
  std::string file;
  Sweep s;
  while (list >> file >> s.rows >> s.cols >> s.ns) {
    const std::size_t n = s.rows * (s.cols > 0 ? s.cols : 1) * 4;
    s.data.resize(n);
    std::ifstream in(dir + "/" + file, std::ios::binary);
    if (!in.read(reinterpret_cast<char*>(s.data.data()),
                 static_cast<std::streamsize>(n * sizeof(float))))
      throw std::runtime_error("'" + dir + "/" + file + "' is shorter than " +
                               std::to_string(n * sizeof(float)) + " bytes");
    out.push_back(s);
  }
  if (out.empty()) throw std::runtime_error("no sweep in '" + dir + "/sweeps.txt'");
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: dynobj_python_bench_reference <dir> <threads 1|2> [sensor.ini]\n";
    return 2;
  }
  try {
    const std::vector<Sweep> sweeps = readSweeps(argv[1]);
    dynobj::core::DetectorParams p;
    p.pipeline.threads = std::stoi(argv[2]);
    p.validate();
    std::optional<dynobj::core::SensorModel> sensor;
    if (argc > 3) sensor = dynobj::io::readSensorModel(argv[3]);
    dynobj::core::DynamicObjectDetector detector(p);
    dynobj::python::ArraySweeps convert(sensor);
    dynobj::mrptio::Frame frame;
    std::string line;
    for (const Sweep& s : sweeps) {
      if (!std::getline(std::cin, line)) break;
      dynobj::python::ArrayView v;
      v.data = s.data.data();
      v.rows = s.rows;
      v.cols = s.cols;
      const double cpu0 = cpuMs();
      const auto t0 = Clock::now();
      convert.convert(v, s.ns, frame);
      const auto t1 = Clock::now();
      const auto& r = detector.process(frame.frame);
      const dynobj::python::Mask mask = dynobj::python::ArraySweeps::maskOf(frame, r.dynamic);
      const auto t2 = Clock::now();
      const double cpu = cpuMs() - cpu0;
      std::size_t moving = 0;
      for (const std::uint8_t m : mask.values) moving += m;
      std::printf("%.4f %.4f %.4f %.4f %zu\n", ms(t0, t1), r.timings.total, ms(t0, t2), cpu,
                  moving);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::cerr << "dynobj_python_bench_reference: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
