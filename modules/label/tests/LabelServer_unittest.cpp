// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/label/LabelServer.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "../../core/tests/SyntheticScene.h"

using namespace dynobj;
using nlohmann::json;

namespace {

std::string tempDir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("dynobj_labelserver_" + name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d.string();
}

struct Fixture {
  label::MemorySweeps src;
  std::unique_ptr<label::LabelEditor> session;
  std::unique_ptr<label::LabelServer> server;
  std::thread thread;
  int port = 0;

  explicit Fixture(const std::string& output, int want_port = 0) {
    test::Scene scene;
    scene.posts.push_back({4, 0, 0.3, 1.8});
    src.add(test::render(scene, test::smallSensor(16, 360), true, 1000));
    src.add(test::render(scene, test::smallSensor(16, 360), true, 2000));
    session = std::make_unique<label::LabelEditor>(src, label::LabelParams{});
    label::ServerOptions o;
    o.port = want_port;
    o.page_dir = std::string(DYNOBJ_SHARE_DIR) + "/label";
    o.output = output;
    o.autosave_s = 0;
    server = std::make_unique<label::LabelServer>(*session, o);
  }
  void start() {
    port = server->bind();
    thread = std::thread([this] { server->run(); });
  }
  ~Fixture() {
    server->stop();
    if (thread.joinable()) thread.join();
  }
};

}  // namespace

TEST(LabelServer, ServesThePageAndTheApiOnLocalhost) {
  const std::string dir = tempDir("api");
  Fixture fx(dir + "/out");
  fx.start();
  ASSERT_GT(fx.port, 0);
  httplib::Client cli("127.0.0.1", fx.port);
  auto page = cli.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("dynobj-label"), std::string::npos);
  auto info = cli.Get("/api/info");
  ASSERT_TRUE(info);
  const json j = json::parse(info->body);
  EXPECT_EQ(j["rows"], 16);
  EXPECT_EQ(j["cols"], 360);
  EXPECT_EQ(j["sweeps"], 2);
  auto data = cli.Get("/api/sweep-data?k=1");
  ASSERT_TRUE(data);
  EXPECT_EQ(data->body.size(), 16u * 360u * 14u);
  auto bad = cli.Get("/api/sweep?k=5");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_NE(json::parse(bad->body)["error"].get<std::string>().find("does not exist"),
            std::string::npos);
  auto obj = cli.Post("/api/object", R"({"k":0,"id":0,"pixels":[3,1,2]})", "application/json");
  ASSERT_TRUE(obj);
  ASSERT_EQ(obj->status, 200) << obj->body;
  EXPECT_EQ(json::parse(obj->body)["id"], 1);
  auto sweep = cli.Get("/api/sweep?k=0");
  EXPECT_EQ(json::parse(sweep->body)["objects"][0]["pixels"], json::parse("[1,2,3]"));
  auto save = cli.Post("/api/save", "{}", "application/json");
  ASSERT_TRUE(save);
  EXPECT_EQ(save->status, 200) << save->body;
  EXPECT_TRUE(std::filesystem::exists(dir + "/out.instances"));
  // What another site's page could send: a form-like POST, or any request under another name.
  auto form = cli.Post("/api/object", R"({"k":0,"id":0,"pixels":[5]})", "text/plain");
  ASSERT_TRUE(form);
  EXPECT_EQ(form->status, 403);
  auto rebound = cli.Get("/api/info", {{"Host", "evil.example:" + std::to_string(fx.port)}});
  ASSERT_TRUE(rebound);
  EXPECT_EQ(rebound->status, 403);
  EXPECT_EQ(json::parse(cli.Get("/api/sweep?k=0")->body)["objects"].size(), 1u);
}

TEST(LabelServer, ASaveToAnUnwritablePlaceIsReportedAndNothingIsLost) {
  const std::string dir = tempDir("unwritable");
  { std::ofstream(dir + "/file") << "x"; }
  Fixture fx(dir + "/file/out");
  fx.start();
  httplib::Client cli("127.0.0.1", fx.port);
  ASSERT_EQ(cli.Post("/api/object", R"({"k":1,"id":4,"pixels":[9]})", "application/json")->status,
            200);
  auto save = cli.Post("/api/save", "{}", "application/json");
  ASSERT_TRUE(save);
  EXPECT_EQ(save->status, 500);
  EXPECT_NE(save->body.find("save failed"), std::string::npos) << save->body;
  const json info = json::parse(cli.Get("/api/info")->body);
  EXPECT_NE(info["save_error"].get<std::string>(), "");
  EXPECT_EQ(json::parse(cli.Get("/api/sweep?k=1")->body)["objects"][0]["pixels"],
            json::parse("[9]"));
}

TEST(LabelServer, APortInUseIsAClearError) {
  const std::string dir = tempDir("port");
  Fixture first(dir + "/a");
  first.start();
  Fixture second(dir + "/b", first.port);
  try {
    second.server->bind();
    FAIL() << "bound a port in use";
  } catch (const label::LabelError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("127.0.0.1:" + std::to_string(first.port)), std::string::npos) << m;
    EXPECT_NE(m.find("in use"), std::string::npos) << m;
  }
}

TEST(LabelServer, AMissingPageIsAClearError) {
  label::MemorySweeps src;
  src.add(test::render({}, test::smallSensor(16, 360), true, 1000));
  label::LabelEditor s(src, {});
  label::ServerOptions o;
  o.page_dir = tempDir("nopage");
  EXPECT_THROW(label::LabelServer(s, o), label::LabelError);
}
