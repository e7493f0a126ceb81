// FirstNonFinite names the first non-finite value of an S-Graph a merge would use, and nothing
// on a finite one.
#include <gtest/gtest.h>

#include <limits>

#include "is_graphs/sgraph/finite_checks.h"

namespace is_graphs {
namespace sgraph {
namespace {

SGraph Small() {
  SGraph g;
  g.stamp = 10.0;
  for (int i = 0; i < 3; ++i) {
    Keyframe k;
    k.id = i;
    k.stamp = 10.0 + i;
    k.pose.translation() = Eigen::Vector3d(i, 0, 0);
    g.keyframes.push_back(k);
  }
  Plane p;
  p.id = 7;
  p.plane.normal = Eigen::Vector3d::UnitX();
  p.plane.d = 2.0;
  g.planes.push_back(p);
  PlaneObservation o;
  o.keyframe = 1;
  o.plane = 7;
  o.local = p.plane;
  g.observations.push_back(o);
  Room r;
  r.id = 3;
  g.rooms.push_back(r);
  return g;
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(SGraphFiniteChecks, NamesTheFirstNonFiniteValue) {
  EXPECT_EQ(FirstNonFinite(Small()), "");
  SGraph g = Small();
  g.keyframes[1].pose.translation().x() = kNaN;
  EXPECT_EQ(FirstNonFinite(g), "keyframe 1: pose");
  g = Small();
  g.keyframes[2].odom_pose.linear()(1, 1) = std::numeric_limits<double>::infinity();
  EXPECT_EQ(FirstNonFinite(g), "keyframe 2: odom_pose");
  g = Small();
  g.planes[0].plane.d = kNaN;
  EXPECT_EQ(FirstNonFinite(g), "plane 7: plane");
  g = Small();
  g.observations[0].local.normal.y() = kNaN;
  EXPECT_EQ(FirstNonFinite(g), "observation of plane 7 from keyframe 1");
  g = Small();
  g.rooms[0].center.z() = kNaN;
  EXPECT_EQ(FirstNonFinite(g), "room 3: center");
  g = Small();
  g.stamp = kNaN;
  EXPECT_EQ(FirstNonFinite(g), "stamp");
}

}  // namespace
}  // namespace sgraph
}  // namespace is_graphs
