#include "backend/backend_config.h"

#include <string>

#include "common/error.h"

namespace storey {

void BackendConfig::validate() const {
  const BackendConfig& c = *this;
  auto require = [](bool ok, const char* key, const char* what) {
    if (!ok) throw Error(std::string("backend.") + key + ": " + what);
  };
  require(c.queue_scans >= 0 && c.queue_scans <= 64, "queue_scans", "must be in [0, 64]");
  require(c.keyframes.distance > 0, "keyframes.distance", "must be positive");
  require(c.keyframes.pitch_roll_deg > 0, "keyframes.pitch_roll_deg", "must be positive");
  require(c.keyframes.max_interval >= 0, "keyframes.max_interval", "must be >= 0");
  require(c.graph.first_tilt_sigma >= 0, "graph.first_tilt_sigma", "must be >= 0");
  require(c.graph.tilt_prior_sigma >= 0, "graph.tilt_prior_sigma", "must be >= 0");
  const SrpExtractionConfig& e = c.extraction;
  require(e.min_points >= 3, "extraction.min_points", "must be >= 3");
  require(e.max_srps >= 1 && e.max_srps <= 3, "extraction.max_srps", "must be within [1, 3]");
  require(e.explained_fraction >= 0 && e.explained_fraction <= 1, "extraction.explained_fraction",
          "must be within [0, 1]");
  require(e.max_detected_planes >= 1, "extraction.max_detected_planes", "must be >= 1");
  require(e.orthogonal_tolerance_deg > 0 && e.orthogonal_tolerance_deg < 45,
          "extraction.orthogonal_tolerance_deg", "must be within (0, 45)");
  require(e.ransac_distance > 0, "extraction.ransac_distance", "must be positive");
  require(e.ransac_iterations >= 1, "extraction.ransac_iterations", "must be >= 1");
  require(e.voxel_size > 0, "extraction.voxel_size", "must be positive");
  require(e.ransac_max_points >= 10, "extraction.ransac_max_points", "must be >= 10");
  require(e.max_range > e.min_range, "extraction.max_range", "must exceed extraction.min_range");
  require(e.max_points >= 0, "extraction.max_points", "must be >= 0 (0: every point)");
  require(e.min_view_angle_deg >= 0 && e.min_view_angle_deg < 45, "extraction.min_view_angle_deg",
          "must be within [0, 45)");
  require(e.point_sigma > 0, "extraction.point_sigma", "must be positive");
  require(e.max_effective_points >= 3, "extraction.max_effective_points", "must be >= 3");
  const AssociationConfig& a = c.association;
  require(a.angle_gate_deg > 0 && a.angle_gate_deg < 45, "association.angle_gate_deg",
          "must be within (0, 45)");
  require(a.distance_gate > 0, "association.distance_gate", "must be positive");
  require(a.mahalanobis_gate > 0, "association.mahalanobis_gate", "must be positive");
  require(a.pose_sigma_rotation > 0, "association.pose_sigma_rotation", "must be positive");
  require(a.pose_sigma_tilt > 0, "association.pose_sigma_tilt", "must be positive");
  require(a.pose_sigma_translation > 0, "association.pose_sigma_translation", "must be positive");
  require(a.plane_sigma_rotation > 0, "association.plane_sigma_rotation", "must be positive");
  require(a.plane_sigma_distance > 0, "association.plane_sigma_distance", "must be positive");
  require(a.ambiguity_margin >= 0, "association.ambiguity_margin", "must be >= 0");
  require(a.new_plane_separation >= 1, "association.new_plane_separation", "must be >= 1");
  require(a.confirmed_observations >= 1, "association.confirmed_observations", "must be >= 1");
  require(a.max_rms_ratio == 0 || a.max_rms_ratio > 1, "association.max_rms_ratio",
          "must be 0 (off) or above 1");
  require(a.track_distance >= 0, "association.track_distance", "must be >= 0");
  require(a.track_gate > 0, "association.track_gate", "must be positive");
  const GraphConfig& g = c.graph;
  require(g.odometry_sigma_translation > 0, "graph.odometry_sigma_translation", "must be positive");
  require(g.odometry_sigma_translation_per_m >= 0, "graph.odometry_sigma_translation_per_m",
          "must be >= 0");
  require(g.odometry_sigma_rotation > 0, "graph.odometry_sigma_rotation", "must be positive");
  require(g.odometry_sigma_rotation_per_m >= 0, "graph.odometry_sigma_rotation_per_m",
          "must be >= 0");
  require(g.odometry_sigma_translation_per_rad >= 0, "graph.odometry_sigma_translation_per_rad",
          "must be >= 0");
  require(g.odometry_sigma_translation_per_m_climbed >= 0,
          "graph.odometry_sigma_translation_per_m_climbed", "must be >= 0");
  require(g.odometry_sigma_rotation_per_rad >= 0, "graph.odometry_sigma_rotation_per_rad",
          "must be >= 0");
  require(g.odometry_sigma_rotation_per_m_climbed >= 0,
          "graph.odometry_sigma_rotation_per_m_climbed", "must be >= 0");
  require(g.plane_loss_width > 0, "graph.plane_loss_width", "must be positive");
  require(g.height_span_keyframes >= 0, "graph.height_span_keyframes", "must be >= 0 (0: off)");
  require(g.height_span_sigma > 0, "graph.height_span_sigma", "must be positive");
  require(g.plane_sigma_rotation >= 0, "graph.plane_sigma_rotation", "must be >= 0");
  require(g.plane_sigma_distance >= 0, "graph.plane_sigma_distance", "must be >= 0");
  require(g.level_prior_sigma >= 0, "graph.level_prior_sigma", "must be >= 0");
  require(g.level_tolerance_deg >= 0 && g.level_tolerance_deg < 45, "graph.level_tolerance_deg",
          "must be within [0, 45)");
  require(g.max_iterations >= 1, "graph.max_iterations", "must be >= 1");
  require(g.window_keyframes >= 0, "graph.window_keyframes", "must be >= 0");
  require(g.window_held_observations >= 0, "graph.window_held_observations", "must be >= 0");
  require(g.full_every >= 1, "graph.full_every", "must be >= 1");
  require(g.full_every_share >= 0 && g.full_every_share <= 1, "graph.full_every_share",
          "must be in [0, 1]");
  require(g.final_iterations >= 0, "graph.final_iterations", "must be >= 0");
  require(g.outlier_chi2 > 0, "graph.outlier_chi2", "must be positive");
  require(g.level_view_max_tilt_deg >= 0 && g.level_view_max_tilt_deg < 45,
          "graph.level_view_max_tilt_deg", "must be within [0, 45)");
}

}  // namespace storey
