// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/io/TracksCsv.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace dynobj;

TEST(TracksCsv, HeaderAndOneRowPerObjectAppearOnlyAfterClose) {
  const std::string p = (std::filesystem::temp_directory_path() / "dynobj_tracks.csv").string();
  {
    io::TracksCsvWriter w(p);
    core::DetectionResult r;
    r.timestamp_ns = 42;
    core::TrackedObject a;
    a.id = 3;
    a.dynamic = true;
    a.age = 5;
    a.points = 17;
    a.centroid = {1, 2, 3};
    a.velocity = {0.5, -1};
    a.box_min = {0, 1, 2};
    a.box_max = {2, 3, 4};
    r.objects = {a, core::TrackedObject{}};
    w.write("LIDAR", r);
    EXPECT_FALSE(std::filesystem::exists(p));
    w.close();
  }
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(),
            "timestamp_ns,sensor_label,id,dynamic,age,points,x,y,z,vx,vy,min_x,min_y,min_z,max_x,"
            "max_y,max_z\n42,LIDAR,3,1,5,17,1,2,3,0.5,-1,0,1,2,2,3,4\n"
            "42,LIDAR,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n");
  std::filesystem::remove(p);
}
