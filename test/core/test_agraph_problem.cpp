#include <ceres/normal_prior.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.h"
#include "is_graphs/agraph/agraph_io.h"
#include "is_graphs/agraph/agraph_problem.h"
#include "is_graphs/common/ceres_compat.h"

namespace is_graphs {
namespace agraph {
namespace {

AGraph TwoRooms() { return LoadAGraph(testing::TwoRoomsPath()).value(); }

void ExpectSameGeometry(const AGraph& a, const AGraph& b, double tolerance) {
  for (size_t i = 0; i < a.surfaces.size(); ++i) {
    EXPECT_LT((a.surfaces[i].plane.normal - b.surfaces[i].plane.normal).norm(), tolerance) << i;
    EXPECT_NEAR(a.surfaces[i].plane.d, b.surfaces[i].plane.d, tolerance) << i;
  }
  for (size_t i = 0; i < a.walls.size(); ++i) {
    EXPECT_LT((a.walls[i].center - b.walls[i].center).norm(), tolerance) << "wall " << i;
  }
  for (size_t i = 0; i < a.rooms.size(); ++i) {
    EXPECT_LT((a.rooms[i].center - b.rooms[i].center).norm(), tolerance) << "room " << i;
  }
  for (size_t i = 0; i < a.doorways.size(); ++i) {
    EXPECT_LT((a.doorways[i].position - b.doorways[i].position).norm(), tolerance) << i;
  }
}

TEST(AGraphProblemConfig, Validate) {
  EXPECT_EQ(AGraphProblemConfig().Validate(), "");
  AGraphProblemConfig config;
  config.wall_centre_sigma = -0.1;
  EXPECT_NE(config.Validate().find("wall_centre_sigma"), std::string::npos);
  config = AGraphProblemConfig();
  config.huber_scale = -1.0;
  EXPECT_NE(config.Validate().find("huber_scale"), std::string::npos);
  config = AGraphProblemConfig();
  config.max_iterations = 0;
  EXPECT_NE(config.Validate().find("max_iterations"), std::string::npos);
  config = AGraphProblemConfig();
  config.huber_scale = 0.0;  // no robust loss: valid
  EXPECT_EQ(config.Validate(), "");
}

TEST(AGraphProblem, ConsistentGraphStaysPut) {
  const AGraph bim = TwoRooms();
  AGraphProblem problem(bim);
  const AGraphSolveSummary summary = problem.Solve();
  EXPECT_TRUE(summary.usable) << summary.ToString();
  EXPECT_LT(summary.initial_cost, 1e-20);
  EXPECT_LT(summary.final_cost, 1e-20);
  EXPECT_EQ(summary.parameter_blocks, 29);  // 10 × (normal, d) + 5 walls + 2 rooms + 2 doorways
  EXPECT_EQ(summary.residual_blocks, 20);   // 10 plane, 5 wall, 2 room priors, 3 doorway–room
  AGraph out = bim;
  ASSERT_TRUE(problem.WriteBack(out));
  ExpectSameGeometry(out, bim, 1e-12);
}

TEST(AGraphProblem, PerturbedWallCentreReturns) {
  const AGraph bim = TwoRooms();
  AGraph perturbed = bim;
  perturbed.walls[4].center += Eigen::Vector3d(0.2, 0.0, 0.0);  // the interior wall, x = 4.0
  AGraphProblem problem(perturbed);
  const AGraphSolveSummary summary = problem.Solve();
  ASSERT_TRUE(summary.usable) << summary.ToString();
  EXPECT_GT(summary.initial_cost, summary.final_cost);
  EXPECT_LT(summary.final_cost, 1e-12);
  AGraph out = perturbed;
  ASSERT_TRUE(problem.WriteBack(out));
  EXPECT_LT((out.walls[4].center - Eigen::Vector3d(4.0, 2.0, 0.0)).norm(), 1e-6)
      << out.walls[4].center.transpose();
  ExpectSameGeometry(out, bim, 1e-6);
}

TEST(AGraphProblem, PerturbedRoomAndDoorwayReturn) {
  const AGraph bim = TwoRooms();
  AGraph perturbed = bim;
  perturbed.rooms[1].center += Eigen::Vector3d(0.0, 0.3, 0.0);
  perturbed.doorways[0].position += Eigen::Vector3d(-0.1, 0.1, 0.0);
  // Only the initial values move; the measurements are the BIM's.
  AGraphProblem problem(bim);
  problem.RoomCentre(1)[1] += 0.3;
  problem.DoorwayPosition(0)[0] -= 0.1;
  problem.DoorwayPosition(0)[1] += 0.1;
  const AGraphSolveSummary summary = problem.Solve();
  ASSERT_TRUE(summary.usable) << summary.ToString();
  EXPECT_LT(summary.final_cost, 1e-12);
  AGraph out = perturbed;
  ASSERT_TRUE(problem.WriteBack(out));
  ExpectSameGeometry(out, bim, 1e-6);
}

TEST(AGraphProblem, NonParallelWallFacesGiveAFiniteSolution) {
  AGraph bim = TwoRooms();
  const double a = 5.0 * M_PI / 180.0;  // face 9 of the interior wall tilted by 5° about z
  bim.surfaces[9].plane = geometry::Plane::FromPointNormal(
      Eigen::Vector3d(4.1, 2.0, 0.0), Eigen::Vector3d(std::cos(a), std::sin(a), 0.0));
  AGraphProblem problem(bim);
  const AGraphSolveSummary summary = problem.Solve();
  ASSERT_TRUE(summary.usable) << summary.ToString();
  EXPECT_TRUE(std::isfinite(summary.final_cost));
  AGraph out = bim;
  ASSERT_TRUE(problem.WriteBack(out));
  EXPECT_TRUE(out.walls[4].center.allFinite());
  EXPECT_TRUE(out.surfaces[9].plane.normal.allFinite());
  EXPECT_NEAR(out.surfaces[9].plane.normal.norm(), 1.0, 1e-9);
  // w_s = (4, 2, 0) lies on both faces' mid-plane near the wall: the centre stays close to it.
  EXPECT_LT((out.walls[4].center - Eigen::Vector3d(4.0, 2.0, 0.0)).norm(), 0.02);
}

TEST(AGraphProblem, AddToALargerProblem) {
  const AGraph bim = TwoRooms();
  AGraphProblem agraph(bim);
  ceres::Problem problem;
  double other[2] = {1.0, 2.0};  // e.g. the merger's own blocks
  problem.AddParameterBlock(other, 2);
  agraph.AddTo(problem);
  EXPECT_EQ(problem.NumParameterBlocks(), 30);
  EXPECT_EQ(problem.NumResidualBlocks(), 20);
  EXPECT_EQ(problem.NumResiduals(), 60);
  ASSERT_TRUE(problem.HasParameterBlock(agraph.SurfaceNormal(3)));
  EXPECT_NE(ceres_compat::GetParameterization(problem, agraph.SurfaceNormal(3)), nullptr);
  EXPECT_EQ(ceres_compat::TangentSize(problem, agraph.SurfaceNormal(3)), 2);
  EXPECT_EQ(ceres_compat::GetParameterization(problem, agraph.WallCentre(0)), nullptr);
  EXPECT_DOUBLE_EQ(agraph.WallCentre(4)[0], 4.0);
  EXPECT_DOUBLE_EQ(*agraph.SurfaceOffset(3), 8.2);
}

TEST(AGraphProblem, AddConnectedToTakesTheWallsAndRoomsTouched) {
  const AGraph bim = TwoRooms();  // 10 surfaces, walls of two faces each, 2 rooms, 2 doorways
  const Wall& wall = bim.walls[0];
  {
    AGraphProblem agraph(bim);
    ceres::Problem problem;
    agraph.AddConnectedTo(problem, {wall.surface_a, 99, -1}, {});  // out-of-range ids ignored
    EXPECT_EQ(problem.NumParameterBlocks(), 5);  // both faces (normal, d) and the wall centre
    EXPECT_EQ(problem.NumResidualBlocks(), 3);   // two plane priors, the wall's factor
    EXPECT_TRUE(problem.HasParameterBlock(agraph.SurfaceNormal(wall.surface_b)));
    EXPECT_NE(ceres_compat::GetParameterization(problem, agraph.SurfaceNormal(wall.surface_b)),
              nullptr);
    EXPECT_FALSE(problem.HasParameterBlock(agraph.SurfaceNormal(bim.walls[1].surface_a)));
    EXPECT_FALSE(problem.HasParameterBlock(agraph.RoomCentre(0)));
  }
  {
    AGraphProblem agraph(bim);
    ceres::Problem problem;
    agraph.AddConnectedTo(problem, {}, {0});  // room 0, its door to room 1, that room
    EXPECT_TRUE(problem.HasParameterBlock(agraph.RoomCentre(1)));
    EXPECT_TRUE(problem.HasParameterBlock(agraph.DoorwayPosition(0)));
    EXPECT_FALSE(problem.HasParameterBlock(agraph.SurfaceOffset(0)));
  }
  {
    AGraphProblem agraph(bim);
    ceres::Problem problem;
    agraph.AddConnectedTo(problem, {}, {});
    EXPECT_EQ(problem.NumParameterBlocks(), 0);
  }
}

TEST(AGraphProblem, AddConnectedToSolvesLikeTheWholeGraph) {
  // A pull on one face (as a match would): the wall it belongs to moves the same whether the
  // rest of the A-Graph is in the problem or not.
  const AGraph bim = TwoRooms();
  const Wall& wall = bim.walls[0];
  auto solve = [&](bool whole, AGraphProblem& agraph) {
    ceres::Problem problem;
    if (whole)
      agraph.AddTo(problem);
    else
      agraph.AddConnectedTo(problem, {wall.surface_a}, {});
    ceres::Matrix a(1, 1);
    a(0, 0) = 1.0 / 0.01;
    ceres::Vector b(1);
    b(0) = *agraph.SurfaceOffset(wall.surface_a) + 0.05;
    problem.AddResidualBlock(new ceres::NormalPrior(a, b), nullptr,
                             agraph.SurfaceOffset(wall.surface_a));
    ceres::Solver::Options options;
    options.function_tolerance = 1e-14;
    options.gradient_tolerance = 1e-14;
    options.parameter_tolerance = 1e-14;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    ASSERT_TRUE(summary.IsSolutionUsable()) << summary.BriefReport();
  };
  AGraphProblem whole(bim), part(bim);
  solve(true, whole);
  solve(false, part);
  EXPECT_GT(std::abs(*part.SurfaceOffset(wall.surface_a) - bim.surfaces[wall.surface_a].plane.d),
            0.01);  // it did move
  for (int s : {wall.surface_a, wall.surface_b}) {
    EXPECT_NEAR(*part.SurfaceOffset(s), *whole.SurfaceOffset(s), 1e-6) << s;
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(part.SurfaceNormal(s)[i], whole.SurfaceNormal(s)[i], 1e-6) << s;
  }
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(part.WallCentre(wall.id)[i], whole.WallCentre(wall.id)[i], 1e-6);
}

TEST(AGraphProblem, WriteBackNeedsTheSameGraph) {
  AGraphProblem problem(TwoRooms());
  AGraph other = TwoRooms();
  other.rooms.pop_back();
  EXPECT_FALSE(problem.WriteBack(other));
}

TEST(AGraphProblem, EmptyGraph) {
  AGraphProblem problem{AGraph()};
  const AGraphSolveSummary summary = problem.Solve();
  EXPECT_TRUE(summary.usable);
  EXPECT_EQ(summary.residual_blocks, 0);
}

}  // namespace
}  // namespace agraph
}  // namespace is_graphs
