#include "backend/association.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "backend/plane_math.h"

namespace storey::backend {

const char* toString(AssociationOutcome outcome) {
  switch (outcome) {
    case AssociationOutcome::kMatched:
      return "matched";
    case AssociationOutcome::kNewPlane:
      return "new_plane";
    case AssociationOutcome::kAmbiguous:
      return "ambiguous";
    case AssociationOutcome::kNearExisting:
      return "near_existing_plane";
    case AssociationOutcome::kRoughFit:
      return "rough_fit";
    case AssociationOutcome::kCount:
      break;
  }
  return "unknown";
}

const char* toString(GateReject reason) {
  switch (reason) {
    case GateReject::kFacing:
      return "facing_the_other_way";
    case GateReject::kAngle:
      return "angle_gate";
    case GateReject::kDistance:
      return "distance_gate";
    case GateReject::kMahalanobis:
      return "uncertainty_gate";
    case GateReject::kFaceChange:
      return "not_the_tracked_face";
    case GateReject::kCount:
      break;
  }
  return "unknown";
}

namespace {

constexpr double kDeg = M_PI / 180.0;
using Matrix36 = Eigen::Matrix<double, 3, 6>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

/// A candidate pair, linearised in the keyframe pose correction
/// delta = (phi, rho): R' = R Exp(phi), t' = t + R rho.
struct Candidate {
  int prediction = -1;
  double chi2 = 0.0;
  Eigen::Vector3d r0;  // [B^T n_p ; d_p - d_o]
  Matrix36 J;          // d r / d delta
  Eigen::Matrix3d W;   // information of the pair (fit + landmark/model)
};

struct Hypothesis {
  std::vector<int> choice;  // per SRP: index into its candidates, or -1 = new plane
  double cost = 0.0;
};

}  // namespace

AssociationResult associate(const std::vector<DetectedPlane>& srps,
                            const std::vector<PlanePrediction>& predictions,
                            const AssociationConfig& config, const Eigen::Vector3d& up_kf) {
  AssociationResult result;
  result.srps.resize(srps.size());
  const double cos_gate = std::cos(config.angle_gate_deg * kDeg);
  const double sep = std::max(config.new_plane_separation, 1.0);
  const double cos_near = std::cos(std::min(sep * config.angle_gate_deg, 89.0) * kDeg);
  const Eigen::Vector3d model_var(config.plane_sigma_rotation * config.plane_sigma_rotation,
                                  config.plane_sigma_rotation * config.plane_sigma_rotation,
                                  config.plane_sigma_distance * config.plane_sigma_distance);
  // Uncertainty of the predicted pose's correction delta = (phi, rho), in the
  // keyframe frame: rotation about the up direction u (yaw) with
  // pose_sigma_rotation, about the horizontal axes (tilt) with pose_sigma_tilt,
  // translation isotropic: Sigma_phi = s_tilt^2 I + (s_yaw^2 - s_tilt^2) u u^T.
  const Eigen::Vector3d up = up_kf.normalized();
  const double var_yaw = config.pose_sigma_rotation * config.pose_sigma_rotation;
  const double var_tilt = config.pose_sigma_tilt * config.pose_sigma_tilt;
  const double var_t = config.pose_sigma_translation * config.pose_sigma_translation;
  const Eigen::Vector3d pose_var(var_tilt, var_tilt, var_t);

  // 1. Gates, pair by pair.
  std::vector<std::vector<Candidate>> candidates(srps.size());
  std::vector<bool> near_existing(srps.size(), false);
  for (std::size_t i = 0; i < srps.size(); ++i) {
    const Eigen::Vector3d& n_o = srps[i].plane.normal();
    const double d_o = srps[i].plane.distance();
    const Eigen::Matrix<double, 3, 2> B = tangentBasis(n_o);
    for (std::size_t j = 0; j < predictions.size(); ++j) {
      const PlanePrediction& p = predictions[j];
      const double cos_angle = p.n_kf.dot(n_o);
      const double dd = p.d_kf - d_o;
      // A tracked landmark's newest view, moved here by the odometry, tells
      // whether the SRP is the same surface far better than the graph's
      // prediction: beyond track_gate it is another one (a parallel face).
      if (p.tracked && cos_angle >= cos_gate &&
          std::abs(p.n_track_kf.dot(srps[i].centroid) - p.d_track_kf) > config.track_gate) {
        ++result.gate_rejects[static_cast<std::size_t>(GateReject::kFaceChange)];
        continue;
      }
      // Only a confirmed landmark keeps a new plane from being made next to it:
      // one seen once may be a phantom (an edge-on beam cone, a stair tread),
      // and then it would keep a real surface out of the graph for good.
      if (cos_angle >= cos_near && std::abs(dd) <= sep * config.distance_gate &&
          p.observations >= config.confirmed_observations)
        near_existing[i] = true;
      if (cos_angle < cos_gate) {
        ++result.gate_rejects[static_cast<std::size_t>(cos_angle < 0.0 ? GateReject::kFacing
                                                                       : GateReject::kAngle)];
        continue;
      }
      if (std::abs(dd) > config.distance_gate) {
        ++result.gate_rejects[static_cast<std::size_t>(GateReject::kDistance)];
        continue;
      }
      Candidate c;
      c.prediction = static_cast<int>(j);
      c.r0 << B.transpose() * p.n_kf, dd;
      c.J.setZero();
      c.J.block<2, 3>(0, 0) = B.transpose() * skew(p.n_kf);
      c.J.block<1, 3>(2, 3) = -p.n_kf.transpose();
      const Eigen::Matrix3d S = srps[i].covariance + Eigen::Matrix3d(model_var.asDiagonal());
      c.W = S.inverse();
      // The pose's uncertainty in this pair's residual, J Sigma_delta J^T:
      // diag(s_tilt^2, s_tilt^2, s_t^2) (J's normal rows are orthonormal up to
      // the small angle between n_kf and n_obs) plus the yaw's share along
      // a = d(normal residual)/d(yaw) = B^T [n_kf]x u (zero for a floor).
      const Eigen::Vector2d a = c.J.block<2, 3>(0, 0) * up;
      Eigen::Matrix3d S_gate = S + Eigen::Matrix3d(pose_var.asDiagonal());
      S_gate.topLeftCorner<2, 2>() += (var_yaw - var_tilt) * a * a.transpose();
      c.chi2 = c.r0.dot(S_gate.ldlt().solve(c.r0));
      if (!(c.chi2 <= config.mahalanobis_gate)) {
        ++result.gate_rejects[static_cast<std::size_t>(GateReject::kMahalanobis)];
        continue;
      }
      candidates[i].push_back(c);
    }
    std::sort(candidates[i].begin(), candidates[i].end(),
              [](const Candidate& a, const Candidate& b) { return a.chi2 < b.chi2; });
    if (candidates[i].size() > 3) candidates[i].resize(3);
    result.srps[i].candidates = static_cast<int>(candidates[i].size());
  }

  // 2. Joint hypotheses: each SRP to one of its candidates or to a new plane.
  // The prior on the correction: Sigma_delta^-1 (Sigma_phi^-1 in closed form).
  Matrix6 P = Matrix6::Zero();
  P.topLeftCorner<3, 3>() =
      Eigen::Matrix3d(Eigen::Vector3d::Constant(1.0 / var_tilt).asDiagonal()) +
      (1.0 / var_yaw - 1.0 / var_tilt) * up * up.transpose();
  P.bottomRightCorner<3, 3>() =
      Eigen::Matrix3d(Eigen::Vector3d::Constant(1.0 / var_t).asDiagonal());
  std::vector<Hypothesis> hypotheses;
  Hypothesis h;
  h.choice.assign(srps.size(), -1);
  auto score = [&](Hypothesis& hyp) {
    Matrix6 H = P;
    Vector6 g = Vector6::Zero();
    double cost = 0.0;
    for (std::size_t i = 0; i < srps.size(); ++i) {
      if (hyp.choice[i] < 0) {
        cost += config.mahalanobis_gate;
        continue;
      }
      const Candidate& c = candidates[i][static_cast<std::size_t>(hyp.choice[i])];
      H += c.J.transpose() * c.W * c.J;
      g += c.J.transpose() * c.W * c.r0;
      cost += c.r0.dot(c.W * c.r0);
    }
    cost -= g.dot(H.ldlt().solve(g));  // minimum over the pose correction
    hyp.cost = cost;
  };
  std::function<void(std::size_t)> enumerate = [&](std::size_t i) {
    if (i == srps.size()) {
      score(h);
      hypotheses.push_back(h);
      return;
    }
    for (int k = -1; k < static_cast<int>(candidates[i].size()); ++k) {
      if (k >= 0) {
        const int pred = candidates[i][static_cast<std::size_t>(k)].prediction;
        bool used = false;
        for (std::size_t m = 0; m < i; ++m)
          if (h.choice[m] >= 0 &&
              candidates[m][static_cast<std::size_t>(h.choice[m])].prediction == pred)
            used = true;
        if (used) continue;
      }
      h.choice[i] = k;
      enumerate(i + 1);
    }
  };
  enumerate(0);
  result.hypotheses = static_cast<int>(hypotheses.size());
  const Hypothesis* best = &hypotheses.front();
  for (const Hypothesis& hyp : hypotheses)
    if (hyp.cost < best->cost) best = &hyp;

  // 3. Decisions; a match contradicted by a near-equal hypothesis is ambiguous.
  for (std::size_t i = 0; i < srps.size(); ++i) {
    SrpAssociation& out = result.srps[i];
    const int k = best->choice[i];
    if (k < 0) {
      out.outcome = !candidates[i].empty() || near_existing[i]
                        ? (candidates[i].empty() ? AssociationOutcome::kNearExisting
                                                 : AssociationOutcome::kAmbiguous)
                        : AssociationOutcome::kNewPlane;
      continue;
    }
    const Candidate& c = candidates[i][static_cast<std::size_t>(k)];
    double rival = std::numeric_limits<double>::infinity();
    for (const Hypothesis& hyp : hypotheses) {
      if (hyp.choice[i] < 0 || hyp.choice[i] == k) continue;
      rival = std::min(rival, hyp.cost);
    }
    if (rival - best->cost < config.ambiguity_margin) {
      out.outcome = AssociationOutcome::kAmbiguous;
      continue;
    }
    out.outcome = AssociationOutcome::kMatched;
    out.landmark = predictions[static_cast<std::size_t>(c.prediction)].landmark;
    out.chi2 = c.chi2;
  }
  return result;
}

}  // namespace storey::backend
