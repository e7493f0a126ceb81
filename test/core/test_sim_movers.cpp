// People, carts and doors that move (scene.people, scene.doors): where a mover is along its path,
// beams meeting bodies, a path through a wall refused with its field, a door leaf blocking when
// shut and not when open, and scans on the office with people in view.
#include <gtest/gtest.h>

#include <cmath>

#include "is_graphs/sim/movers.h"
#include "is_graphs/sim/scenario_yaml.h"
#include "is_graphs/sim/simulation.h"
#include "sim_office_helpers.h"
#include "sim_test_helpers.h"

namespace is_graphs {
namespace sim {
namespace {

using testing::HaveConverter;
using testing::Prepare;

TEST(SimMovers, AlongAPathBackAndForth) {
  const std::vector<Eigen::Vector2d> path{{0, 0}, {4, 0}, {4, 3}};  // 7 m
  Eigen::Vector2d heading;
  EXPECT_TRUE(Movers::AlongPath(path, 1.0, &heading).isApprox(Eigen::Vector2d(1, 0)));
  EXPECT_TRUE(heading.isApprox(Eigen::Vector2d(1, 0)));
  EXPECT_TRUE(Movers::AlongPath(path, 5.0, &heading).isApprox(Eigen::Vector2d(4, 1)));
  EXPECT_TRUE(heading.isApprox(Eigen::Vector2d(0, 1)));
  // 7 m out, then back: 9 m walked is 2 m back from the end, heading down.
  EXPECT_TRUE(Movers::AlongPath(path, 9.0, &heading).isApprox(Eigen::Vector2d(4, 1)));
  EXPECT_TRUE(heading.isApprox(Eigen::Vector2d(0, -1)));
  EXPECT_TRUE(Movers::AlongPath(path, 14.0 + 1.0, &heading).isApprox(Eigen::Vector2d(1, 0)));
}

TEST(SimMovers, BeamsMeetPeopleAndBoxes) {
  MovingBody person;
  person.centre = {5.0, 0.0};
  person.radius = 0.25;
  person.size = {0.0, 0.0, 1.75};
  person.reflectivity = 0.3f;
  MovingBody cart;
  cart.box = true;
  cart.centre = {0.0, 3.0};
  cart.yaw = M_PI / 2;  // 1 m long along y, 0.6 m wide along x
  cart.size = {1.0, 0.6, 1.0};
  cart.reflectivity = 0.5f;
  const std::vector<MovingBody> bodies{person, cart};
  float d = 0.0f, r = 0.0f;
  Eigen::Vector3f n;
  const Eigen::Vector3f origin(0.0f, 0.0f, 0.7f);
  ASSERT_TRUE(
      IntersectBodies(bodies, Ray{origin, Eigen::Vector3f::UnitX(), 30.f}, 30.f, &d, &n, &r));
  EXPECT_NEAR(d, 4.75f, 1e-5);
  EXPECT_TRUE(n.isApprox(-Eigen::Vector3f::UnitX()));
  EXPECT_FLOAT_EQ(r, 0.3f);
  ASSERT_TRUE(
      IntersectBodies(bodies, Ray{origin, Eigen::Vector3f::UnitY(), 30.f}, 30.f, &d, &n, &r));
  EXPECT_NEAR(d, 2.5f, 1e-5);  // the cart's near end
  EXPECT_TRUE(n.isApprox(-Eigen::Vector3f::UnitY(), 1e-5f));
  EXPECT_FLOAT_EQ(r, 0.5f);
  // Over the person's head, past the cart's side, and nearer than the person: no hit.
  const Eigen::Vector3f up = Eigen::Vector3f(1.0f, 0.0f, 0.3f).normalized();
  EXPECT_FALSE(IntersectBodies(bodies, Ray{origin, up, 30.f}, 30.f, &d, &n, &r));
  EXPECT_FALSE(IntersectBodies(
      bodies, Ray{Eigen::Vector3f(0.5f, 0.0f, 0.7f), Eigen::Vector3f::UnitY(), 30.f}, 30.f, &d, &n,
      &r));
  EXPECT_FALSE(
      IntersectBodies(bodies, Ray{origin, Eigen::Vector3f::UnitX(), 4.0f}, 4.0f, &d, &n, &r));
}

TEST(SimMovers, PeopleWalkTheirRoutesAndDoorsSwing) {
  if (!HaveConverter()) GTEST_SKIP() << "bim/office.ifc or the converter's venv is missing";
  const auto s = Prepare(R"(
building: bim/office.ifc
seed: 11
duration: 8
trajectory: {rooms: [Corridor, "102"], speed: 1.0, pause: 0.2}
scene:
  people: [{rooms: ["101", Corridor, "103"]}, {type: cart, rooms: [Meeting, Corridor], start: 3}]
  doors: [{between: [Corridor, "104"], period: 10, hold_distance: 0}]
)");
  ASSERT_TRUE(s);
  ASSERT_FALSE(s->movers.empty());
  const auto at0 = s->movers.BodiesAt(0.0), at2 = s->movers.BodiesAt(2.0);
  ASSERT_EQ(at0.size(), 3u);
  EXPECT_NEAR((at2[0].centre - at0[0].centre).norm(), 2.6, 0.3);  // 1.3 m/s, about straight
  EXPECT_FALSE(at0[0].box);
  EXPECT_TRUE(at0[1].box);
  // The door: shut at 0 s (in the wall's line), open at 5 s (turned 90 degrees about its hinge).
  const Eigen::Vector2d shut = at0[2].centre, open = s->movers.BodiesAt(5.0)[2].centre;
  EXPECT_NEAR((shut - open).norm(), std::sqrt(2.0) * 0.5 * (at0[2].size.x() + 0.02), 0.02);
  // A beam across the doorway at 1 m height meets the shut leaf and passes the open one.
  const Eigen::Vector2d normal(-std::sin(at0[2].yaw), std::cos(at0[2].yaw));
  const Eigen::Vector2d from = shut - 1.0 * normal;
  const Ray across{Eigen::Vector3f(from.x(), from.y(), s->floor_z + 1.0f),
                   Eigen::Vector3f(normal.x(), normal.y(), 0.0f), 2.0f};
  float d = 0.0f, r = 0.0f;
  Eigen::Vector3f n;
  EXPECT_TRUE(IntersectBodies({at0[2]}, across, 2.0f, &d, &n, &r));
  EXPECT_NEAR(d, 1.0 - 0.02, 0.01);
  EXPECT_FALSE(IntersectBodies({s->movers.BodiesAt(5.0)[2]}, across, 2.0f, &d, &n, &r));
}

TEST(SimMovers, ScansSeeThePeopleAndStayDeterministic) {
  if (!HaveConverter()) GTEST_SKIP() << "bim/office.ifc or the converter's venv is missing";
  const char* base = R"(
building: bim/office.ifc
seed: 11
duration: 4
trajectory: {rooms: [Corridor, "102"], speed: 1.0, pause: 0.2}
)";
  const std::string with_people =
      std::string(base) + "scene: {people: [{rooms: [\"101\", Corridor, \"103\"]}]}\n";
  const auto plain = Prepare(base), a = Prepare(with_people), b = Prepare(with_people);
  ASSERT_TRUE(plain && a && b);
  EXPECT_TRUE(plain->movers.empty());
  int near_person = 0, near_plain = 0, changed = 0;
  for (int k = 0; k < 20; ++k) {
    const double t = 0.1 * k;
    const LidarScan p = plain->scans->Simulate(k, t), x = a->scans->Simulate(k, t),
                    y = b->scans->Simulate(k, t);
    ASSERT_EQ(x.points.size(), y.points.size());
    for (size_t i = 0; i < x.points.size(); ++i) ASSERT_EQ(x.points[i].x, y.points[i].x) << i;
    changed += x.points.size() != p.points.size();
    // Points within 0.35 m of the person's axis, in bim.
    const MovingBody person = a->movers.BodiesAt(t)[0];
    const Eigen::Isometry3d bim_T_sensor = a->motion->BasePose(t) * a->base_T_sensor;
    auto near = [&](const LidarScan& scan) {
      int n = 0;
      for (const LidarPoint& q : scan.points) {
        const Eigen::Vector3d w = bim_T_sensor * Eigen::Vector3d(q.x, q.y, q.z);
        n += (w.head<2>() - person.centre).norm() < 0.35 && w.z() > a->floor_z + 0.2;
      }
      return n;
    };
    near_person += near(x);
    near_plain += near(p);
  }
  EXPECT_GT(near_person, near_plain + 50) << "the person is in view: " << near_person << " vs "
                                          << near_plain << " points where it stands";
  EXPECT_GT(changed, 0);
}

TEST(SimMovers, BadPathsAndDoorsNameTheirField) {
  if (!HaveConverter()) GTEST_SKIP() << "bim/office.ifc or the converter's venv is missing";
  auto error = [](const std::string& scene) {
    const std::string yaml = "building: bim/office.ifc\ntrajectory: {rooms: [Corridor]}\n" + scene;
    const Result<ScenarioConfig> c = ParseScenarioYaml(yaml, "t.yaml", testing::kSourceRoot);
    if (!c.ok()) return c.error();
    const auto s = PrepareSimulation(c.value(), std::string(IS_GRAPHS_TEST_TMP_DIR) + "/bim_cache");
    return s.ok() ? std::string() : s.error();
  };
  // Straight from office 101 into 102 through the wall between them.
  const std::string through = error(
      "scene: {people: [{rooms: [Corridor, \"101\"]}, {waypoints: [[2.0, 9.6], [6.0, 9.6]]}]}\n");
  EXPECT_NE(through.find("scene.people[1].waypoints: the walk from (2.00, 9.60) to (6.00, 9.60) "
                         "is blocked at"),
            std::string::npos)
      << through;
  EXPECT_NE(error("scene: {people: [{waypoints: [[2.0, 9.6], [-30.0, 9.6]]}]}\n")
                .find("scene.people[0].waypoints[1]: (-30.00, 9.60) is in no room"),
            std::string::npos);
  EXPECT_NE(error("scene: {people: [{rooms: [Corridor, Attic]}]}\n").find("scene.people[0]"),
            std::string::npos);
  EXPECT_NE(error("scene: {doors: [{between: [\"101\", \"102\"]}]}\n")
                .find("scene.doors[0].between: no door or opening joins '101' and '102'"),
            std::string::npos);
  EXPECT_NE(error("scene: {people: [{rooms: [Corridor, \"101\"], speed: 9}]}\n")
                .find("scene.people[0].speed: must be in [0, 3]"),
            std::string::npos);
  EXPECT_NE(error("scene: {people: [{type: dog, rooms: [Corridor, \"101\"]}]}\n")
                .find("scene.people[0].type: must be person or cart"),
            std::string::npos);
  EXPECT_NE(error("scene: {people: [{rooms: [Corridor]}]}\n").find("scene.people[0].rooms"),
            std::string::npos);
  EXPECT_NE(error("scene: {doors: [{between: [Corridor, \"101\"], phase: 2}]}\n")
                .find("scene.doors[0].phase"),
            std::string::npos);
  EXPECT_NE(error("scene: {people: [{rooms: [Corridor, \"101\"], legs: 2}]}\n")
                .find("scene.people[0].legs: unknown key"),
            std::string::npos);
}

}  // namespace
}  // namespace sim
}  // namespace is_graphs
