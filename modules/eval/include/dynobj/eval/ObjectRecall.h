// SPDX-License-Identifier: BSD-3-Clause
// Object-level recall: a ground-truth moving object seen in a sweep (at least `min_points` of its
// pixels, from the instance file <name>.gt.instances) counts as detected when at least
// `min_flagged` of those pixels are predicted dynamic. Which objects move, and their class, come
// from <name>.gt.objects.csv.
#pragma once

#include <dynobj/io/LabelFile.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dynobj::eval {

/// The moving objects of each sweep, read from <name>.gt.objects.csv.
struct GroundTruthObjects {
  struct Sweep {
    std::int64_t timestamp_ns = 0;
    std::map<int, std::string> moving;  ///< object id -> class
  };
  std::vector<Sweep> sweeps;  ///< by sweep index

  /// Throws EvaluationError "<path>:<line>: <problem>" on a malformed file.
  static GroundTruthObjects read(const std::string& path);
};

struct ObjectTally {
  std::int64_t present = 0;   ///< object-sweeps with at least min_points pixels
  std::int64_t detected = 0;  ///< ... of which at least min_flagged were flagged
  std::optional<double> recall() const;
};

class ObjectRecall {
 public:
  explicit ObjectRecall(int min_points = 10, double min_flagged = 0.5);

  /// One sweep: its instance pixels, the predicted dynamic pixels (ascending) and its moving
  /// objects. Throws EvaluationError when the timestamps differ.
  void add(const io::LabelSweep& instances, const std::vector<std::uint32_t>& predicted,
           const GroundTruthObjects::Sweep& objects);

  /// One object in one sweep, of class `cls`: `points` of its points, `flagged` of them predicted
  /// moving (counted when points >= min_points).
  void count(const std::string& cls, std::int64_t points, std::int64_t flagged);

  const ObjectTally& total() const { return total_; }
  const std::map<std::string, ObjectTally>& byClass() const { return by_class_; }
  int minPoints() const { return min_points_; }

 private:
  int min_points_;
  double min_flagged_;
  ObjectTally total_;
  std::map<std::string, ObjectTally> by_class_;
};

}  // namespace dynobj::eval
