// SPDX-License-Identifier: BSD-3-Clause
// filterRawlog's shared second half (EntryWriter) and its pipelined first half (threads > 1).
// Threads of the pipelined loop and what crosses between them:
//
//   reader thread      RawlogReader::next() (gzip inflate + MRPT deserialization); splits each
//                      entry into observation tasks, converts the LiDAR ones into frames
//                      (DynamicObjectFilter::preconvert, in entry order, as the single-threaded
//                      loop would), hands them to their label's lane, and queues the entry (a
//                      Job) for the writer: `jobs_`, bounded.
//   lane threads       one DynamicObjectFilter each (the label's detector); a label always goes
//                      to the same lane, so its frames are detected in order.
//   calling thread     takes the jobs in entry order, waits until its lanes are done with it and
//                      hands it to the EntryWriter (hindsight, tags, serialization into the
//                      RawlogWriter, whose workers compress blocks in parallel).
//
// Memory: at most `jobs_` capacity + 2 entries between the reader and the writer (the lanes hold
// only jobs that are also queued), the entries of the hindsight lag in the EntryWriter, plus
// RawlogWriter's 2 x threads blocks.
#include "RawlogPipeline.h"

#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace dynobj::mrptio::detail {
namespace {

namespace mobs = mrpt::obs;

/// A FIFO with a capacity (0 = unbounded); close() wakes every waiter.
template <class T>
class BoundedQueue {
 public:
  explicit BoundedQueue(std::size_t capacity = 0) : capacity_(capacity) {}
  /// False when the queue was closed (the item is dropped).
  bool push(T item) {
    std::unique_lock<std::mutex> lk(m_);
    not_full_.wait(lk, [&] { return closed_ || capacity_ == 0 || q_.size() < capacity_; });
    if (closed_) return false;
    q_.push_back(std::move(item));
    not_empty_.notify_one();
    return true;
  }
  /// False when closed and empty.
  bool pop(T& item) {
    std::unique_lock<std::mutex> lk(m_);
    not_empty_.wait(lk, [&] { return closed_ || !q_.empty(); });
    if (q_.empty()) return false;
    item = std::move(q_.front());
    q_.pop_front();
    not_full_.notify_one();
    return true;
  }
  void close() {
    {
      std::lock_guard<std::mutex> lk(m_);
      closed_ = true;
    }
    not_full_.notify_all();
    not_empty_.notify_all();
  }

 private:
  std::size_t capacity_;
  std::deque<T> q_;
  bool closed_ = false;
  std::mutex m_;
  std::condition_variable not_full_, not_empty_;
};

class Pipeline {
 public:
  Pipeline(RawlogReader& reader, const RawlogFilterOptions& o, unsigned threads)
      : reader_(reader),
        o_(o),
        max_lanes_(threads),
        jobs_(4 + 2 * static_cast<std::size_t>(threads)) {}

  ~Pipeline() { stop(); }

  FilterSummary run(EntryWriter& writer) {
    reader_thread_ = std::thread([this] { guarded([this] { readAll(); }); });
    JobPtr job;
    while (jobs_.pop(job)) {
      {
        std::unique_lock<std::mutex> lk(done_m_);
        done_cv_.wait(lk, [&] { return job->pending == 0 || failed_; });
        if (failed_) break;
      }
      writer.add(std::move(job));  // an error here: ~Pipeline stops the threads
    }
    stop();
    if (error_) std::rethrow_exception(error_);
    // The lanes' summaries hold everything they counted, warnings included; the observations
    // no lane saw were counted by the reader thread.
    FilterSummary total;
    total.observations = unrouted_observations_;
    total.seen = unrouted_seen_.seen;
    for (const auto& lane : lanes_) total += lane->filter.summary();
    return total;
  }

  /// Takes back a written frame's buffers, for the reader thread's next conversion.
  void recycle(std::unique_ptr<PreconvertedFrame> f) {
    std::lock_guard<std::mutex> lk(spare_m_);
    spare_frames_.push_back(std::move(f));
  }

 private:
  struct Lane {
    explicit Lane(const DynamicObjectFilter::Options& opts) : filter(opts) {}
    DynamicObjectFilter filter;
    BoundedQueue<std::pair<JobPtr, std::size_t>> tasks;  // bounded by jobs_ (its jobs are queued)
    std::thread thread;
  };

  /// Runs `body`; the first exception of any thread stops the pipeline and is rethrown by run().
  void guarded(const std::function<void()>& body) {
    try {
      body();
    } catch (...) {
      {
        std::lock_guard<std::mutex> lk(done_m_);
        if (!error_) error_ = std::current_exception();
        failed_ = true;
      }
      done_cv_.notify_all();
      jobs_.close();
    }
  }

  void stop() {
    stopping_ = true;
    jobs_.close();
    if (reader_thread_.joinable()) reader_thread_.join();
    for (auto& lane : lanes_) lane->tasks.close();
    for (auto& lane : lanes_)
      if (lane->thread.joinable()) lane->thread.join();
  }

  /// The reader thread.
  void readAll() {
    for (;;) {
      auto job = std::make_shared<Job>();
      if (!reader_.next(job->entry)) break;
      const RawlogEntry& e = job->entry;
      job->filtered = e.index >= o_.from && e.index <= o_.to;
      for (auto& obs : e.observations()) job->tasks.emplace_back().obs = obs;
      std::vector<std::pair<Lane*, std::size_t>> routed;
      if (job->filtered) {
        for (std::size_t i = 0; i < job->tasks.size(); i++) {
          const auto& obs = job->tasks[i].obs;
          if (obs && routing_filter_.handles(*obs)) {
            if (routing_filter_.converts(*obs)) {  // the lanes only detect
              job->tasks[i].pre = spareFrame();
              routing_filter_.preconvert(*obs, *job->tasks[i].pre);
            }
            routed.emplace_back(&laneOf(obs->sensorLabel), i);
          } else {
            job->tasks[i].delta.observations = 1;  // not a LiDAR one: only counted
            if (obs) unrouted_seen_.see(*obs);
          }
        }
        unrouted_observations_ += job->tasks.size() - routed.size();
      }
      job->pending = routed.size();  // before any lane can finish a task
      for (auto& [lane, i] : routed) lane->tasks.push({job, i});
      if (!jobs_.push(std::move(job))) return;  // stopped
    }
    jobs_.close();
  }

  /// A frame to convert into: one written and freed already (its buffers), or a new one.
  std::unique_ptr<PreconvertedFrame> spareFrame() {
    std::lock_guard<std::mutex> lk(spare_m_);
    if (spare_frames_.empty()) return std::make_unique<PreconvertedFrame>();
    auto f = std::move(spare_frames_.back());
    spare_frames_.pop_back();
    return f;
  }

  Lane& laneOf(const std::string& label) {
    auto it = lane_of_label_.find(label);
    if (it != lane_of_label_.end()) return *lanes_[it->second];
    std::size_t idx;
    if (lanes_.size() < max_lanes_) {
      idx = lanes_.size();
      auto lane = std::make_unique<Lane>(o_.filter);
      Lane* l = lane.get();
      lanes_.push_back(std::move(lane));
      l->thread = std::thread([this, l] { guarded([this, l] { detect(*l); }); });
    } else {
      idx = lane_of_label_.size() % max_lanes_;
    }
    lane_of_label_[label] = idx;
    return *lanes_[idx];
  }

  /// A lane thread.
  void detect(Lane& lane) {
    std::pair<JobPtr, std::size_t> item;
    while (lane.tasks.pop(item)) {
      Job& job = *item.first;
      Task& t = job.tasks[item.second];
      if (stopping_) continue;  // an error elsewhere: nobody waits for this any more
      detectTask(lane.filter, t);
      if (--job.pending == 0) {
        std::lock_guard<std::mutex> lk(done_m_);  // so the writer cannot miss the wake-up
        done_cv_.notify_all();
      }
      item.first.reset();
    }
  }

  RawlogReader& reader_;
  const RawlogFilterOptions& o_;
  const std::size_t max_lanes_;
  DynamicObjectFilter routing_filter_{o_.filter};  // handles(), converts(), preconvert(): reader
  BoundedQueue<JobPtr> jobs_;
  std::vector<std::unique_ptr<Lane>> lanes_;  // created and looked up by the reader thread
  std::map<std::string, std::size_t> lane_of_label_;
  std::size_t unrouted_observations_ = 0;  // reader thread; read after it is joined
  FilterSummary unrouted_seen_;            // reader thread: the observations no lane saw
  std::mutex spare_m_;
  std::vector<std::unique_ptr<PreconvertedFrame>> spare_frames_;  // at most the jobs in flight
  std::thread reader_thread_;
  std::mutex done_m_;
  std::condition_variable done_cv_;
  bool failed_ = false;  // guarded by done_m_
  std::atomic<bool> stopping_{false};
  std::exception_ptr error_;
};

}  // namespace

FilterSummary difference(const FilterSummary& after, const FilterSummary& before) {
  FilterSummary d;
  d.observations = after.observations - before.observations;
  d.lidar = after.lidar - before.lidar;
  d.points = after.points - before.points;
  d.dynamic_points = after.dynamic_points - before.dynamic_points;
  d.passed_through = after.passed_through - before.passed_through;
  d.detector_ms = after.detector_ms - before.detector_ms;
  d.data_faults.assign(
      after.data_faults.begin() + static_cast<std::ptrdiff_t>(before.data_faults.size()),
      after.data_faults.end());
  return d;
}

void detectTask(DynamicObjectFilter& filter, Task& t) {
  const FilterSummary before = filter.summary();
  if (!t.pre && t.obs && filter.converts(*t.obs)) {  // not converted ahead: here
    t.pre = std::make_unique<PreconvertedFrame>();
    filter.preconvert(*t.obs, *t.pre);
  }
  if (const core::DetectionResult* r = filter.detect(t.obs, t.pre.get())) t.detected = r->clone();
  t.delta += difference(filter.summary(), before);
}

EntryWriter::EntryWriter(const RawlogFilterOptions& o, RawlogWriter& out, ResultSink on_result)
    : o_(o),
      out_(out),
      on_result_(std::move(on_result)),
      tagger_(o.filter),
      held_(
          o.filter.detector,
          [](const Ref& r) -> const core::LidarFrame& { return r.job->tasks[r.task].pre->frame; }),
      release_([this](core::HindsightQueue<Ref>::Item& h) { tag(h); }) {}

void EntryWriter::add(JobPtr job) {
  pending_.push_back(job);
  for (std::size_t i = 0; i < job->tasks.size(); i++) {
    Task& t = job->tasks[i];
    if (!t.detected) continue;
    job->held++;
    core::DetectionResult r = std::move(*t.detected);
    t.detected.reset();
    held_.push(t.obs->sensorLabel, Ref{job.get(), i}, std::move(r), release_);
  }
  flush();
}

void EntryWriter::finish() {
  held_.finish(release_);
  flush();
}

void EntryWriter::tag(core::HindsightQueue<Ref>::Item& h) {
  Task& t = h.data.job->tasks[h.data.task];
  const FilterSummary before = tagger_.summary();
  tagger_.tag(t.obs, t.pre->frame, h.result, &t.extra);
  t.delta += difference(tagger_.summary(), before);
  if (on_result_) on_result_(*t.obs, h.result);
  h.data.job->held--;
}

void EntryWriter::flush() {
  while (!pending_.empty() && pending_.front()->held == 0) {
    Job& job = *pending_.front();
    RawlogEntry& e = job.entry;
    for (Task& t : job.tasks) {
      running_ += t.delta;
      if (t.pre && recycle_) recycle_(std::move(t.pre));
    }
    if (e.isPair()) {
      for (Task& t : job.tasks)
        for (auto& x : t.extra) e.sensory_frame->insert(x);
      if (e.actions) out_.write(*e.actions);
      out_.write(*e.sensory_frame);
    } else {
      out_.write(*e.observation);
      for (Task& t : job.tasks)
        for (auto& x : t.extra) out_.write(*x);
    }
    written_ = e.index + 1;
    if (o_.progress) o_.progress(written_, running_);
    pending_.pop_front();  // frees the entry
  }
}

FilterSummary detectPipelined(RawlogReader& reader, EntryWriter& writer,
                              const RawlogFilterOptions& o, unsigned threads) {
  Pipeline p(reader, o, threads);
  writer.setRecycle([&p](std::unique_ptr<PreconvertedFrame> f) { p.recycle(std::move(f)); });
  const FilterSummary s = p.run(writer);
  writer.setRecycle({});
  return s;
}

}  // namespace dynobj::mrptio::detail
