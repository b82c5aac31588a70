// SPDX-License-Identifier: BSD-3-Clause
// Procedural worlds: one place per seed, reproducible, frozen worlds identical, objects clear of
// the platform's route, ground truth only on moving actors, clear errors.
#include <dynobj/sim/LidarSimulator.h>
#include <dynobj/sim/Procedural.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace dynobj::sim;

namespace {

const char* const kKinds[] = {"street", "plaza", "room", "parking", "warehouse"};

std::string spec(const std::string& kind, const std::string& extra = "") {
  return "name: p\nframes: 80\nsensor: sensors/vlp-16.ini\nmount: [0, 0, 1.0]\n"
         "procedural: {kind: " +
         kind + extra + "}\n";
}

Scenario load(const std::string& text, std::uint32_t seed) {
  return Scenario::fromYamlText(text, DYNOBJ_SHARE_DIR, {{"seed", std::to_string(seed)}}, "p.yaml");
}

std::string errorOf(const std::string& text) {
  try {
    load(text, 1);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

/// Is the point (x, y) inside the footprint of a solid static part, grown by `margin`?
bool insideSolid(const Scenario& s, const Eigen::Vector2d& p, double margin) {
  for (const Part& part : s.statics) {
    if (part.kind == Part::Kind::Box) {
      const Box& b = part.box;
      const double c = std::cos(b.yaw), sn = std::sin(b.yaw);
      const Eigen::Vector2d d = p - b.center.head<2>();
      if (std::abs(c * d.x() + sn * d.y()) < b.half.x() + margin &&
          std::abs(-sn * d.x() + c * d.y()) < b.half.y() + margin)
        return true;
    } else if (part.kind == Part::Kind::Cylinder) {
      if ((p - part.cylinder.center).norm() < part.cylinder.radius + margin) return true;
    }
  }
  return false;
}

}  // namespace

TEST(Procedural, OnePlacePerSeedReproducible) {
  for (const char* kind : kKinds) {
    SCOPED_TRACE(kind);
    const Scenario a = load(spec(kind), 3), b = load(spec(kind), 3), c = load(spec(kind), 4);
    EXPECT_FALSE(a.world_yaml.empty());
    EXPECT_EQ(a.world_yaml, b.world_yaml);
    EXPECT_NE(a.world_yaml, c.world_yaml);
    EXPECT_GT(a.statics.size(), 5u);
    EXPECT_FALSE(a.actors.empty());
    const LidarSimulator sa(a), sb(b);
    const auto wa = sa.simulate(7), wb = sb.simulate(7);
    EXPECT_EQ(cv::norm(wa.frame.range, wb.frame.range, cv::NORM_INF), 0.0);
    EXPECT_GT(wa.frame.validCount(), 2000u);
  }
}

TEST(Procedural, FrozenWorldSimulatesIdentically) {
  // The generated YAML, pasted into a plain scenario, is the same world with the same draws.
  const Scenario proc = load(spec("plaza"), 5);
  const Scenario frozen = load(
      "name: p\nframes: 80\nsensor: sensors/vlp-16.ini\n"
      "mount: [0, 0, 1.0]\n" +
          proc.world_yaml,
      5);
  ASSERT_EQ(frozen.statics.size(), proc.statics.size());
  ASSERT_EQ(frozen.actors.size(), proc.actors.size());
  const auto a = LidarSimulator(proc).simulate(12), b = LidarSimulator(frozen).simulate(12);
  EXPECT_EQ(cv::norm(a.frame.range, b.frame.range, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.frame.intensity, b.frame.intensity, cv::NORM_INF), 0.0);
}

TEST(Procedural, RouteClearOfObstaclesAndTruthOnlyOnMovers) {
  for (const char* kind : kKinds)
    for (std::uint32_t seed : {1u, 2u, 3u}) {
      SCOPED_TRACE(std::string(kind) + " seed " + std::to_string(seed));
      const Scenario s = load(spec(kind), seed);
      for (double t = 0; t < s.duration(); t += 0.5) {
        const Pose2 p = s.platform.at(t);
        EXPECT_FALSE(insideSolid(s, {p.x, p.y}, 0.5)) << "t = " << t;
      }
      const LidarSimulator sim(s);
      for (int k : {0, 40, 79}) {
        const auto sw = sim.simulate(k);
        for (int i = 0; i < sw.dynamic.rows * sw.dynamic.cols; i++) {
          const int r = i / sw.dynamic.cols, c = i % sw.dynamic.cols;
          if (!sw.dynamic(r, c)) continue;
          ASSERT_GE(sw.actor(r, c), 0);
          EXPECT_TRUE(sw.actors[static_cast<std::size_t>(sw.actor(r, c))].moving);
        }
      }
    }
}

TEST(Procedural, CountsAndRoutesFromTheSpec) {
  const Scenario room = load(spec("room", ", pedestrians: 7, standing: 0"), 2);
  EXPECT_EQ(room.actors.size(), 7u);
  for (const Actor& a : room.actors) EXPECT_EQ(a.cls, ActorClass::Pedestrian);
  // Parking: exactly 3 parked cars pull out (stand, then drive), no cruising cars, no people.
  const Scenario lot = load(spec("parking", ", cars: 0, pedestrians: 0, pulling_out: 3"), 2);
  ASSERT_EQ(lot.actors.size(), 3u);
  for (const Actor& a : lot.actors) {
    EXPECT_EQ(a.cls, ActorClass::Car);
    EXPECT_EQ(a.track.speed(0.5), 0.0);
    EXPECT_GT(a.track.keys().back().t, 1.0);
  }
  const Scenario corner = load(spec("street", ", crossing: true, platform: {route: corner}"), 2);
  EXPECT_EQ(corner.platform.keys().size(), 1u);  // stationary
  EXPECT_EQ(corner.platform.speed(3.0), 0.0);
}

TEST(Procedural, ErrorsNameTheKey) {
  EXPECT_NE(errorOf(spec("forest")).find("procedural.kind: unknown kind 'forest'"),
            std::string::npos);
  EXPECT_NE(errorOf(spec("room", ", platform: {route: drive}")).find("procedural.platform: route"),
            std::string::npos);
  EXPECT_NE(errorOf(spec("room", ", pedestrians: -2")).find("procedural.pedestrians"),
            std::string::npos);
  EXPECT_NE(errorOf(spec("room", ", trees: 2.5")).find("procedural.trees: expected a whole"),
            std::string::npos);
  EXPECT_NE(errorOf(spec("room", ", lakes: 2")).find("unknown key 'lakes'"), std::string::npos);
  EXPECT_NE(errorOf("name: p\nprocedural: {size: [10, 10]}\n").find("procedural.kind"),
            std::string::npos);
}

TEST(Procedural, VehiclesNeverDriveIntoThePlatform) {
  // The sensor never comes within 0.5 m of a car's or cyclist's footprint (people may pass
  // close: they walk at random).
  for (const char* kind : kKinds)
    for (std::uint32_t seed : {1u, 2u, 3u, 4u}) {
      SCOPED_TRACE(std::string(kind) + " seed " + std::to_string(seed));
      const Scenario s = load(spec(kind), seed);
      for (const Actor& a : s.actors) {
        if (a.cls == ActorClass::Pedestrian) continue;
        const double hl = a.cls == ActorClass::Car ? 2.2 : 0.85;
        const double hw = a.cls == ActorClass::Car ? 0.9 : 0.3;
        for (double t = 0; t < s.duration(); t += 0.05) {
          const Pose2 p = s.platform.at(t), q = a.track.at(t);
          const double c = std::cos(q.yaw), sn = std::sin(q.yaw), dx = p.x - q.x, dy = p.y - q.y;
          const double lx = std::max(std::abs(c * dx + sn * dy) - hl, 0.0);
          const double ly = std::max(std::abs(-sn * dx + c * dy) - hw, 0.0);
          ASSERT_GE(std::hypot(lx, ly), 0.5) << "actor " << a.id << " at t = " << t;
        }
      }
    }
}

namespace {

/// Do two vehicle footprints (rectangles of half size hl x hw at the poses) overlap? Separating
/// axis test over the four edge normals.
bool overlap(const Pose2& a, double ahl, double ahw, const Pose2& b, double bhl, double bhw) {
  const Eigen::Vector2d d(b.x - a.x, b.y - a.y);
  const Eigen::Vector2d ax[2] = {{std::cos(a.yaw), std::sin(a.yaw)},
                                 {-std::sin(a.yaw), std::cos(a.yaw)}};
  const Eigen::Vector2d bx[2] = {{std::cos(b.yaw), std::sin(b.yaw)},
                                 {-std::sin(b.yaw), std::cos(b.yaw)}};
  for (const Eigen::Vector2d& n : {ax[0], ax[1], bx[0], bx[1]}) {
    const double ra = ahl * std::abs(ax[0].dot(n)) + ahw * std::abs(ax[1].dot(n));
    const double rb = bhl * std::abs(bx[0].dot(n)) + bhw * std::abs(bx[1].dot(n));
    if (std::abs(d.dot(n)) > ra + rb) return false;
  }
  return true;
}

}  // namespace

TEST(Procedural, VehiclesNeverDriveThroughEachOtherOrSomeoneStanding) {
  // Cars and cyclists keep right and are drawn again when they would meet another vehicle or a
  // standing person: their bodies (the footprint less 0.2 m all round) never overlap, and no one
  // standing is inside a footprint.
  const auto half = [](const Actor& a) {
    return a.cls == ActorClass::Car ? Eigen::Vector2d(2.2, 0.9) : Eigen::Vector2d(0.85, 0.3);
  };
  for (const char* kind : kKinds)
    for (std::uint32_t seed : {1u, 2u, 3u, 4u, 5u}) {
      SCOPED_TRACE(std::string(kind) + " seed " + std::to_string(seed));
      const Scenario s =
          load(spec(kind, kind == std::string("street") ? ", crossing: true" : ""), seed);
      std::vector<const Actor*> vehicles, standing;
      for (const Actor& a : s.actors)
        if (a.cls != ActorClass::Pedestrian)
          vehicles.push_back(&a);
        else if (a.track.keys().size() == 1)
          standing.push_back(&a);
      for (double t = 0; t < s.duration(); t += 0.05)
        for (std::size_t i = 0; i < vehicles.size(); i++) {
          const Actor& a = *vehicles[i];
          const Pose2 p = a.track.at(t);
          const Eigen::Vector2d h = half(a);
          for (std::size_t j = i + 1; j < vehicles.size(); j++) {
            const Actor& b = *vehicles[j];
            const Eigen::Vector2d g = half(b);
            ASSERT_FALSE(
                overlap(p, h.x() - 0.2, h.y() - 0.2, b.track.at(t), g.x() - 0.2, g.y() - 0.2))
                << "actors " << a.id << " and " << b.id << " at t = " << t;
          }
          for (const Actor* st : standing) {
            const Pose2 q = st->track.at(0);
            ASSERT_FALSE(overlap(p, h.x(), h.y(), q, 0.01, 0.01))
                << "actor " << a.id << " through stander " << st->id << " at t = " << t;
          }
        }
    }
}

TEST(Procedural, DenseTrafficAddsRiderGroupsAndParkedTwoWheelersWithPeopleBeside) {
  for (const std::uint32_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    const Scenario plain = load(spec("street"), seed);
    const Scenario dense =
        load(spec("street", ", rider_groups: 2, two_wheelers: 8, standing: 0"), seed);
    // Asked for nothing more, the street is the one it was (no extra draw).
    EXPECT_EQ(plain.world_yaml, load(spec("street", ", rider_groups: 0"), seed).world_yaml);
    // Riders in a group: cyclists 2.2-3 m apart at the same speed at some time.
    int close_pairs = 0;
    for (std::size_t i = 0; i < dense.actors.size(); i++)
      for (std::size_t j = i + 1; j < dense.actors.size(); j++) {
        const Actor &a = dense.actors[i], &b = dense.actors[j];
        if (a.cls != ActorClass::Cyclist || b.cls != ActorClass::Cyclist) continue;
        const Pose2 pa = a.track.at(1.0), pb = b.track.at(1.0);
        const double d = std::hypot(pa.x - pb.x, pa.y - pb.y);
        if (d > 1.5 && d < 3.5 && std::abs(a.track.speed(1.0) - b.track.speed(1.0)) < 1e-9)
          close_pairs++;
      }
    EXPECT_GE(close_pairs, 2);
    // Parked two-wheelers (1.9 x 0.7 m boxes) with someone standing within 1.2 m of most.
    int bikes = 0, with_someone = 0;
    for (const Part& p : dense.statics) {
      if (p.kind != Part::Kind::Box || std::abs(p.box.half.x() - 0.95) > 1e-6 ||
          std::abs(p.box.half.y() - 0.35) > 1e-6)
        continue;
      bikes++;
      for (const Actor& a : dense.actors) {
        const Pose2 at = a.track.at(0.0);
        if (a.cls == ActorClass::Pedestrian && a.track.speed(0.0) == 0 &&
            std::hypot(at.x - p.box.center.x(), at.y - p.box.center.y()) < 1.2) {
          with_someone++;
          break;
        }
      }
    }
    EXPECT_GE(bikes, 3);
    EXPECT_GE(with_someone, 1);
  }
}
