// SPDX-License-Identifier: BSD-3-Clause
// filterRawlog pipelined (threads > 1) against single-threaded on a rawlog with two LiDARs: the
// two labels go to two detection lanes that run in parallel; the output must be the same bytes
// once decompressed, and each label detected as if it were alone.
#include <dynobj/mrptio/RawlogFilter.h>
#include <dynobj/mrptio/RawlogReader.h>
#include <dynobj/mrptio/RawlogWriter.h>
#include <dynobj/testing/ScratchPath.h>
#include <gtest/gtest.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/filesystem.h>

#include <filesystem>

using namespace dynobj::mrptio;

namespace {

const std::string kSample = DYNOBJ_SOURCE_DIR "/rawlogs/hall-small/hall-small.rawlog";
constexpr std::size_t kEntries = 24;  // 12 sweeps + 12 odometry

std::string tempPath(const std::string& name) {
  return dynobj::testing::scratchPath("_") + name;
}

/// A deep copy (pixel labels included) with another sensor label.
mrpt::obs::CObservation::Ptr relabelled(const mrpt::obs::CObservation& o, const std::string& l) {
  mrpt::io::CMemoryStream m;
  auto arch = mrpt::serialization::archiveFrom(m);
  arch << o;
  m.Seek(0);
  auto copy = std::dynamic_pointer_cast<mrpt::obs::CObservation>(arch.ReadObject());
  copy->sensorLabel = l;
  return copy;
}

/// The sample's first entries with every LiDAR observation doubled as "LIDAR2": as observations
/// one after the other (`frames` false), or each entry as one sensory frame (`frames` true).
std::string twoLidarRawlog(bool frames) {
  const std::string path = tempPath(frames ? "two-sf.rawlog" : "two-obs.rawlog");
  RawlogReader in(kSample);
  RawlogWriter out(path, 0);
  RawlogEntry e;
  while (in.entriesRead() < kEntries && in.next(e)) {
    auto obs = e.observation;
    const bool lidar = ObservationConverter::isLidarObservation(*obs);
    if (frames) {
      mrpt::obs::CSensoryFrame sf;
      sf.insert(obs);
      if (lidar) sf.insert(relabelled(*obs, "LIDAR2"));
      out.write(sf);
    } else {
      out.write(*obs);
      if (lidar) out.write(*relabelled(*obs, "LIDAR2"));
    }
  }
  out.commit();
  return path;
}

/// Every byte the stock reader sees (the decompressed rawlog).
std::string content(const std::string& path) {
  GzipInputStream in;
  std::string err, out;
  EXPECT_TRUE(in.open(path, err)) << err;
  char buf[65536];
  for (std::size_t n; (n = in.Read(buf, sizeof(buf))) > 0;) out.append(buf, n);
  return out;
}

RawlogFilterSummary run(const std::string& in, const std::string& out, unsigned threads,
                        const std::string& label = "") {
  RawlogFilterOptions o;
  o.threads = threads;
  o.overwrite = true;
  o.filter.sensor_label = label;
  return filterRawlog(in, out, o);
}

}  // namespace

TEST(RawlogFilter, TwoLidarsInParallelLanesSameOutputAsOneThread) {
  if (!std::filesystem::exists(kSample)) GTEST_SKIP() << "no " << kSample;
  for (bool frames : {false, true}) {
    SCOPED_TRACE(frames ? "sensory frames" : "observations");
    const std::string in = twoLidarRawlog(frames);
    const std::string one = tempPath("one.rawlog"), two = tempPath("two.rawlog");
    const RawlogFilterSummary s1 = run(in, one, 1), s2 = run(in, two, 2);
    EXPECT_TRUE(content(one) == content(two));  // (not EXPECT_EQ: megabytes)
    EXPECT_EQ(s1.entries, s2.entries);
    EXPECT_EQ(s2.filter.observations, 3 * kEntries / 2);
    EXPECT_EQ(s2.filter.lidar, kEntries);  // 12 sweeps x 2 labels
    EXPECT_EQ(s1.filter.lidar, s2.filter.lidar);
    EXPECT_EQ(s1.filter.points, s2.filter.points);
    EXPECT_EQ(s1.filter.dynamic_points, s2.filter.dynamic_points);
    EXPECT_GT(s2.filter.dynamic_points, 0u);
    // Each label has a detector of its own: LIDAR2 (a copy) alone finds what LIDAR finds.
    const RawlogFilterSummary only2 = run(in, tempPath("only2.rawlog"), 2, "LIDAR2");
    EXPECT_EQ(only2.filter.lidar, kEntries / 2);
    EXPECT_EQ(2 * only2.filter.dynamic_points, s2.filter.dynamic_points);
  }
}

TEST(RawlogFilter, PipelinedReadErrorNamesTheEntryAndLeavesNoOutput) {
  if (!std::filesystem::exists(kSample)) GTEST_SKIP() << "no " << kSample;
  const std::string in = twoLidarRawlog(false);  // plain: cut anywhere
  const std::string cut = tempPath("cut.rawlog"), out = tempPath("cut-out.rawlog");
  std::filesystem::copy_file(in, cut);
  std::filesystem::resize_file(cut, std::filesystem::file_size(in) * 2 / 3);
  try {
    run(cut, out, 2);
    FAIL() << "a truncated rawlog was accepted";
  } catch (const RawlogError& e) {
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(out + ".partial"));
}

TEST(RawlogFilter, PipelinedWriterErrorStopsEveryThread) {
  if (!std::filesystem::exists(kSample)) GTEST_SKIP() << "no " << kSample;
  // A label file holds one LiDAR: the writing thread throws at LIDAR2's first frame while the
  // reader and both lanes are busy; the error must come out, and no output file.
  const std::string in = twoLidarRawlog(false), out = tempPath("two-labels.rawlog");
  RawlogFilterOptions o;
  o.threads = 2;
  o.labels_out = tempPath("two.labels");
  try {
    filterRawlog(in, out, o);
    FAIL() << "two LiDARs into one label file were accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("several LiDARs"), std::string::npos) << e.what();
  }
  for (const auto& f : {out, out + ".partial", o.labels_out, o.labels_out + ".partial"})
    EXPECT_FALSE(std::filesystem::exists(f)) << f;
}
