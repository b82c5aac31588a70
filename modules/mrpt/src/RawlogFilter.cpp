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
  void write(const std::string& sensor, const core::DetectionResult& r) {  // in time order
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

/// The single-threaded loop: read, detect, hand on to the writer, one entry after the other.
FilterSummary detectSerial(RawlogReader& reader, detail::EntryWriter& writer,
                           const RawlogFilterOptions& o) {
  DynamicObjectFilter filter(o.filter);
  for (;;) {
    auto job = std::make_shared<detail::Job>();
    if (!reader.next(job->entry)) break;
    job->filtered = job->entry.index >= o.from && job->entry.index <= o.to;
    for (auto& obs : job->entry.observations()) {
      detail::Task& t = job->tasks.emplace_back();
      t.obs = obs;
      if (job->filtered) detail::detectTask(filter, t);  // outside --from/--to: copied unchanged
    }
    writer.add(std::move(job));
  }
  return filter.summary();
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
  detail::ResultSink on_result;
  if (labels || tracks)
    on_result = [&](const mrpt::obs::CObservation& obs, const core::DetectionResult& r) {
      if (tracks) tracks->write(obs.sensorLabel, r);
      if (labels) labels->write(obs.sensorLabel, r);
    };
  detail::EntryWriter writer(o, out, on_result);
  FilterSummary total = threads > 1 ? detail::detectPipelined(reader, writer, o, threads)
                                    : detectSerial(reader, writer, o);
  writer.finish();
  total += writer.tagging();
  if (total.lidar == 0 && !o.allow_none)  // nothing written: the .partial is removed
    throw std::runtime_error("'" + input + "': " + total.nothingFiltered(o.filter.sensor_label));
  out.commit();
  if (labels) labels->close();
  if (tracks) tracks->close();
  return {reader.entriesRead(), total};
}

}  // namespace dynobj::mrptio
