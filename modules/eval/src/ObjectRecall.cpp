// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/ObjectRecall.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "dynobj/eval/SequenceMetrics.h"

namespace dynobj::eval {
namespace {

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string field;
  while (std::getline(ss, field, ',')) out.push_back(field);
  return out;
}

}  // namespace

GroundTruthObjects GroundTruthObjects::read(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw EvaluationError(path + ": cannot open objects file");
  std::string line;
  const std::string header = "sweep,timestamp_ns,id,class,x,y,z,vx,vy,speed,moving,points";
  if (!std::getline(in, line) || line != header)
    throw EvaluationError(path + ":1: expected the header '" + header + "'");
  GroundTruthObjects g;
  for (std::size_t no = 2; std::getline(in, line); no++) {
    const auto bad = [&](const std::string& what) {
      return EvaluationError(path + ":" + std::to_string(no) + ": " + what);
    };
    const auto f = splitCsv(line);
    if (f.size() != 12) throw bad("expected 12 fields, found " + std::to_string(f.size()));
    std::size_t sweep = 0;
    std::int64_t stamp = 0;
    int id = 0, moving = 0;
    try {
      sweep = std::stoul(f[0]);
      stamp = std::stoll(f[1]);
      id = std::stoi(f[2]);
      moving = std::stoi(f[10]);
    } catch (const std::exception&) {
      throw bad("non-numeric sweep, timestamp, id or moving field");
    }
    if (sweep != g.sweeps.size() && sweep + 1 != g.sweeps.size())
      throw bad("sweep " + std::to_string(sweep) + " out of order");
    if (sweep == g.sweeps.size()) {
      g.sweeps.emplace_back();
      g.sweeps.back().timestamp_ns = stamp;
    }
    if (g.sweeps.back().timestamp_ns != stamp)
      throw bad("timestamp differs from the sweep's first row");
    if (moving) g.sweeps.back().moving[id] = f[3];
  }
  return g;
}

std::optional<double> ObjectTally::recall() const {
  if (present == 0) return std::nullopt;
  return static_cast<double>(detected) / static_cast<double>(present);
}

ObjectRecall::ObjectRecall(int min_points, double min_flagged)
    : min_points_(min_points), min_flagged_(min_flagged) {}

void ObjectRecall::add(const io::LabelSweep& instances, const std::vector<std::uint32_t>& predicted,
                       const GroundTruthObjects::Sweep& objects) {
  if (instances.timestamp_ns != objects.timestamp_ns)
    throw EvaluationError("instances at t = " + std::to_string(instances.timestamp_ns) +
                          " ns but objects at t = " + std::to_string(objects.timestamp_ns) + " ns");
  std::map<int, std::pair<std::int64_t, std::int64_t>> seen;  // id -> (pixels, flagged)
  for (std::size_t i = 0; i < instances.pixels.size(); i++) {
    const int id = instances.ids[i];
    if (!objects.moving.count(id)) continue;
    auto& [n, flagged] = seen[id];
    n++;
    flagged += std::binary_search(predicted.begin(), predicted.end(), instances.pixels[i]) ? 1 : 0;
  }
  for (const auto& [id, counts] : seen) count(objects.moving.at(id), counts.first, counts.second);
}

void ObjectRecall::count(const std::string& cls, std::int64_t points, std::int64_t flagged) {
  if (points < min_points_) return;
  const bool hit = static_cast<double>(flagged) >= min_flagged_ * static_cast<double>(points);
  for (ObjectTally* t : {&total_, &by_class_[cls]}) {
    t->present++;
    t->detected += hit ? 1 : 0;
  }
}

}  // namespace dynobj::eval
