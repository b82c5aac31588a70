// SPDX-License-Identifier: BSD-3-Clause
// Test tool: writes a folder of PCD sweeps in a spinning LiDAR's raw firing order (no ring field:
// the lasers as they fired, no-returns left out), from the simulated firing patterns of the row
// recovery tests (modules/core/tests/UnorderedSweep.h), for the command-line tests of
// dynobj-import.
//   raw_firing_sweeps <vlp16|hdl32|hdl64|vls128> <folder> <sweeps> <sweep_deg> [shuffle]
#include <dynobj/io/PcdFile.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "UnorderedSweep.h"

int main(int argc, char** argv) {
  if (argc < 5 || argc > 6) {
    std::fprintf(stderr,
                 "usage: raw_firing_sweeps <vlp16|hdl32|hdl64|vls128> <folder> <sweeps> "
                 "<sweep_deg> [shuffle]\n");
    return 2;
  }
  const std::string name = argv[1];
  dynobj::test::FiringPattern p;
  if (name == "vlp16") {
    p = dynobj::test::vlp16Pattern();
  } else if (name == "hdl32") {
    p = dynobj::test::hdl32Pattern();
  } else if (name == "hdl64") {
    p = dynobj::test::hdl64Pattern();
  } else if (name == "vls128") {
    p = dynobj::test::vls128Pattern();
  } else {
    std::fprintf(stderr, "raw_firing_sweeps: unknown pattern '%s'\n", name.c_str());
    return 2;
  }
  const std::filesystem::path folder = argv[2];
  const int sweeps = std::stoi(argv[3]);
  const double sweep_deg = std::stod(argv[4]);
  const bool shuffled = argc == 6 && std::string(argv[5]) == "shuffle";
  std::filesystem::create_directories(folder);
  for (int k = 0; k < sweeps; k++) {
    std::vector<int> laser;
    dynobj::core::PointCloud c =
        dynobj::test::rawFiringSweep(p, laser, sweep_deg, 30.0, static_cast<unsigned>(k + 1));
    if (shuffled) dynobj::test::shuffle(c, laser);
    char file[32];
    std::snprintf(file, sizeof(file), "%06d.pcd", k);
    dynobj::io::writePcd((folder / file).string(), c);
  }
  return 0;
}
