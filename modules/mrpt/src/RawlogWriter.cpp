// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/RawlogWriter.h"

#include <dynobj/io/AtomicFile.h>
#include <mrpt/io/CStream.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace dynobj::mrptio {

namespace {

/// A CStream that appends whatever is written to a std::string (serialization target).
class StringSink : public mrpt::io::CStream {
 public:
  explicit StringSink(std::string& out) : out_(out) {}
  size_t Read(void*, size_t) override { return 0; }
  size_t Write(const void* buf, size_t n) override {
    out_.append(static_cast<const char*>(buf), n);
    return n;
  }
  uint64_t Seek(int64_t, CStream::TSeekOrigin) override {
    throw std::logic_error("StringSink cannot seek");
  }
  uint64_t getTotalBytesCount() const override { return out_.size(); }
  uint64_t getPosition() const override { return out_.size(); }

 private:
  std::string& out_;
};

}  // namespace

struct RawlogWriter::Impl {
  struct Block {
    std::string raw, packed;
    bool done = false;
    std::exception_ptr error;
  };

  io::AtomicFile file;
  GzipMemberEncoder encoder;  // the caller's (threads == 1)
  std::string current;        // the block being filled
  std::uint64_t written = 0;

  // Compression pool (threads > 1): blocks in file order; workers take them from `todo`.
  std::vector<std::thread> workers;
  std::deque<std::shared_ptr<Block>> inflight, todo;
  std::vector<std::string> spare;  // raw buffers to reuse (their capacity)
  std::size_t max_inflight = 0;
  std::mutex m;
  std::condition_variable work_cv, done_cv;
  bool stop = false;

  Impl(const std::string& path, int level, unsigned threads) : file(path), encoder(level) {
    current.reserve(kBlockBytes + (kBlockBytes >> 1));
    if (threads > 1 && level > 0) {
      max_inflight = 2 * static_cast<std::size_t>(threads);
      for (unsigned i = 0; i < threads; i++) workers.emplace_back([this, level] { work(level); });
    }
  }

  ~Impl() { shutdown(); }

  void shutdown() {
    {
      std::lock_guard<std::mutex> lk(m);
      stop = true;
    }
    work_cv.notify_all();
    for (auto& t : workers) t.join();
    workers.clear();
  }

  void work(int level) {
    GzipMemberEncoder enc(level);
    for (;;) {
      std::shared_ptr<Block> b;
      {
        std::unique_lock<std::mutex> lk(m);
        work_cv.wait(lk, [&] { return stop || !todo.empty(); });
        if (stop) return;  // commit() drained the queue first; otherwise an error stops us
        b = todo.front();
        todo.pop_front();
      }
      try {
        enc.encode(b->raw, b->packed);
      } catch (...) {
        b->error = std::current_exception();
      }
      {
        std::lock_guard<std::mutex> lk(m);
        b->done = true;
      }
      done_cv.notify_all();
    }
  }

  void writeBytes(const std::string& bytes) {
    file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!file.stream()) throw std::runtime_error("cannot write '" + file.partialPath() + "'");
    written += bytes.size();
  }

  /// Writes the finished blocks at the front, in order; with `wait_for`, first waits until at most
  /// that many blocks remain in flight.
  void drain(std::size_t wait_for) {
    for (;;) {
      std::shared_ptr<Block> b;
      {
        std::unique_lock<std::mutex> lk(m);
        if (inflight.size() > wait_for) done_cv.wait(lk, [&] { return inflight.front()->done; });
        if (inflight.empty() || !inflight.front()->done) return;
        b = inflight.front();
        inflight.pop_front();
      }
      if (b->error) std::rethrow_exception(b->error);
      writeBytes(b->packed);
      b->raw.clear();
      std::lock_guard<std::mutex> lk(m);
      spare.push_back(std::move(b->raw));
    }
  }

  /// Closes the current block: compressed and written now, or handed to the pool.
  void submit() {
    if (current.empty()) return;
    if (encoder.level() == 0) {
      writeBytes(current);
    } else if (workers.empty()) {
      std::string packed;
      encoder.encode(current, packed);
      writeBytes(packed);
    } else {
      drain(max_inflight - 1);  // bounded memory: wait for a slot
      auto b = std::make_shared<Block>();
      b->raw.swap(current);
      {
        std::lock_guard<std::mutex> lk(m);
        if (!spare.empty()) {
          current.swap(spare.back());
          spare.pop_back();
        }
        inflight.push_back(b);
        todo.push_back(b);
      }
      work_cv.notify_one();
      drain(max_inflight);  // whatever is already done
      if (current.capacity() < kBlockBytes) current.reserve(kBlockBytes + (kBlockBytes >> 1));
      return;
    }
    current.clear();
  }
};

RawlogWriter::RawlogWriter(const std::string& path, int compress_level, unsigned threads) {
  GzipMemberEncoder check(compress_level);  // throws on a bad level, before the file exists
  impl_ = std::make_unique<Impl>(path, compress_level, threads);  // io::AtomicFile names the cause
}

RawlogWriter::~RawlogWriter() = default;

unsigned RawlogWriter::hardwareThreads() {
  return std::max(1u, std::thread::hardware_concurrency());
}  // an uncommitted file is removed by io::AtomicFile

void RawlogWriter::write(const mrpt::serialization::CSerializable& obj) {
  StringSink sink(impl_->current);
  auto archive = mrpt::serialization::archiveFrom(sink);
  archive << obj;
  if (impl_->current.size() >= kBlockBytes) impl_->submit();
}

void RawlogWriter::commit() {
  impl_->submit();
  if (!impl_->workers.empty()) impl_->drain(0);
  impl_->shutdown();
  impl_->file.commit();
}

const std::string& RawlogWriter::path() const {
  return impl_->file.path();
}

std::uint64_t RawlogWriter::bytesWritten() const {
  return impl_->written;
}

}  // namespace dynobj::mrptio
