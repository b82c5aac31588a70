// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mapclean/MapCleanJob.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>

using dynobj::mapclean::MapCleanOptions;
using dynobj::mapclean::MapFormats;
using dynobj::mapclean::outputFiles;

namespace {

std::string messageOf(const std::string& list) {
  try {
    MapFormats::parse(list);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

bool has(const std::vector<std::string>& files, const std::string& f) {
  return std::find(files.begin(), files.end(), f) != files.end();
}

}  // namespace

TEST(MapFormats, DefaultIsOneCompactFormatThePngsAndTheSimplemap) {
  EXPECT_EQ(MapFormats{}.toString(), "ply,png,simplemap");
}

TEST(MapFormats, ParsesAListAndAll) {
  const MapFormats f = MapFormats::parse("txt,ply");
  EXPECT_TRUE(f.ply);
  EXPECT_TRUE(f.txt);
  EXPECT_FALSE(f.png);
  EXPECT_FALSE(f.pointsmap);
  EXPECT_FALSE(f.simplemap);
  EXPECT_EQ(f.toString(), "ply,txt");
  EXPECT_EQ(MapFormats::parse("all").toString(), "ply,pointsmap,txt,png,simplemap");
}

TEST(MapFormats, UnknownOrEmptyNamesAreErrorsNamingThem) {
  EXPECT_EQ(messageOf("ply,pnng"),
            "--formats: unknown format 'pnng' (did you mean 'png'?); one or more of ply, "
            "pointsmap, txt, png, simplemap (comma-separated), or all");
  EXPECT_NE(messageOf("bag").find("unknown format 'bag';"), std::string::npos);  // nothing near
  EXPECT_NE(messageOf("ply,,png").find("an empty name"), std::string::npos);
  EXPECT_NE(messageOf("").find("an empty name"), std::string::npos);
}

TEST(MapFormats, OutputFilesFollowTheFormats) {
  MapCleanOptions o;
  o.out_dir = "out";
  o.formats = MapFormats::parse("txt");
  const auto files = outputFiles(o);
  EXPECT_EQ(files,
            (std::vector<std::string>{"out/static.txt", "out/dynamic.txt", "out/poses.tum"}));
  o.formats = MapFormats{};
  const auto def = outputFiles(o);
  EXPECT_TRUE(has(def, "out/static.ply") && has(def, "out/map.png") &&
              has(def, "out/cleaned.simplemap") && has(def, "out/poses.tum"));
  EXPECT_FALSE(has(def, "out/static.txt") || has(def, "out/static.pointsmap"));
}
