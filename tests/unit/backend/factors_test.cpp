// Plane-observation, relative-pose and level-prior factors: Jacobians against
// numeric differentiation on their manifolds (Ceres' GradientChecker), and the
// plane residual against the project's plane transform (types/plane.h).
#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <ceres/sphere_manifold.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "backend/analytic_factors.h"
#include "backend/factors.h"
#include "backend/tilt_prior.h"
#include "types/plane.h"

namespace storey::backend {
namespace {

Pose randomPose(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::Quaterniond q(Eigen::Vector4d(g(rng), g(rng), g(rng), g(rng)).normalized());
  return Pose(q, Eigen::Vector3d(3 * g(rng), 3 * g(rng), g(rng)));
}

/// An upper-triangular 6x6 square-root information, 20 on the diagonal.
Eigen::Matrix<double, 6, 6> randomSqrtInfo6(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  Eigen::Matrix<double, 6, 6> L = Eigen::Matrix<double, 6, 6>::Identity() * 20.0;
  for (int r = 0; r < 6; ++r)
    for (int c = r + 1; c < 6; ++c) L(r, c) = u(rng);
  return L;
}

/// The parameter blocks (q_a, t_a, q_b, t_b) of a relative-pose cost.
std::vector<std::vector<double>> twoPoseValues(const Eigen::Quaterniond& qa,
                                               const Eigen::Vector3d& ta,
                                               const Eigen::Quaterniond& qb,
                                               const Eigen::Vector3d& tb) {
  return {{qa.x(), qa.y(), qa.z(), qa.w()},
          {ta.x(), ta.y(), ta.z()},
          {qb.x(), qb.y(), qb.z(), qb.w()},
          {tb.x(), tb.y(), tb.z()}};
}

Eigen::Matrix3d randomSqrtInfo(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  Eigen::Matrix3d L = Eigen::Matrix3d::Identity() * 5.0;
  for (int r = 0; r < 3; ++r)
    for (int c = r + 1; c < 3; ++c) L(r, c) = u(rng);
  return L;
}

TEST(PlaneFactor, JacobiansMatchNumericOnManifolds) {
  std::mt19937 rng(3);
  ceres::EigenQuaternionManifold quaternion;
  ceres::SphereManifold<3> sphere;
  const std::vector<const ceres::Manifold*> manifolds{&quaternion, nullptr, &sphere, nullptr};
  for (int trial = 0; trial < 20; ++trial) {
    const Pose T_world_kf = randomPose(rng);
    const Plane plane_world(Eigen::Vector3d::Random(), 2.0 + trial * 0.3);
    // Observation: the true plane in the keyframe, slightly perturbed.
    const Plane truth_kf = plane_world.transformed(T_world_kf.inverse());
    const Eigen::Vector3d n_obs =
        (truth_kf.normal() + 0.02 * Eigen::Vector3d::Random()).normalized();
    std::unique_ptr<ceres::CostFunction> cost(
        PlaneObservationFactor::create(n_obs, truth_kf.distance() + 0.05, randomSqrtInfo(rng)));
    const Eigen::Quaterniond& q = T_world_kf.rotation();
    double qv[4] = {q.x(), q.y(), q.z(), q.w()};
    double tv[3] = {T_world_kf.translation().x(), T_world_kf.translation().y(),
                    T_world_kf.translation().z()};
    Eigen::Vector3d n = plane_world.normal();
    double nv[3] = {n.x(), n.y(), n.z()};
    double dv[1] = {plane_world.distance()};
    const double* params[] = {qv, tv, nv, dv};
    ceres::NumericDiffOptions options;
    ceres::GradientChecker checker(cost.get(), &manifolds, options);
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(params, 1e-7, &results)) << results.error_log;
  }
}

TEST(PlaneFactor, ZeroResidualAtTheTruePlaneAndAgreesWithPlaneTransform) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    const Pose T_world_kf = randomPose(rng);
    const Plane plane_world(Eigen::Vector3d::Random(), 1.0 + trial);
    // The convention of DESIGN.md: n_b = R n_a, d_b = d_a + n_b . t under T_b_a.
    const Plane plane_kf = plane_world.transformed(T_world_kf.inverse());
    // Orient the landmark like the observation (observer on the side opposite n).
    Eigen::Vector3d n_w = T_world_kf.rotation() * plane_kf.normal();
    double d_w = plane_kf.distance() + n_w.dot(T_world_kf.translation());
    PlaneObservationFactor f(plane_kf.normal(), plane_kf.distance(), Eigen::Matrix3d::Identity());
    const Eigen::Quaterniond& q = T_world_kf.rotation();
    double qv[4] = {q.x(), q.y(), q.z(), q.w()};
    double r[3];
    ASSERT_TRUE(f(qv, T_world_kf.translation().data(), n_w.data(), &d_w, r));
    EXPECT_NEAR(Eigen::Vector3d(r[0], r[1], r[2]).norm(), 0.0, 1e-9);
    // Moving the keyframe 0.1 m along the normal changes the distance residual by -0.1.
    const Eigen::Vector3d t2 = T_world_kf.translation() + 0.1 * n_w;
    ASSERT_TRUE(f(qv, t2.data(), n_w.data(), &d_w, r));
    EXPECT_NEAR(r[2], -0.1, 1e-9);
  }
}

// The analytic cost functions the graph uses: the reference functors'
// residuals, their automatic derivatives, and numeric ones on the manifolds.
void expectSameEvaluation(const ceres::CostFunction& analytic, const ceres::CostFunction& reference,
                          const std::vector<std::vector<double>>& parameter_values,
                          const std::vector<const ceres::Manifold*>& manifolds) {
  const int residuals = analytic.num_residuals();
  const std::vector<std::int32_t>& sizes = analytic.parameter_block_sizes();
  std::vector<const double*> params;
  for (const auto& p : parameter_values) params.push_back(p.data());
  std::vector<double> r_a(residuals), r_b(residuals);
  std::vector<std::vector<double>> J_a, J_b;
  std::vector<double*> jac_a, jac_b;
  for (std::int32_t size : sizes) {
    J_a.emplace_back(static_cast<std::size_t>(residuals * size));
    J_b.emplace_back(static_cast<std::size_t>(residuals * size));
  }
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    jac_a.push_back(J_a[i].data());
    jac_b.push_back(J_b[i].data());
  }
  ASSERT_TRUE(analytic.Evaluate(params.data(), r_a.data(), jac_a.data()));
  ASSERT_TRUE(reference.Evaluate(params.data(), r_b.data(), jac_b.data()));
  for (int i = 0; i < residuals; ++i)
    EXPECT_NEAR(r_a[static_cast<std::size_t>(i)], r_b[static_cast<std::size_t>(i)], 1e-11);
  for (std::size_t b = 0; b < sizes.size(); ++b)
    for (std::size_t k = 0; k < J_a[b].size(); ++k)
      EXPECT_NEAR(J_a[b][k], J_b[b][k], 1e-10) << "parameter block " << b << ", entry " << k;
  std::vector<double> r_only(static_cast<std::size_t>(residuals));
  ASSERT_TRUE(analytic.Evaluate(params.data(), r_only.data(), nullptr));
  EXPECT_EQ(r_only, r_a);
  ceres::GradientChecker checker(&analytic, &manifolds, ceres::NumericDiffOptions());
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(params.data(), 1e-7, &results)) << results.error_log;
}

TEST(PlaneObservationCost, EqualsTheAutomaticDerivativesAndNumericOnManifolds) {
  std::mt19937 rng(13);
  ceres::EigenQuaternionManifold quaternion;
  ceres::SphereManifold<3> sphere;
  const std::vector<const ceres::Manifold*> manifolds{&quaternion, nullptr, &sphere, nullptr};
  for (int trial = 0; trial < 30; ++trial) {
    const Pose T_world_kf = randomPose(rng);
    const PlaneObservationFactor factor(Eigen::Vector3d::Random().normalized(), 0.5 + 0.3 * trial,
                                        randomSqrtInfo(rng));
    const PlaneObservationCost analytic(factor);
    const ceres::AutoDiffCostFunction<PlaneObservationFactor, 3, 4, 3, 3, 1> reference(
        new PlaneObservationFactor(factor));
    const Eigen::Quaterniond& q = T_world_kf.rotation();
    const Eigen::Vector3d& t = T_world_kf.translation();
    const Eigen::Vector3d n = Eigen::Vector3d::Random().normalized();
    const std::vector<std::vector<double>> values{
        {q.x(), q.y(), q.z(), q.w()}, {t.x(), t.y(), t.z()}, {n.x(), n.y(), n.z()}, {trial - 10.0}};
    expectSameEvaluation(analytic, reference, values, manifolds);
  }
}

TEST(RelativePoseCost, EqualsTheAutomaticDerivativesAndNumericOnManifolds) {
  std::mt19937 rng(17);
  ceres::EigenQuaternionManifold quaternion;
  const std::vector<const ceres::Manifold*> manifolds{&quaternion, nullptr, &quaternion, nullptr};
  for (int trial = 0; trial < 30; ++trial) {
    const Pose a = randomPose(rng), b = randomPose(rng), measured = randomPose(rng);
    const Eigen::Matrix<double, 6, 6> L = randomSqrtInfo6(rng);
    const RelativePoseFactor factor(measured, L);
    const RelativePoseCost analytic(factor);
    const ceres::AutoDiffCostFunction<RelativePoseFactor, 6, 4, 3, 4, 3> reference(
        new RelativePoseFactor(factor));
    const Eigen::Quaterniond &qa = a.rotation(), &qb = b.rotation();
    expectSameEvaluation(analytic, reference,
                         twoPoseValues(qa, a.translation(), qb, b.translation()), manifolds);
  }
}

TEST(HeadingRelativePoseCost, EqualsTheAutomaticDerivativesAndNumericOnManifolds) {
  std::mt19937 rng(19);
  ceres::EigenQuaternionManifold quaternion;
  const std::vector<const ceres::Manifold*> manifolds{&quaternion, nullptr, &quaternion, nullptr};
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (int trial = 0; trial < 30; ++trial) {
    const Pose a = randomPose(rng), b = randomPose(rng), measured = randomPose(rng);
    const Eigen::Quaterniond q_odom_a = randomPose(rng).rotation();
    const Eigen::Quaterniond levelling(
        Eigen::AngleAxisd(0.01 * trial, Eigen::Vector3d(u(rng), u(rng), 0.0).normalized()));
    const Eigen::Matrix<double, 6, 6> L = randomSqrtInfo6(rng);
    const HeadingRelativePoseFactor factor(measured, q_odom_a, &levelling, L);
    const HeadingRelativePoseCost analytic(factor);
    const ceres::AutoDiffCostFunction<HeadingRelativePoseFactor, 6, 4, 3, 4, 3> reference(
        new HeadingRelativePoseFactor(factor));
    // Keyframe a where the graph keeps it: the odometry's levelled attitude
    // turned by any yaw and tilted by up to 0.1 rad (the yaw of a far larger
    // tilt is ill-defined, and so is the numeric derivative).
    const Eigen::Quaterniond qa =
        Eigen::AngleAxisd(10.0 * u(rng), Eigen::Vector3d::UnitZ()) *
        Eigen::AngleAxisd(0.5 * u(rng), Eigen::Vector3d(u(rng), u(rng), 0.0).normalized()) *
        (levelling * q_odom_a);
    const Eigen::Quaterniond& qb = b.rotation();
    expectSameEvaluation(analytic, reference,
                         twoPoseValues(qa, a.translation(), qb, b.translation()), manifolds);
  }
}

// The heading-frame edge: zero at the odometry's own poses (levelled), the
// same translation residual whatever the graph's tilt of keyframe a, and
// turned with a's yaw; the body-frame edge turns the displacement with the
// tilt (1 m along x and 3 mrad of pitch: 3 mm of height).
TEST(HeadingRelativePoseCost, ATiltOfTheKeyframeDoesNotTurnTheDisplacementIntoHeight) {
  const Eigen::Quaterniond levelling(Eigen::AngleAxisd(0.004, Eigen::Vector3d::UnitX()));
  const Pose odom_a(Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                                       Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitY())),
                    Eigen::Vector3d(1.0, 2.0, 0.5));
  const Pose odom_b(
      odom_a.rotation() * Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ())),
      odom_a.translation() + Eigen::Vector3d(0.8, 0.6, 0.1));
  const Pose level(levelling, Eigen::Vector3d::Zero());
  const Pose world_a = level * odom_a, world_b = level * odom_b;
  const Pose T_a_b = odom_a.inverse() * odom_b;
  const Eigen::Matrix<double, 6, 6> L = Eigen::Matrix<double, 6, 6>::Identity();
  const HeadingRelativePoseCost heading(
      HeadingRelativePoseFactor(T_a_b, odom_a.rotation(), &levelling, L));
  const RelativePoseCost body(RelativePoseFactor(T_a_b, L));
  auto evaluate = [](const ceres::CostFunction& cost, const Pose& a, const Pose& b) {
    const Eigen::Quaterniond &qa = a.rotation(), &qb = b.rotation();
    const double q_a[4] = {qa.x(), qa.y(), qa.z(), qa.w()},
                 q_b[4] = {qb.x(), qb.y(), qb.z(), qb.w()};
    const double* params[] = {q_a, a.translation().data(), q_b, b.translation().data()};
    Eigen::Matrix<double, 6, 1> r;
    EXPECT_TRUE(cost.Evaluate(params, r.data(), nullptr));
    return r;
  };
  EXPECT_LT(evaluate(heading, world_a, world_b).norm(), 1e-12);
  EXPECT_LT(evaluate(body, world_a, world_b).norm(), 1e-12);
  // The graph pitches a by 3 mrad (its level floor says so); b moves with it.
  const Pose tilt(Eigen::Quaterniond(Eigen::AngleAxisd(0.003, Eigen::Vector3d::UnitY())),
                  Eigen::Vector3d::Zero());
  const Pose tilted_a(tilt.rotation() * world_a.rotation(), world_a.translation());
  const Pose tilted_b(tilt.rotation() * world_b.rotation(), world_b.translation());
  const Eigen::Matrix<double, 6, 1> r_heading = evaluate(heading, tilted_a, tilted_b);
  const Eigen::Matrix<double, 6, 1> r_body = evaluate(body, tilted_a, tilted_b);
  EXPECT_LT(r_heading.head<3>().norm(), 1e-12);
  EXPECT_GT(r_body.head<3>().norm(), 0.002);
  // A yaw correction of a turns the displacement with it, as the body edge does.
  const Pose yaw(Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitZ())),
                 Eigen::Vector3d::Zero());
  const Pose turned_a = yaw * world_a;
  const Pose turned_b = yaw * world_b;
  EXPECT_LT(evaluate(heading, turned_a, turned_b).norm(), 1e-12);
  EXPECT_LT(evaluate(body, turned_a, turned_b).norm(), 1e-12);
  EXPECT_GT(evaluate(heading, turned_a, world_b).head<3>().norm(), 0.01);
}

// A held keyframe's observation (plane-only, analytic) is the full factor with
// the pose fixed: the same residual and the same Jacobians for the plane.
TEST(HeldPlaneObservationFactor, EqualsTheFullFactorWithThePoseHeld) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Pose T_world_kf = randomPose(rng);
    const Eigen::Vector3d n_obs = Eigen::Vector3d::Random().normalized();
    const PlaneObservationFactor observation(n_obs, 1.0 + 0.2 * trial, randomSqrtInfo(rng));
    std::unique_ptr<ceres::CostFunction> full(
        new ceres::AutoDiffCostFunction<PlaneObservationFactor, 3, 4, 3, 3, 1>(
            new PlaneObservationFactor(observation)));
    const HeldPlaneObservationFactor held(observation, T_world_kf.rotationMatrix(),
                                          T_world_kf.translation());
    const Eigen::Quaterniond& q = T_world_kf.rotation();
    double qv[4] = {q.x(), q.y(), q.z(), q.w()};
    double tv[3] = {T_world_kf.translation().x(), T_world_kf.translation().y(),
                    T_world_kf.translation().z()};
    const Eigen::Vector3d n = Eigen::Vector3d::Random().normalized();
    double nv[3] = {n.x(), n.y(), n.z()};
    double dv[1] = {3.0 * (trial % 5) - 4.0};
    const double* full_params[] = {qv, tv, nv, dv};
    const double* held_params[] = {nv, dv};
    double r_full[3], r_held[3];
    double Jq[12], Jt[9], Jn_full[9], Jd_full[3], Jn_held[9], Jd_held[3];
    double* full_jacobians[] = {Jq, Jt, Jn_full, Jd_full};
    double* held_jacobians[] = {Jn_held, Jd_held};
    ASSERT_TRUE(full->Evaluate(full_params, r_full, full_jacobians));
    ASSERT_TRUE(held.Evaluate(held_params, r_held, held_jacobians));
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(r_held[i], r_full[i], 1e-12);
      EXPECT_NEAR(Jd_held[i], Jd_full[i], 1e-12);
    }
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(Jn_held[i], Jn_full[i], 1e-12);
    // Residual only, no Jacobians asked for.
    double r_only[3];
    ASSERT_TRUE(held.Evaluate(held_params, r_only, nullptr));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(r_only[i], r_held[i]);
  }
}

TEST(RelativePoseFactor, JacobiansMatchNumericOnManifolds) {
  std::mt19937 rng(11);
  ceres::EigenQuaternionManifold quaternion;
  const std::vector<const ceres::Manifold*> manifolds{&quaternion, nullptr, &quaternion, nullptr};
  for (int trial = 0; trial < 20; ++trial) {
    const Pose a = randomPose(rng), b = randomPose(rng);
    const Pose measured =
        (a.inverse() * b) *
        Pose(Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d(1, 2, 3).normalized())),
             Eigen::Vector3d(0.02, -0.01, 0.03));
    Eigen::Matrix<double, 6, 6> L = Eigen::Matrix<double, 6, 6>::Identity() * 10.0;
    L(0, 4) = 0.5;
    std::unique_ptr<ceres::CostFunction> cost(RelativePoseFactor::create(measured, L));
    double qa[4] = {a.rotation().x(), a.rotation().y(), a.rotation().z(), a.rotation().w()};
    double qb[4] = {b.rotation().x(), b.rotation().y(), b.rotation().z(), b.rotation().w()};
    Eigen::Vector3d ta = a.translation(), tb = b.translation();
    const double* params[] = {qa, ta.data(), qb, tb.data()};
    ceres::NumericDiffOptions options;
    ceres::GradientChecker checker(cost.get(), &manifolds, options);
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(params, 1e-7, &results)) << results.error_log;
    // Exact measurement: zero residual.
    std::unique_ptr<ceres::CostFunction> exact(RelativePoseFactor::create(a.inverse() * b, L));
    double r[6];
    ASSERT_TRUE(exact->Evaluate(params, r, nullptr));
    const Eigen::Map<Eigen::Matrix<double, 6, 1>> rv(r);
    EXPECT_NEAR(rv.norm(), 0.0, 1e-9);
  }
}

TEST(RotationPriorFactor, JacobiansMatchNumericOnTheQuaternionManifold) {
  std::mt19937 rng(17);
  ceres::EigenQuaternionManifold quaternion;
  const std::vector<const ceres::Manifold*> manifolds{&quaternion};
  for (int trial = 0; trial < 10; ++trial) {
    const Pose a = randomPose(rng), b = randomPose(rng);
    std::unique_ptr<ceres::CostFunction> cost(
        RotationPriorFactor::create(a.rotation(), Eigen::Vector3d(100, 200, 1e4).asDiagonal()));
    const Eigen::Quaterniond q = a.rotation().slerp(0.1, b.rotation());
    double qv[4] = {q.x(), q.y(), q.z(), q.w()};
    const double* params[] = {qv};
    ceres::NumericDiffOptions options;
    ceres::GradientChecker checker(cost.get(), &manifolds, options);
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(params, 1e-7, &results)) << results.error_log;
  }
}

TEST(LevelPriorFactor, JacobiansMatchNumericOnTheSphere) {
  ceres::SphereManifold<3> sphere;
  const std::vector<const ceres::Manifold*> manifolds{&sphere};
  for (bool level : {true, false}) {
    std::unique_ptr<ceres::CostFunction> cost(LevelPriorFactor::create(level, 0.01));
    Eigen::Vector3d n = Eigen::Vector3d(0.05, -0.03, level ? 1.0 : 0.02).normalized();
    if (!level) n = Eigen::Vector3d(0.7, 0.7, 0.03).normalized();
    const double* params[] = {n.data()};
    ceres::NumericDiffOptions options;
    ceres::GradientChecker checker(cost.get(), &manifolds, options);
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(params, 1e-7, &results)) << results.error_log;
  }
}

TEST(TiltPriorCost, JacobiansMatchNumericOnTheQuaternionManifold) {
  std::mt19937 rng(23);
  ceres::EigenQuaternionManifold quaternion;
  const std::vector<const ceres::Manifold*> manifolds{&quaternion};
  for (int trial = 0; trial < 10; ++trial) {
    const Pose a = randomPose(rng), b = randomPose(rng);
    const TiltPriorCost cost(a.rotation(), 0.005);
    const Eigen::Quaterniond q = a.rotation().slerp(0.1, b.rotation());
    double qv[4] = {q.x(), q.y(), q.z(), q.w()};
    const double* params[] = {qv};
    ceres::NumericDiffOptions options;
    ceres::GradientChecker checker(&cost, &manifolds, options);
    ceres::GradientChecker::ProbeResults results;
    checker.Probe(params, 1e-7, &results);
    // The derivative along yaw is zero, where a relative comparison is
    // meaningless: compare against the Jacobian's scale instead.
    const Eigen::MatrixXd& analytic = results.local_jacobians.at(0);
    const Eigen::MatrixXd& numeric = results.local_numeric_jacobians.at(0);
    ASSERT_EQ(analytic.rows(), 2);
    ASSERT_EQ(analytic.cols(), 3);
    EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-7 * numeric.cwiseAbs().maxCoeff())
        << results.error_log;
  }
}

TEST(TiltPriorCost, MeasuresTheTiltAndIgnoresYaw) {
  std::mt19937 rng(29);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Quaterniond q_ref = randomPose(rng).rotation();
    const double sigma = 0.004;
    const TiltPriorCost cost(q_ref, sigma);
    auto residualNorm = [&](const Eigen::Quaterniond& q) {
      double qv[4] = {q.x(), q.y(), q.z(), q.w()};
      const double* params[] = {qv};
      double r[2];
      EXPECT_TRUE(cost.Evaluate(params, r, nullptr));
      return std::hypot(r[0], r[1]) * sigma;
    };
    // Any yaw (a turn about the world's up) leaves the tilt at zero.
    const Eigen::Quaterniond yawed =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.3 + trial, Eigen::Vector3d::UnitZ())) * q_ref;
    EXPECT_NEAR(residualNorm(yawed), 0.0, 1e-12);
    // A tilt by an angle about a horizontal world axis: |r| sigma = sin(angle), with any yaw too.
    const double angle = 0.01 * (trial + 1);
    const Eigen::Vector3d axis(std::cos(trial), std::sin(trial), 0.0);
    const Eigen::Quaterniond tilted =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ())) *
        Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)) * q_ref;
    EXPECT_NEAR(residualNorm(tilted), std::sin(angle), 1e-12);
  }
}

/// The span in keyframe a's frame: its residual is the height change the
/// graph's attitude of a gives the odometry's relative translation, its
/// derivatives match numeric ones on the quaternion manifold, and a yaw of a
/// (about the world's up) does not change it.
TEST(KeyframeHeightDifferenceCost, HeightOfTheTurnedTranslationAndNumericJacobians) {
  std::mt19937 rng(31);
  ceres::EigenQuaternionManifold quaternion;
  const std::vector<const ceres::Manifold*> manifolds{&quaternion, nullptr, nullptr};
  for (int trial = 0; trial < 20; ++trial) {
    const Pose a = randomPose(rng), b = randomPose(rng);
    const Eigen::Vector3d p_a_ab = 3.0 * Eigen::Vector3d::Random();
    const double sigma = 0.01;
    const KeyframeHeightDifferenceCost cost(p_a_ab, sigma);
    auto residual = [&](const Eigen::Quaterniond& q) {
      const Eigen::Vector3d &ta = a.translation(), &tb = b.translation();
      double qv[4] = {q.x(), q.y(), q.z(), q.w()};
      const double* params[] = {qv, ta.data(), tb.data()};
      double r = 0.0;
      EXPECT_TRUE(cost.Evaluate(params, &r, nullptr));
      return r;
    };
    const Eigen::Quaterniond& qa = a.rotation();
    const double expected = ((b.translation() - a.translation()).z() - (qa * p_a_ab).z()) / sigma;
    EXPECT_NEAR(residual(qa), expected, 1e-9);
    const Eigen::Quaterniond yawed(Eigen::AngleAxisd(0.7 + trial, Eigen::Vector3d::UnitZ()));
    EXPECT_NEAR(residual(yawed * qa), expected, 1e-9);

    double qv[4] = {qa.x(), qa.y(), qa.z(), qa.w()};
    const double* params[] = {qv, a.translation().data(), b.translation().data()};
    ceres::GradientChecker checker(&cost, &manifolds, ceres::NumericDiffOptions());
    ceres::GradientChecker::ProbeResults results;
    checker.Probe(params, 1e-7, &results);
    // The derivative along the world's yaw is zero, where a relative
    // comparison is meaningless: compare against each block's scale.
    for (std::size_t k = 0; k < 3; ++k) {
      const Eigen::MatrixXd& analytic = results.local_jacobians.at(static_cast<int>(k));
      const Eigen::MatrixXd& numeric = results.local_numeric_jacobians.at(static_cast<int>(k));
      EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-7 * numeric.cwiseAbs().maxCoeff())
          << results.error_log;
    }
  }
}

}  // namespace
}  // namespace storey::backend
