// SPDX-License-Identifier: BSD-3-Clause
// Internal: what filterRawlog's two loops share. Each rawlog entry becomes a Job: its
// observations as Tasks, the LiDAR ones detected (converted, then DynamicObjectFilter::detect:
// by the single-threaded loop itself, or by the pipelined loop's lanes); then, in entry order,
// EntryWriter holds each detection for the hindsight lag (core::HindsightQueue: tracks confirmed
// later flag their earlier sweeps, as in dynobj-detect), tags the observation with its final
// result (DynamicObjectFilter::tag) and writes the entries in order once all of theirs are final.
#pragma once

#include <dynobj/core/HindsightQueue.h>

#include <atomic>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "dynobj/mrptio/RawlogFilter.h"
#include "dynobj/mrptio/RawlogReader.h"
#include "dynobj/mrptio/RawlogWriter.h"

namespace dynobj::mrptio::detail {

/// Called for every detected observation in entry order with its final detection.
using ResultSink =
    std::function<void(const mrpt::obs::CObservation&, const core::DetectionResult&)>;

/// One observation of an entry.
struct Task {
  mrpt::obs::CObservation::Ptr obs;
  std::unique_ptr<PreconvertedFrame> pre;           ///< its frame, when the filter converts it
  std::optional<core::DetectionResult> detected;    ///< its detection (a clone), until tagged
  std::vector<mrpt::obs::CObservation::Ptr> extra;  ///< split mode: the removed points
  FilterSummary delta;  ///< what its detection and tagging added to the summary
};

/// One rawlog entry on its way from the reader to the writer.
struct Job {
  RawlogEntry entry;
  bool filtered = false;  ///< inside [from, to]
  std::vector<Task> tasks;
  std::atomic<std::size_t> pending{0};  ///< tasks still being detected (pipelined loop)
  std::size_t held = 0;                 ///< detections held for hindsight, not tagged yet
};
using JobPtr = std::shared_ptr<Job>;

/// Counts, times and data faults (no warnings) that `after` has more than `before`.
FilterSummary difference(const FilterSummary& after, const FilterSummary& before);

/// Detects task `t` with `filter` (converting its observation first unless it was converted
/// ahead); the detection is cloned into t.detected and the summary's change added to t.delta.
void detectTask(DynamicObjectFilter& filter, Task& t);

/// The second half of filterRawlog, on the calling thread: jobs come in entry order, detected.
class EntryWriter {
 public:
  /// `on_result` may be empty.
  EntryWriter(const RawlogFilterOptions& o, RawlogWriter& out, ResultSink on_result);
  /// Who takes back a written task's frame buffers (none: they are freed).
  void setRecycle(std::function<void(std::unique_ptr<PreconvertedFrame>)> recycle) {
    recycle_ = std::move(recycle);
  }

  /// Holds the job's detections for the lag; tags and writes what is final.
  void add(JobPtr job);
  /// End of the input: tags and writes everything still held.
  void finish();
  /// What tagging counted (LiDAR observations, points, dynamic points, its warnings).
  const FilterSummary& tagging() const { return tagger_.summary(); }
  std::size_t entriesWritten() const { return written_; }

 private:
  struct Ref {
    Job* job;
    std::size_t task;
  };
  void tag(core::HindsightQueue<Ref>::Item& h);
  /// Writes the jobs at the front whose detections are all tagged.
  void flush();

  const RawlogFilterOptions& o_;
  RawlogWriter& out_;
  ResultSink on_result_;
  std::function<void(std::unique_ptr<PreconvertedFrame>)> recycle_;
  DynamicObjectFilter tagger_;
  core::HindsightQueue<Ref> held_;
  std::function<void(core::HindsightQueue<Ref>::Item&)> release_;
  std::deque<JobPtr> pending_;
  FilterSummary running_;  ///< in entry order, for the progress callback
  std::size_t written_ = 0;
};

/// Reads `reader` to its end in a thread of its own, detects in one lane per sensor label (at most
/// `threads` lanes; each label's frames in order, different labels in parallel), and hands the
/// jobs in entry order to `writer` from the calling thread. Returns what the lanes and the reader
/// counted (the writer's tagging is counted by the writer).
FilterSummary detectPipelined(RawlogReader& reader, EntryWriter& writer,
                              const RawlogFilterOptions& o, unsigned threads);

}  // namespace dynobj::mrptio::detail
