// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/BoxTrackFile.h"

#include <fstream>
#include <sstream>

#include "dynobj/io/FormatError.h"

namespace dynobj::io {

std::vector<BoxTrackRow> readBoxTracks(const std::string& path) {
  std::ifstream in(path);
  if (!in) throwFormatError(path, "cannot open box-track file");
  const std::string header = "sweep,track,class,x,y,z,length,width,height,yaw";
  std::vector<BoxTrackRow> rows;
  bool have_header = false;
  std::string line;
  for (int no = 1; std::getline(in, line); no++) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::string where = path + ":" + std::to_string(no);
    if (!have_header) {
      if (line != header) throwFormatError(where, "expected the header '" + header + "'");
      have_header = true;
      continue;
    }
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string field; std::getline(ss, field, ',');) f.push_back(field);
    if (f.size() != 10)
      throwFormatError(where, "expected 10 fields, found " + std::to_string(f.size()));
    BoxTrackRow r;
    try {
      std::size_t used = 0;
      const long sweep = std::stol(f[0], &used);
      if (sweep < 0 || used != f[0].size()) throw std::invalid_argument("sweep");
      r.sweep = static_cast<std::size_t>(sweep);
      r.track = std::stoi(f[1]);
      r.cls = f[2];
      for (int i = 0; i < 3; i++) {
        r.centre(i) = std::stod(f[3 + i]);
        r.size(i) = std::stod(f[6 + i]);
      }
      r.yaw = std::stod(f[9]);
    } catch (const std::exception&) {
      throwFormatError(where, "a field is not a number (or the sweep is negative)");
    }
    if (!(r.size.minCoeff() > 0)) throwFormatError(where, "length, width and height must be > 0");
    rows.push_back(r);
  }
  if (!have_header) throwFormatError(path, "empty file (expected the header '" + header + "')");
  return rows;
}

}  // namespace dynobj::io
