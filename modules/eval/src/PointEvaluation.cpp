// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/PointEvaluation.h"

#include <dynobj/io/AtomicFile.h>
#include <dynobj/io/PoseFile.h>
#include <dynobj/io/SemanticKittiLabel.h>
#include <dynobj/mrptio/SequenceRunner.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "dynobj/eval/SequenceMetrics.h"

namespace dynobj::eval {
namespace {

namespace fs = std::filesystem;

/// A frame's points and, for each, its pixel (-1: none): the file's points for point-cloud
/// sources, else one point per valid pixel.
struct FramePoints {
  const core::PointCloud* cloud = nullptr;
  const std::vector<std::int32_t>* pixel = nullptr;
  core::PointCloud own_cloud;
  std::vector<std::int32_t> own_pixel;

  explicit FramePoints(const mrptio::Frame& f) {
    if (!f.points.empty()) {
      cloud = &f.points;
      pixel = &f.frame.point_pixel;
      if (pixel->size() != cloud->size())
        throw std::logic_error("a frame's points and point_pixel differ in number");
      return;
    }
    const core::LidarFrame& fr = f.frame;
    for (int px = 0; px < static_cast<int>(fr.pixelCount()); px++) {
      if (!fr.valid(px / fr.cols(), px % fr.cols())) continue;
      const cv::Vec3f& p = fr.pointAt(px);
      own_cloud.push_back(p[0], p[1], p[2]);
      own_pixel.push_back(px);
    }
    cloud = &own_cloud;
    pixel = &own_pixel;
  }
};

std::string sweepName(std::size_t k) {
  char b[32];
  std::snprintf(b, sizeof(b), "%06zu.label", k);
  return b;
}

void makeFolder(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw std::runtime_error("cannot create folder '" + dir + "'");
}

/// Per mode: each sweep's predicted points (indices of flagged points, ascending).
struct ModeRun {
  RunResult result;
  std::vector<std::vector<std::uint32_t>> flagged;
  std::vector<double> ms;
};

}  // namespace

std::string describePointMode(const std::string& mode) {
  if (mode == "online")
    return "this detector, online (causal: icp-slam-dynobj, rawlog-dynobj --online)";
  if (mode == "offline")
    return "this detector, offline (each sweep held for the hindsight lag: rawlog-dynobj, "
           "dynobj-detect, dynobj-mapclean)";
  throw std::invalid_argument("unknown mode '" + mode + "' (online, offline)");
}

std::vector<std::string> parsePointModes(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream ss(list);
  for (std::string m; std::getline(ss, m, ',');) {
    if (m.empty()) continue;
    try {
      describePointMode(m);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--modes: ") + e.what());
    }
    out.push_back(m);
  }
  if (out.empty()) throw std::invalid_argument("--modes: no mode given (online, offline)");
  return out;
}

PointEvaluation evaluatePoints(mrptio::FrameSource& source, PointTruthSource& truth,
                               const PointEvalOptions& opts) {
  if (opts.modes.empty()) throw std::invalid_argument("no mode to run");
  for (const auto& m : opts.modes) describePointMode(m);
  PointEvaluation out;
  std::vector<ModeRun> runs(opts.modes.size());
  std::vector<Eigen::Isometry3d> ego;  // the first run's sensor poses (first sweep = identity)
  std::vector<std::int64_t> stamps;
  for (std::size_t m = 0; m < opts.modes.size(); m++) {
    const std::string& mode = opts.modes[m];
    ModeRun& run = runs[m];
    run.result.mode = mode;
    run.result.description = describePointMode(mode);
    run.result.timing.emplace();
    mrptio::SequenceOptions so;
    so.detector = opts.params;
    if (mode == "online") so.detector.hindsight.lag = 0;
    so.single_sensor = true;
    so.max_frames = opts.max_frames;
    source.rewind();
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    mrptio::SequenceRunner(source, so).run([&](const mrptio::FrameResult& fr) {
      const core::DetectionResult& r = *fr.detection;
      const FramePoints pts(fr.frame);
      std::vector<std::uint32_t> flagged;
      const std::uint8_t* dyn = r.dynamic.ptr<std::uint8_t>(0);
      for (std::size_t i = 0; i < pts.pixel->size(); i++) {
        const std::int32_t px = (*pts.pixel)[i];
        if (px >= 0 && dyn[px]) flagged.push_back(static_cast<std::uint32_t>(i));
      }
      run.flagged.push_back(std::move(flagged));
      run.ms.push_back(r.timings.total);
      run.result.timing->add(r.timings);
      if (fr.frame.index > 0 && !r.ego_motion.ok) run.result.ego_failed++;
      run.result.rows = fr.frame.frame.rows();
      run.result.cols = fr.frame.frame.cols();
      run.result.rate_hz = fr.frame.frame.sensor.frequency;
      if (m == 0) {
        if (!stamps.empty()) pose = pose * r.ego_motion.motion;
        ego.push_back(pose);
        stamps.push_back(fr.frame.frame.timestamp_ns);
      }
      if (opts.progress) opts.progress(mode, fr.frame.index + 1);
    });
  }

  if (truth.needsPoses()) {
    std::vector<Eigen::Isometry3d> poses = ego;
    if (!opts.truth_poses.empty()) {
      const std::vector<io::TimedPose> given = io::readPoseFile(opts.truth_poses);
      for (std::size_t k = 0; k < stamps.size(); k++) {
        const io::TimedPose* p =
            given.size() == stamps.size() ? &given[k] : io::findPose(given, stamps[k]);
        if (!p)
          throw EvaluationError("'" + opts.truth_poses + "' has no pose for sweep " +
                                std::to_string(k));
        poses[k] = p->pose;
      }
    }
    truth.setSensorPoses(poses, stamps);
  }
  if (!opts.truth_dir.empty()) makeFolder(opts.truth_dir);
  if (!opts.predictions_dir.empty())
    for (const auto& m : opts.modes) makeFolder(opts.predictions_dir + "/" + m);

  // Score: the truth of each sweep once, against every mode's predictions.
  for (ModeRun& run : runs) run.result.objects.emplace(opts.min_object_points);
  source.rewind();
  mrptio::Frame f;
  for (std::size_t k = 0; k < stamps.size() && source.next(f); k++) {
    const FramePoints pts(f);
    const SweepTruth t = truth.truthOf(k, *pts.cloud);
    if (!opts.truth_dir.empty())
      io::writeSemanticKittiLabels(opts.truth_dir + "/" + sweepName(k), toSemanticKitti(t, truth));
    out.points += t.label.size();
    for (std::size_t m = 0; m < runs.size(); m++) {
      ModeRun& run = runs[m];
      std::vector<std::uint8_t> pred(t.label.size(), 0);
      for (std::uint32_t i : run.flagged[k]) pred[i] = 1;
      Confusion c;
      struct Seen {
        std::int64_t points = 0, flagged = 0;
        Eigen::Vector2d sum{0, 0};
      };
      std::map<int, Seen> objects;
      for (std::size_t i = 0; i < pred.size(); i++) {
        if (t.label[i] == PointLabel::Unknown) continue;
        const bool moving = t.label[i] == PointLabel::Moving;
        c.tp += moving && pred[i];
        c.fp += !moving && pred[i];
        c.fn += moving && !pred[i];
        c.tn += !moving && !pred[i];
        if (moving) {
          Seen& o = objects[t.object[i]];
          o.points++;
          o.flagged += pred[i];
          o.sum += Eigen::Vector2d(pts.cloud->x[i], pts.cloud->y[i]);
        }
      }
      if (m == 0) {
        out.known_points += static_cast<std::size_t>(c.tp + c.fp + c.fn + c.tn);
        out.moving_points += static_cast<std::size_t>(c.tp + c.fn);
      }
      run.result.metrics.add(f.frame.timestamp_ns, c, run.ms[k]);
      for (const auto& [id, o] : objects) {
        run.result.objects->count(truth.className(id), o.points, o.flagged);
        out.sightings.push_back({opts.modes[m], k, id, truth.className(id), o.points, o.flagged,
                                 (o.sum / static_cast<double>(o.points)).norm()});
      }
      if (!opts.predictions_dir.empty()) {
        std::vector<std::uint32_t> labels(pred.size());
        for (std::size_t i = 0; i < pred.size(); i++)
          labels[i] = pred[i] ? io::semantic_kitti::kMoving : io::semantic_kitti::kStatic;
        io::writeSemanticKittiLabels(
            opts.predictions_dir + "/" + opts.modes[m] + "/" + sweepName(k), labels);
      }
    }
    out.sweeps++;
  }
  if (out.sweeps != stamps.size())
    throw std::runtime_error(source.describe() + " gave fewer frames on the second reading");
  if (const auto* boxes = dynamic_cast<const BoxTruth*>(&truth)) out.tracks = boxes->tracks();
  for (ModeRun& run : runs) out.runs.push_back(std::move(run.result));
  return out;
}

std::string sightingsCsv(const std::vector<ObjectSighting>& sightings) {
  std::ostringstream s;
  s << "mode,sweep,object,class,points,flagged,range\n";
  for (const ObjectSighting& o : sightings) {
    char b[32];
    std::snprintf(b, sizeof(b), "%.1f", o.range);
    s << o.mode << "," << o.sweep << "," << o.object << "," << o.cls << "," << o.points << ","
      << o.flagged << "," << b << "\n";
  }
  return s.str();
}

std::string trackMotionCsv(const std::vector<TrackMotion>& tracks) {
  std::ostringstream s;
  s << "track,class,sweeps,first,last,max_speed,moving,static,unknown\n";
  for (const TrackMotion& t : tracks) {
    double hi = 0;
    int n[3] = {0, 0, 0};
    for (std::size_t i = 0; i < t.sweeps.size(); i++) {
      if (std::isfinite(t.speed[i])) hi = std::max(hi, t.speed[i]);
      n[static_cast<int>(t.state[i])]++;
    }
    char b[64];
    std::snprintf(b, sizeof(b), "%.2f", hi);
    s << t.track << "," << t.cls << "," << t.sweeps.size() << "," << t.sweeps.front() << ","
      << t.sweeps.back() << "," << b << "," << n[1] << "," << n[0] << "," << n[2] << "\n";
  }
  return s.str();
}

}  // namespace dynobj::eval
