// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/ExperimentRunner.h"

#include <dynobj/io/AtomicFile.h>
#include <dynobj/io/LabelFile.h>
#include <dynobj/mrptio/PoseConversion.h>
#include <dynobj/mrptio/RawlogFrameSource.h>
#include <dynobj/mrptio/SequenceRunner.h>
#include <dynobj/mrptio/TimeConversion.h>
#include <dynobj/sim/LidarSimulator.h>
#include <dynobj/sim/SequenceWriter.h>
#include <mrpt/maps/CPointCloudFilterByDistance.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/poses/CPose3D.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "dynobj/eval/Overlay.h"

namespace dynobj::eval {
namespace {

/// 64-bit FNV-1a of a byte string, in hex.
std::string fnv1a(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ULL;
  std::ostringstream o;
  o << std::hex << h;
  return o.str();
}

/// What the simulator makes of a scenario, in a few bytes: a hash of one sweep's ranges,
/// intensities, ground truth and pose (any change to the sensor, noise, intensity or scene models
/// shows here).
std::string sweepFingerprint(const sim::SimulatedSweep& s) {
  std::string b;
  const auto add = [&](const cv::Mat& m) {
    const cv::Mat c = m.isContinuous() ? m : m.clone();
    b.append(reinterpret_cast<const char*>(c.data), c.total() * c.elemSize());
  };
  add(s.frame.range);
  add(s.frame.intensity);
  add(s.dynamic);
  b.append(reinterpret_cast<const char*>(s.sensor_pose.matrix().data()), 16 * sizeof(double));
  b.append(std::to_string(s.timestamp_ns));
  return fnv1a(b);
}

namespace fs = std::filesystem;

std::string ifExists(const std::string& path) {
  return fs::exists(path) ? path : std::string();
}

/// MRPT's CPointCloudFilterByDistance over the valid pixels of each frame (default options:
/// a point is deleted when the previous keyframe has no point within min_dist of it).
class MrptDistanceFilter {
 public:
  void process(const core::LidarFrame& f, const Eigen::Isometry3d& sensor_in_world,
               cv::Mat_<std::uint8_t>& mask) {
    cloud_.clear();
    pixel_.clear();
    for (int r = 0; r < f.rows(); r++)
      for (int c = 0; c < f.cols(); c++)
        if (f.isValid(r, c)) {
          const cv::Vec3f& p = f.xyz(r, c);
          cloud_.insertPoint(p[0], p[1], p[2]);
          pixel_.push_back(r * f.cols() + c);
        }
    std::vector<bool> deleted;
    mrpt::maps::CPointCloudFilterBase::TExtraFilterParams extra;
    extra.out_deletion_mask = &deleted;
    extra.do_not_delete = true;
    filter_.filter(&cloud_, mrptio::fromUnixNs(f.timestamp_ns), mrptio::toCPose3D(sensor_in_world),
                   &extra);
    mask.create(f.rows(), f.cols());
    mask.setTo(0);
    for (std::size_t i = 0; i < deleted.size() && i < pixel_.size(); i++)
      if (deleted[i]) mask(pixel_[i] / f.cols(), pixel_[i] % f.cols()) = 255;
  }

 private:
  mrpt::maps::CPointCloudFilterByDistance filter_;
  mrpt::maps::CSimplePointsMap cloud_;
  std::vector<int> pixel_;
};

}  // namespace

SequenceFiles SequenceFiles::locate(const std::string& path) {
  SequenceFiles s;
  if (fs::is_directory(path)) {
    for (const auto& e : fs::directory_iterator(path))
      if (e.path().extension() == ".rawlog") {
        if (!s.rawlog.empty()) throw EvaluationError("'" + path + "' holds more than one .rawlog");
        s.rawlog = e.path().string();
      }
    if (s.rawlog.empty()) throw EvaluationError("no .rawlog in '" + path + "'");
  } else if (fs::exists(path)) {
    s.rawlog = path;
  } else {
    throw EvaluationError("'" + path + "' does not exist");
  }
  const fs::path base = fs::path(s.rawlog).replace_extension();
  s.name = base.filename().string();
  s.labels = base.string() + ".gt.labels";
  if (!fs::exists(s.labels))
    throw EvaluationError("no ground truth '" + s.labels + "' beside the rawlog");
  s.instances = ifExists(base.string() + ".gt.instances");
  s.objects = ifExists(base.string() + ".gt.objects.csv");
  s.poses = ifExists(base.string() + ".gt.tum");
  return s;
}

SequenceFiles SequenceFiles::prepare(const std::string& input, const std::string& out_dir,
                                     const std::string& share_dir, int frames) {
  if (fs::path(input).extension() != ".yaml") return locate(input);
  std::map<std::string, std::string> overrides;
  if (frames > 0) overrides["frames"] = std::to_string(frames);
  const sim::LidarSimulator simulator(sim::Scenario::fromYamlFile(input, share_dir, overrides));
  const sim::Scenario& sc = simulator.scenario();
  const std::string dir = out_dir + "/" + sc.name;
  // The stamp beside the rawlog says what it was simulated from: the scenario's text, the
  // overrides (frames), the seed and count as read, and the simulator's fingerprint (a hash of its
  // first sweep). A sequence is reused only when its stamp matches; otherwise it is simulated
  // again.
  const std::string stamp_path = dir + "/" + sc.name + ".sim-stamp";
  std::ostringstream what;
  {
    std::ifstream yaml(input, std::ios::binary);
    what << "scenario " << fnv1a(std::string(std::istreambuf_iterator<char>(yaml), {})) << "\n";
  }
  what << "frames " << sc.frames << "\nseed " << sc.seed << "\n";
  for (const auto& [k, v] : overrides) what << "set " << k << "=" << v << "\n";
  what << "simulator " << sweepFingerprint(simulator.simulate(0)) << "\n";
  const std::string stamp = what.str();
  std::string old;
  if (std::ifstream f(stamp_path, std::ios::binary); f)
    old.assign(std::istreambuf_iterator<char>(f), {});
  const bool have = fs::exists(dir + "/" + sc.name + ".rawlog");
  SequenceFiles seq;
  if (have && old == stamp) {
    seq = locate(dir);
    seq.note = "reusing the sequence simulated earlier in " + dir + " (its " + sc.name +
               ".sim-stamp matches the scenario, seed, frames and simulator)";
    return seq;
  }
  sim::SequenceWriter writer(dir, sc);
  for (int k = 0; k < sc.frames; k++) writer.write(simulator.simulate(k));
  writer.close();
  io::AtomicFile f(stamp_path);
  f.stream() << stamp;
  f.commit();
  seq = locate(dir);
  seq.note = have ? "simulated " + dir + " again: " +
                        (old.empty() ? std::string("it had no .sim-stamp")
                                     : "the scenario, seed, frames or simulator changed")
                  : "simulated " + dir;
  return seq;
}

RunResult runExperiment(const SequenceFiles& seq, const RunOptions& opts) {
  if (!RunOptions::modes().count(opts.mode))
    throw EvaluationError("unknown mode '" + opts.mode + "'");
  const bool needs_poses = opts.mode != "intensity";
  if (needs_poses && seq.poses.empty())
    throw EvaluationError("mode '" + opts.mode + "' needs ground-truth poses (" + seq.name +
                          ".gt.tum)");
  std::optional<io::LabelFile> instances;
  std::optional<GroundTruthObjects> objects;
  if (!seq.instances.empty() && !seq.objects.empty()) {
    instances = io::LabelFile::read(seq.instances);
    objects = GroundTruthObjects::read(seq.objects);
  }

  RunResult res;
  res.mode = opts.mode;
  res.description = RunOptions::describe(opts.mode, opts.drift);
  res.sequence = seq.name;
  if (instances) res.objects.emplace(opts.min_object_points);
  if (opts.mode != "mrpt-distance") res.timing.emplace();

  DriftModel drift(opts.drift);
  mrptio::SequenceOptions so;
  so.detector = opts.params;
  so.detect = opts.mode != "mrpt-distance";
  if (needs_poses) so.poses = seq.poses;
  if (opts.mode == "drift")
    so.motion_model = [&](const Eigen::Isometry3d& m) { return drift.corrupt(m); };
  so.ground_truth = seq.labels;
  so.max_frames = opts.max_frames;
  mrptio::RawlogFrameSource source(seq.rawlog, mrptio::ObservationConverter(),
                                   {opts.sensor_label, 0, std::numeric_limits<std::size_t>::max()});
  MrptDistanceFilter mrpt_filter;
  cv::Mat_<std::uint8_t> baseline_mask;
  mrptio::SequenceRunner(source, so).run([&](const mrptio::FrameResult& fr) {
    const core::LidarFrame& f = fr.frame.frame;
    const std::size_t k = fr.frame.index;
    const cv::Mat_<std::uint8_t>* predicted = &baseline_mask;
    const core::DetectionResult* r = fr.detection;
    if (r) {
      predicted = &r->dynamic;
      res.timing->add(r->timings);
      if (k > 0 && !r->ego_motion.ok) res.ego_failed++;
    } else {
      mrpt_filter.process(f, fr.pose->pose, baseline_mask);
    }
    const std::vector<std::uint32_t> pred = io::pixelsOfMask(*predicted);
    res.metrics.add(f.timestamp_ns, fr.truth->pixels, pred, cv::countNonZero(f.valid),
                    r ? r->timings.total : -1);
    if (res.objects) {
      if (fr.truth_index >= instances->sweeps.size() || fr.truth_index >= objects->sweeps.size())
        throw EvaluationError(seq.instances + ": fewer sweeps than the rawlog");
      res.objects->add(instances->sweeps[fr.truth_index], pred, objects->sweeps[fr.truth_index]);
    }
    if (opts.overlay_sweeps.count(static_cast<int>(k)))
      res.overlays.emplace_back(static_cast<int>(k),
                                overlayImage(f, *predicted, fr.truthMask(),
                                             r ? r->objects : std::vector<core::TrackedObject>{}));
    res.rows = f.rows();
    res.cols = f.cols();
    res.rate_hz = f.sensor.frequency;
    if (opts.progress) opts.progress(k + 1);
  });
  return res;
}

}  // namespace dynobj::eval
