// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/io/PoseFile.h>
#include <dynobj/mapclean/ChunkMerge.h>
#include <dynobj/mapclean/PointCloudIO.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "FrameFixture.h"

namespace mc = dynobj::mapclean;
namespace fs = std::filesystem;

namespace {

constexpr std::int64_t kT0 = 1700000000000000000;  // the input's first scan
constexpr double kInf = std::numeric_limits<double>::infinity();

std::int64_t at(double s) {
  return kT0 + static_cast<std::int64_t>(std::llround(s * 1e9));
}

Eigen::Isometry3d pose(double x, double y, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, 0);
  return T;
}

struct TimedPoses {
  std::vector<std::pair<double, Eigen::Isometry3d>> poses;  ///< [s] since the first scan
};

/// A chunk folder as dynobj-mapclean --chunk-from/--chunk-to writes it (maps in ply only).
std::string makeChunk(const std::string& name, double from, double to,
                      const std::vector<mc::MapPoint>& st, const std::vector<mc::MapPoint>& dy,
                      const TimedPoses& own, const TimedPoses& overlap, double voxel = 0.0) {
  const std::string dir = dynobj::mapclean::test::tmpPath(name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  mc::writePly(dir + "/static.ply", st);
  mc::writePly(dir + "/dynamic.ply", dy);
  for (const auto& [file, poses] :
       {std::pair{"/poses.tum", &own}, std::pair{"/overlap.tum", &overlap}}) {
    dynobj::io::TumWriter w(dir + file, "test");
    for (const auto& [t, p] : poses->poses) w.write(at(t), p);
    w.close();
  }
  mc::ChunkInfo info;
  info.input = "in.rawlog";
  info.first_scan_ns = kT0;
  info.range = {from, to, 0.5};
  info.scans = own.poses.size();
  info.reached_end = !std::isfinite(to);
  info.voxel_size = voxel;
  info.dynamic_vote = 1.0;
  info.poses = "detector ego-motion";
  info.formats = "ply";
  info.write(dir + "/chunk.ini");
  return dir;
}

mc::MergeOptions mergeInto(const std::string& name, std::vector<std::string> chunks) {
  mc::MergeOptions o;
  o.chunks = std::move(chunks);
  o.out_dir = dynobj::mapclean::test::tmpPath(name);
  fs::remove_all(o.out_dir);
  o.formats = mc::MapFormats::parse("ply");
  return o;
}

std::string mergeError(const mc::MergeOptions& o) {
  try {
    mc::mergeChunks(o);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

/// Two chunks of one run: A maps [0, 1) in the world, B maps [1, end) in its own frame, which
/// started at B's first overlap scan (0.5 s), where A's pose is pose(2, 1, 0.5).
struct TwoChunks {
  Eigen::Isometry3d a_at_05 = pose(2, 1, 0.5), b_at_05 = pose(0, 0, 0);
  Eigen::Isometry3d b_at_1 = pose(1, 0, 0.1), b_at_15 = pose(2, 0.5, 0.2);
  Eigen::Isometry3d b_to_world = a_at_05 * b_at_05.inverse();
  std::string a, b;
  TwoChunks(double seam_error = 0.0) {
    // A read scan 1.0 in its overlap: where B, aligned, puts it (plus an error, if asked)
    Eigen::Isometry3d a_at_1 = b_to_world * b_at_1;
    a_at_1.translation().x() += seam_error;
    a = makeChunk("chunk-a", 0, 1, {{1, 2, 3, 4}}, {{5, 6, 7, 8}},
                  {{{0.0, pose(0, 0, 0)}, {0.5, a_at_05}}}, {{{1.0, a_at_1}}});
    b = makeChunk("chunk-b", 1, kInf, {{1, 0, 0, 9}, {0, 1, 0, 10}}, {},
                  {{{1.0, b_at_1}, {1.5, b_at_15}}}, {{{0.5, b_at_05}}});
  }
};

}  // namespace

TEST(ChunkInfo, WritesAndReadsBack) {
  mc::ChunkInfo c;
  c.input = "/data/long run.rawlog";
  c.first_scan_ns = kT0 + 123;
  c.range = {60, kInf, 30};
  c.scans = 600;
  c.scans_before = 300;
  c.reached_end = true;
  c.last_scan = 119.9;
  c.voxel_size = 0.05;
  c.dynamic_vote = 1;
  c.min_range = 0.5;
  c.poses = "detector ego-motion";
  c.formats = "ply,png";
  const std::string f = dynobj::mapclean::test::tmpPath("chunk.ini");
  c.write(f);
  const mc::ChunkInfo r = mc::ChunkInfo::read(f);
  EXPECT_EQ(r.input, c.input);
  EXPECT_EQ(r.first_scan_ns, c.first_scan_ns);
  EXPECT_EQ(r.range.from, 60);
  EXPECT_TRUE(std::isinf(r.range.to));
  EXPECT_EQ(r.range.overlap, 30);
  EXPECT_EQ(r.scans, 600u);
  EXPECT_EQ(r.scans_before, 300u);
  EXPECT_EQ(r.scans_after, 0u);
  EXPECT_TRUE(r.reached_end);
  EXPECT_DOUBLE_EQ(r.last_scan, 119.9);
  EXPECT_DOUBLE_EQ(r.voxel_size, 0.05);
  EXPECT_DOUBLE_EQ(r.min_range, 0.5);
  EXPECT_EQ(r.poses, c.poses);
  EXPECT_EQ(r.formats, c.formats);
}

TEST(ChunkInfo, MissingOrUnknownKeysAreErrorsNamingThem) {
  const std::string f = dynobj::mapclean::test::tmpPath("bad-chunk.ini");
  std::ofstream(f) << "[chunk]\ninput = x\n";
  try {
    mc::ChunkInfo::read(f);
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("first_scan_ns"), std::string::npos) << e.what();
  }
  std::ofstream(f) << "[chunk]\ninput = x\nvoxel_sise = 1\n";
  try {
    mc::ChunkInfo::read(f);
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("unknown key 'voxel_sise'"), std::string::npos)
        << e.what();
  }
}

TEST(ChunkMerge, PlacesEachChunkInTheFirstOnesWorldByTheScanBothRead) {
  const TwoChunks c;
  const mc::MergeOptions o = mergeInto("merged", {c.b, c.a});  // any order
  const mc::MergeSummary s = mc::mergeChunks(o);
  EXPECT_EQ(s.chunks, 2u);
  EXPECT_EQ(s.scans, 4u);
  ASSERT_EQ(s.seam_gap.size(), 1u);
  EXPECT_NEAR(s.seam_gap[0], 0.0, 1e-5);  // TUM files keep micrometres
  // Voxel size 0: every chunk's points, A's first, B's moved into A's world.
  const std::vector<mc::MapPoint> st = mc::readPly(o.out_dir + "/static.ply");
  ASSERT_EQ(st.size(), 3u);
  EXPECT_EQ(st[0].x, 1.f);
  EXPECT_EQ(st[0].intensity, 4.f);
  for (int k = 0; k < 2; k++) {
    const Eigen::Vector3d p = c.b_to_world * Eigen::Vector3d(k == 0 ? 1 : 0, k == 0 ? 0 : 1, 0);
    EXPECT_NEAR(st[1 + k].x, p.x(), 1e-5);
    EXPECT_NEAR(st[1 + k].y, p.y(), 1e-5);
    EXPECT_NEAR(st[1 + k].z, p.z(), 1e-5);
    EXPECT_EQ(st[1 + k].intensity, 9.f + static_cast<float>(k));
  }
  EXPECT_EQ(mc::readPly(o.out_dir + "/dynamic.ply").size(), 1u);
  // poses.tum: A's own scans, then B's in A's world.
  const auto poses = dynobj::io::readPoseFile(o.out_dir + "/poses.tum");
  ASSERT_EQ(poses.size(), 4u);
  EXPECT_EQ(poses[2].timestamp_ns, at(1.0));
  EXPECT_TRUE(poses[1].pose.isApprox(c.a_at_05, 1e-5));
  EXPECT_TRUE(poses[3].pose.isApprox(c.b_to_world * c.b_at_15, 1e-5));
}

TEST(ChunkMerge, SaysHowFarTheChunksDisagreeAtTheSeam) {
  const TwoChunks c(0.25);
  const mc::MergeSummary s = mc::mergeChunks(mergeInto("merged-gap", {c.a, c.b}));
  ASSERT_EQ(s.seam_gap.size(), 1u);
  EXPECT_NEAR(s.seam_gap[0], 0.25, 1e-5);
}

TEST(ChunkMerge, VotesOverTheChunksPoints) {
  // One voxel (1 m): A saw a static point in it, B two dynamic ones: the vote moves it.
  const std::string a = makeChunk("vote-a", 0, 1, {{0.2f, 0.2f, 0.2f, 1}}, {},
                                  {{{0.0, pose(0, 0, 0)}}}, {{{1.0, pose(0, 0, 0)}}}, 1.0);
  const std::string b =
      makeChunk("vote-b", 1, kInf, {}, {{0.3f, 0.3f, 0.3f, 1}, {0.4f, 0.4f, 0.4f, 1}},
                {{{1.0, pose(0, 0, 0)}}}, {{{0.0, pose(0, 0, 0)}}}, 1.0);
  const mc::MergeOptions o = mergeInto("merged-vote", {a, b});
  const mc::MergeSummary s = mc::mergeChunks(o);
  EXPECT_EQ(s.voted, 1u);
  EXPECT_EQ(s.map_static, 0u);
  EXPECT_EQ(s.map_dynamic, 1u);
}

TEST(ChunkMerge, RefusesChunksThatDoNotMakeOneRun) {
  const TwoChunks c;
  const auto error = [&](const std::string& name, std::vector<std::string> chunks) {
    return mergeError(mergeInto(name, std::move(chunks)));
  };
  EXPECT_NE(error("m1", {c.a}).find("the last chunk, '"), std::string::npos);
  EXPECT_NE(error("m2", {c.b}).find("the first chunk, '"), std::string::npos);
  const std::string late = makeChunk("chunk-late", 1.5, kInf, {}, {}, {{{1.5, pose(0, 0, 0)}}},
                                     {{{0.5, pose(0, 0, 0)}}});
  EXPECT_NE(error("m3", {c.a, late}).find("a gap between chunk '"), std::string::npos);
  const std::string early = makeChunk("chunk-early", 0.8, kInf, {}, {}, {{{1.0, pose(0, 0, 0)}}},
                                      {{{0.5, pose(0, 0, 0)}}});
  EXPECT_NE(error("m4", {c.a, early}).find("an overlap between chunk '"), std::string::npos);
  const std::string lonely = makeChunk("chunk-lonely", 1, kInf, {}, {}, {{{1.0, pose(0, 0, 0)}}},
                                       {{{0.7, pose(0, 0, 0)}}});
  EXPECT_NE(error("m5", {c.a, lonely}).find("shares no scan with"), std::string::npos);
  EXPECT_NE(error("m6", {c.a, dynobj::mapclean::test::tmpPath("no-such-chunk")})
                .find("is not a dynobj-mapclean chunk (no chunk.ini"),
            std::string::npos);
  fs::remove(c.b + "/static.ply");
  EXPECT_NE(error("m7", {c.a, c.b}).find("has no static.ply"), std::string::npos);
  for (const char* m : {"m1", "m2", "m3", "m4", "m5", "m6", "m7"})
    EXPECT_FALSE(fs::exists(dynobj::mapclean::test::tmpPath(m) + "/static.ply")) << m;
}

TEST(ChunkMerge, RefusesChunksOfAnotherInput) {
  const TwoChunks c;
  mc::ChunkInfo info = mc::ChunkInfo::read(c.b + "/chunk.ini");
  info.first_scan_ns += 1000000000;
  info.write(c.b + "/chunk.ini");
  EXPECT_NE(mergeError(mergeInto("m-other", {c.a, c.b})).find("differ in their input"),
            std::string::npos);
}

TEST(ChunkMerge, ExistingOutputsNeedOverwrite) {
  const TwoChunks c;
  mc::MergeOptions o = mergeInto("m-exists", {c.a, c.b});
  mc::mergeChunks(o);
  EXPECT_NE(mergeError(o).find("exists (use -w"), std::string::npos);
  o.overwrite = true;
  EXPECT_NO_THROW(mc::mergeChunks(o));
}
