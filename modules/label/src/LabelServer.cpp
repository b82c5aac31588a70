// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/label/LabelServer.h"

#include <dynobj/io/FrameImages.h>
#include <httplib.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

namespace dynobj::label {

using nlohmann::json;

struct LabelServer::Impl {
  LabelEditor& session;
  ServerOptions opts;
  httplib::Server http;
  std::mutex mutex;  ///< guards the session and the save state
  std::uint64_t saved_revision = 0;
  std::string save_error;
  std::string saved_at;
  std::atomic<bool> running{false};
  std::atomic<bool> stopping{false}, run_entered{false}, run_done{false};
  std::mutex wake_mutex;
  std::condition_variable wake;

  Impl(LabelEditor& s, ServerOptions o) : session(s), opts(std::move(o)) {
    // Nothing is on disk yet for this run (pre-labels, a fresh or resumed session): the first
    // autosave writes the files, so they exist and hold what the page shows from the start.
    saved_revision = ~std::uint64_t{0};
  }

  bool saveLocked(std::string& error, bool force = false) {
    if (!force && session.revision() == saved_revision && save_error.empty()) return true;
    const std::uint64_t rev = session.revision();
    try {
      session.save(opts.output, opts.rawlog);
      saved_revision = rev;
      save_error.clear();
      const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
      char buf[32];
      std::strftime(buf, sizeof(buf), "%H:%M:%S", std::localtime(&now));
      saved_at = buf;
      return true;
    } catch (const std::exception& e) {
      save_error = e.what();
      error = save_error;
      return false;
    }
  }

  json objectsJson() const {
    json a = json::array();
    for (const auto& [id, info] : session.objects())
      a.push_back({{"id", id}, {"class", info.cls}, {"moving", info.moving}});
    return a;
  }

  json infoJson() const {
    return {{"input", opts.rawlog},
            {"output", opts.output},
            {"files", LabelEditor::outputFiles(opts.output)},
            {"rows", session.rows()},
            {"cols", session.cols()},
            {"sweeps", session.size()},
            {"reviewed", session.reviewedCount()},
            {"labelled", session.labelledCount()},
            {"objects", objectsJson()},
            {"distance", session.params().distance},
            {"max_extent", session.params().max_extent},
            {"revision", session.revision()},
            {"saved_revision", saved_revision},
            {"saved_at", saved_at},
            {"save_error", save_error}};
  }

  json sweepJson(std::size_t k) const {
    json objs = json::array();
    for (const auto& o : session.labels(k).objects)
      objs.push_back({{"id", o.id}, {"state", toString(o.state)}, {"pixels", o.pixels}});
    return {{"k", k},
            {"timestamp_ns", session.timestamp(k)},
            {"reviewed", session.labels(k).reviewed},
            {"objects", objs}};
  }

  static std::size_t sweepArg(const httplib::Request& req) {
    if (!req.has_param("k")) throw LabelError("missing parameter k (the sweep)");
    try {
      return static_cast<std::size_t>(std::stoull(req.get_param_value("k")));
    } catch (const std::exception&) {
      throw LabelError("bad sweep number '" + req.get_param_value("k") + "'");
    }
  }

  /// Runs `body` under the session lock; exceptions become 400 / 500 with {error}.
  void handle(httplib::Response& res, const std::function<void()>& body) {
    try {
      std::lock_guard<std::mutex> lock(mutex);
      body();
    } catch (const LabelError& e) {
      res.status = 400;
      res.set_content(json{{"error", e.what()}}.dump(), "application/json");
    } catch (const json::exception& e) {
      res.status = 400;
      res.set_content(json{{"error", std::string("bad request: ") + e.what()}}.dump(),
                      "application/json");
    } catch (const std::exception& e) {
      res.status = 500;
      res.set_content(json{{"error", e.what()}}.dump(), "application/json");
    }
  }

  void routes() {
    http.Get("/api/info", [this](const httplib::Request&, httplib::Response& res) {
      handle(res, [&] { res.set_content(infoJson().dump(), "application/json"); });
    });
    http.Get("/api/sweep", [this](const httplib::Request& req, httplib::Response& res) {
      handle(res, [&] {
        const std::size_t k = sweepArg(req);
        session.sweep(k);  // reads it (errors reach the page)
        res.set_content(sweepJson(k).dump(), "application/json");
      });
    });
    http.Get("/api/sweep-data", [this](const httplib::Request& req, httplib::Response& res) {
      handle(res, [&] {
        const auto s = session.sweep(sweepArg(req));
        const core::LidarFrame& f = s->frame;
        const std::size_t n = f.pixelCount();
        std::string out(n * 2 + n * 12, '\0');
        const cv::Mat_<std::uint8_t> inten = io::intensityToU8(f);
        for (int r = 0; r < f.rows(); r++)
          for (int c = 0; c < f.cols(); c++) {
            const std::size_t i = static_cast<std::size_t>(r * f.cols() + c);
            out[i] = static_cast<char>(inten(r, c));
            out[n + i] = static_cast<char>(s->ground(r, c));
            const cv::Vec3f& p = f.xyz(r, c);
            for (int a = 0; a < 3; a++)
              std::memcpy(&out[2 * n + (static_cast<std::size_t>(a) * n + i) * 4], &p[a], 4);
          }
        res.set_content(out, "application/octet-stream");
      });
    });
    http.Post("/api/grow", [this](const httplib::Request& req, httplib::Response& res) {
      handle(res, [&] {
        const json j = json::parse(req.body);
        const auto px = session.grow(j.at("k").get<std::size_t>(), j.at("row").get<int>(),
                                     j.at("col").get<int>(), j.value("id", -1),
                                     j.value("distance", 0.0), j.value("max_extent", 0.0));
        res.set_content(json{{"pixels", px}}.dump(), "application/json");
      });
    });
    http.Post("/api/object", [this](const httplib::Request& req, httplib::Response& res) {
      handle(res, [&] {
        const json j = json::parse(req.body);
        int id = j.value("id", 0);
        if (id <= 0) id = session.newObject(j.value("class", std::string("object")), true);
        session.setObject(j.at("k").get<std::size_t>(), id,
                          j.at("pixels").get<std::vector<std::uint32_t>>(),
                          labelStateFromString(j.value("state", std::string("confirmed"))));
        res.set_content(json{{"id", id}}.dump(), "application/json");
      });
    });
    http.Post("/api/object-info", [this](const httplib::Request& req, httplib::Response& res) {
      handle(res, [&] {
        const json j = json::parse(req.body);
        session.setObjectInfo(ObjectInfo{j.at("id").get<int>(), j.at("class").get<std::string>(),
                                         j.at("moving").get<bool>()});
        res.set_content("{}", "application/json");
      });
    });
    http.Post("/api/propagate", [this](const httplib::Request& req, httplib::Response& res) {
      handle(res, [&] {
        const json j = json::parse(req.body);
        std::size_t k = j.at("k").get<std::size_t>();
        const int id = j.at("id").get<int>();
        const int steps = std::max(1, std::min(1000, j.value("steps", 1)));
        json out = json::array();
        for (int i = 0; i < steps && k + 1 < session.size(); i++, k++) {
          const Propagation p = session.propagate(k, id);
          out.push_back({{"to", p.to},
                         {"found", p.found},
                         {"kept", p.kept},
                         {"pixels", p.pixels},
                         {"ego_motion", p.ego_motion},
                         {"speed", p.velocity.norm()}});
          if (!p.found) break;
        }
        res.set_content(json{{"steps", out}}.dump(), "application/json");
      });
    });
    http.Post("/api/review", [this](const httplib::Request& req, httplib::Response& res) {
      handle(res, [&] {
        const json j = json::parse(req.body);
        const std::size_t k = j.at("k").get<std::size_t>();
        session.setReviewed(k, j.value("reviewed", true));
        json out = json::array();
        if (j.value("propagate", false) && k + 1 < session.size()) {
          std::vector<int> ids;
          for (const auto& o : session.labels(k).objects) ids.push_back(o.id);
          for (int id : ids)
            if (!session.object(k + 1, id)) {
              const Propagation p = session.propagate(k, id);
              out.push_back({{"id", id}, {"found", p.found}, {"pixels", p.pixels}});
            }
        }
        res.set_content(json{{"propagated", out}}.dump(), "application/json");
      });
    });
    http.Post("/api/save", [this](const httplib::Request&, httplib::Response& res) {
      handle(res, [&] {
        std::string error;
        if (!saveLocked(error)) {
          res.status = 500;
          res.set_content(json{{"error", "save failed: " + error +
                                             " (the labels are still held by dynobj-label: "
                                             "fix the problem and save again)"}}
                              .dump(),
                          "application/json");
          return;
        }
        res.set_content(
            json{{"files", LabelEditor::outputFiles(opts.output)}, {"saved_at", saved_at}}.dump(),
            "application/json");
      });
    });
    // httplib's default also sets SO_REUSEPORT, which lets a second server share a port in use
    // silently: SO_REUSEADDR only (a restarted server may rebind at once, a busy port fails).
    http.set_socket_options([](socket_t sock) {
      int yes = 1;
      setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, reinterpret_cast<const void*>(&yes), sizeof(yes));
    });
    // Only this machine's pages may drive the API: a Host other than 127.0.0.1 / localhost (DNS
    // rebinding) is refused, and a POST must say application/json, which another site's page
    // cannot send here without a CORS preflight this server never grants.
    http.set_pre_routing_handler([](const httplib::Request& req, httplib::Response& res) {
      const std::string host = req.get_header_value("Host");
      const std::string name = host.substr(0, host.rfind(':'));
      const bool local = host.empty() || name == "127.0.0.1" || name == "localhost";
      const bool json_post = req.method != "POST" ||
                             req.get_header_value("Content-Type").rfind("application/json", 0) == 0;
      if (local && json_post) return httplib::Server::HandlerResponse::Unhandled;
      res.status = 403;
      res.set_content(json{{"error", local ? "POST requests must be application/json"
                                           : "dynobj-label answers to 127.0.0.1 only"}}
                          .dump(),
                      "application/json");
      return httplib::Server::HandlerResponse::Handled;
    });
    http.set_mount_point("/", opts.page_dir);
    http.set_file_extension_and_mimetype_mapping("js", "text/javascript");
  }
};

LabelServer::LabelServer(LabelEditor& session, ServerOptions opts)
    : impl_(std::make_unique<Impl>(session, std::move(opts))) {
  if (!std::filesystem::is_regular_file(impl_->opts.page_dir + "/index.html"))
    throw LabelError("the page is missing: no index.html in '" + impl_->opts.page_dir +
                     "' (set DYNOBJ_SHARE to the share/dynobj folder)");
  impl_->routes();
}

LabelServer::~LabelServer() {
  stop();
}

int LabelServer::bind() {
  const int want = impl_->opts.port;
  if (want < 0 || want > 65535) throw LabelError("port " + std::to_string(want) + " is not a port");
  if (want == 0) {
    const int port = impl_->http.bind_to_any_port("127.0.0.1");
    if (port <= 0) throw LabelError("cannot listen on 127.0.0.1 (no free port)");
    return port;
  }
  if (!impl_->http.bind_to_port("127.0.0.1", want))
    throw LabelError("cannot listen on 127.0.0.1:" + std::to_string(want) +
                     ": the port is in use (or not allowed); choose another with --port");
  return want;
}

void LabelServer::run() {
  impl_->run_entered = true;
  if (impl_->stopping) {
    impl_->run_done = true;
    return;
  }
  impl_->running = true;
  std::thread autosave([this] {
    const auto period = std::chrono::duration<double>(impl_->opts.autosave_s);
    std::unique_lock<std::mutex> wl(impl_->wake_mutex);
    while (impl_->running) {
      impl_->wake.wait_for(wl, period > std::chrono::duration<double>(0)
                                   ? std::chrono::duration_cast<std::chrono::milliseconds>(period)
                                   : std::chrono::milliseconds(500));
      if (!impl_->running || impl_->opts.autosave_s <= 0) continue;
      std::lock_guard<std::mutex> lock(impl_->mutex);
      std::string error;
      impl_->saveLocked(error);  // a failure shows in /api/info (save_error) and on the page
    }
  });
  impl_->http.listen_after_bind();
  impl_->running = false;
  impl_->wake.notify_all();
  autosave.join();
  impl_->run_done = true;
}

void LabelServer::stop() {
  impl_->stopping = true;
  impl_->running = false;
  impl_->wake.notify_all();
  // run() may be between its check of `stopping` and httplib's loop: wait until it listens (then
  // stop it) or has returned, so that a stop() right after the start is never lost.
  if (!impl_->run_entered) return;
  while (!impl_->run_done && !impl_->http.is_running())
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  if (impl_->http.is_running()) impl_->http.stop();
}

bool LabelServer::save(std::string& error, bool force) {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->saveLocked(error, force);
}

}  // namespace dynobj::label
