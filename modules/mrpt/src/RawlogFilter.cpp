// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/RawlogFilter.h"

#include <dynobj/io/LabelFile.h>
#include <dynobj/io/TracksCsv.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>

#include "RawlogPipeline.h"
#include "dynobj/mrptio/RawlogReader.h"
#include "dynobj/mrptio/RawlogWriter.h"

namespace dynobj::mrptio {
namespace {

namespace fs = std::filesystem;

/// The label file of one sensor, opened at its first frame.
class LabelsOut {
 public:
  explicit LabelsOut(std::string path) : path_(std::move(path)) {}
  void write(const std::string& sensor, const core::DetectionResult& r) {
    if (!writer_) {
      sensor_ = sensor;
      writer_.emplace(path_, r.dynamic.rows, r.dynamic.cols);
    } else if (sensor != sensor_) {
      throw std::runtime_error("--labels-out: the rawlog has several LiDARs ('" + sensor_ + "', '" +
                               sensor + "'); choose one with --sensor-label");
    }
    writer_->write(r.timestamp_ns, io::pixelsOfMask(r.dynamic));
  }
  void close() {
    if (writer_) writer_->close();
  }

 private:
  std::string path_, sensor_;
  std::optional<io::LabelFileWriter> writer_;
};

/// The single-threaded loop: read, detect, write, one entry after the other.
RawlogFilterSummary filterSerial(RawlogReader& reader, RawlogWriter& out,
                                 const RawlogFilterOptions& o, const detail::ResultSink& onResult) {
  DynamicObjectFilter filter(o.filter);
  RawlogEntry e;
  std::vector<mrpt::obs::CObservation::Ptr> extra;
  while (reader.next(e)) {
    if (e.index >= o.from && e.index <= o.to) {  // outside --from/--to: copied unchanged
      extra.clear();
      if (e.isPair()) {
        for (auto& obs : *e.sensory_frame) onResult(*obs, filter.filter(obs, &extra));
        for (auto& obs : extra) e.sensory_frame->insert(obs);
        extra.clear();
      } else {
        onResult(*e.observation, filter.filter(e.observation, &extra));
      }
    }
    if (e.isPair()) {
      if (e.actions) out.write(*e.actions);
      out.write(*e.sensory_frame);
    } else {
      out.write(*e.observation);
      for (auto& obs : extra) out.write(*obs);
      extra.clear();
    }
    if (o.progress) o.progress(e.index + 1, filter.summary());
  }
  return {reader.entriesRead(), filter.summary()};
}

}  // namespace

unsigned RawlogFilterOptions::threadCount() const {
  if (threads > 0) return threads;
  return RawlogWriter::hardwareThreads();
}

RawlogFilterSummary filterRawlog(const std::string& input, const std::string& output,
                                 const RawlogFilterOptions& o) {
  // Never touch the input; never replace an output unless asked.
  std::error_code ec;
  if (fs::exists(output) && fs::equivalent(input, output, ec))
    throw std::runtime_error("the output '" + output + "' is the input file");
  if (fs::exists(output) && !o.overwrite)
    throw std::runtime_error("output '" + output + "' exists (use -w to replace it)");
  const unsigned threads = o.threadCount();
  RawlogReader reader(input);
  RawlogWriter out(output, o.compression_level, threads);
  std::optional<LabelsOut> labels;
  if (!o.labels_out.empty()) labels.emplace(o.labels_out);
  std::optional<io::TracksCsvWriter> tracks;
  if (!o.tracks_out.empty()) tracks.emplace(o.tracks_out);
  detail::ResultSink onResult;
  if (labels || tracks)
    onResult = [&](const mrpt::obs::CObservation& obs, const core::DetectionResult* r) {
      if (!r) return;
      if (tracks) tracks->write(obs.sensorLabel, *r);
      if (labels) labels->write(obs.sensorLabel, *r);
    };
  else
    onResult = [](const mrpt::obs::CObservation&, const core::DetectionResult*) {};
  const RawlogFilterSummary summary =
      threads > 1 ? detail::filterPipelined(reader, out, o, threads, onResult, labels || tracks)
                  : filterSerial(reader, out, o, onResult);
  if (summary.filter.lidar == 0 && !o.allow_none)  // nothing written: the .partial is removed
    throw std::runtime_error("'" + input +
                             "': " + summary.filter.nothingFiltered(o.filter.sensor_label));
  out.commit();
  if (labels) labels->close();
  if (tracks) tracks->close();
  return summary;
}

}  // namespace dynobj::mrptio
