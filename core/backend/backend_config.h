#pragma once
/// Parameters of the SRP back end (section V of the reference paper,
/// docs/method/backend.md), defaults in the structs, units beside each field.
/// Angles named ..._deg are in degrees (as in the config file) and converted
/// inside the back end; every other angle is in radians.

namespace storey {

/// When a scan becomes a keyframe (a vertex of the graph).
struct KeyframeConfig {
  double distance = 1.0;         ///< travelled since the last keyframe [m, > 0]
  double pitch_roll_deg = 10.0;  ///< pitch or roll change since the last keyframe [deg, > 0]
  double max_interval = 5.0;     ///< also after this long without one (standing still) [s]; 0 = off
};

/// Structural representative planes of a keyframe's deskewed scan.
struct SrpExtractionConfig {
  int min_points = 400;  ///< a plane needs at least this many scan points [>= 3]
  int max_srps = 3;      ///< SRPs kept per keyframe (largest, nearly orthogonal) [1, 3]
  double explained_fraction =
      0.8;                      ///< stop detecting when this share of points is explained [0, 1]
  int max_detected_planes = 8;  ///< planes detected per scan before the SRP choice [>= 1]
  double orthogonal_tolerance_deg =
      15.0;                         ///< SRP normals within this of 90 deg of each other [deg]
  double ransac_distance = 0.05;    ///< inlier distance of RANSAC and of the point count [m, > 0]
  int ransac_iterations = 100;      ///< RANSAC hypotheses per plane [>= 1]
  double voxel_size = 0.2;          ///< RANSAC runs on a voxel subsample of this size [m, > 0]
  int ransac_max_points = 500;      ///< and on at most this many of its points [>= 10]
  double min_range = 0.5;           ///< scan points nearer than this are ignored [m]
  double max_range = 30.0;          ///< scan points farther than this are ignored [m]
  int max_points = 15000;           ///< of the rest, one point in k (scan order) with k the
                                    ///< smallest keeping at most this many, each standing for k
                                    ///< scan points (counts, uncertainty) [>= 0; 0 = all]
  double min_extent = 1.0;          ///< a plane's inliers span at least this (2nd axis, 4 std) [m]
  double min_view_angle_deg = 1.0;  ///< median angle between the beams and the plane at least
                                    ///< this, and the plane at least 3 ransac_distance from the
                                    ///< sensor: else it is the sensor's own beam cone on the
                                    ///< walls around it, not a surface [deg, [0, 45); 0 = off]
  double point_sigma = 0.02;        ///< range noise assumed in the plane uncertainty [m, > 0]
  int max_effective_points = 100;   ///< points counted as independent in the uncertainty
                                    ///< (errors of a scan are correlated) [>= 3]
};

/// Matching the SRPs of a keyframe with the global plane map.
struct AssociationConfig {
  double angle_gate_deg = 6.0;  ///< largest normal angle of a match [deg, > 0]
  double distance_gate = 0.2;   ///< largest |d| difference of a match [m, > 0]
  double mahalanobis_gate =
      16.27;  ///< chi-square (3 dof) gate with the uncertainties (99.9 %) [> 0]
  double pose_sigma_rotation =
      0.02;  ///< uncertainty of the predicted keyframe rotation (its
             ///< yaw; all of it when pose_sigma_tilt is not smaller) [rad, > 0]
  /// ... of its roll and pitch (the odometry is gravity-aligned: its tilt is
  /// known far better than its yaw), so a floor cannot match a surface a few
  /// degrees off level (a 1:12 ramp, a band across two levels) [rad, > 0]
  double pose_sigma_tilt = 0.02;
  double pose_sigma_translation = 0.05;  ///< same for its translation [m, > 0]
  double plane_sigma_rotation = 0.005;   ///< landmark and model uncertainty of a normal [rad, > 0]
  double plane_sigma_distance = 0.02;    ///< same for a distance [m, > 0]
  double ambiguity_margin = 4.0;  ///< joint hypotheses closer than this in cost are ambiguous [> 0]
  double new_plane_separation = 2.0;  ///< no new plane within this many gates of a known one [>= 1]
  int confirmed_observations =
      2;  ///< ... if that one was seen by at least this many keyframes [>= 1]
  /// An SRP whose fit RMS exceeds this many times the median fit RMS of the
  /// run's SRPs so far (after 20) is a rough fit (several surfaces, e.g. treads
  /// near the sensor) and not used: neither matched nor a new plane [> 1; 0 = off]
  /// (docs/method/backend.md, "Rough fits are not used")
  double max_rms_ratio = 0.0;
  /// A landmark seen within this much path of the keyframe (odometry, metres
  /// walked) is tracked: its newest view, moved into the keyframe by the
  /// odometry (exact to millimetres over a few metres, unlike the graph's
  /// prediction), must agree with the SRP within track_gate, or the SRP is
  /// another surface (a parallel face a few centimetres off) and not matched
  /// to it; then it may become a new plane next to it [m, >= 0; 0 = off;
  /// worse on the development seeds at 5 m: docs/benchmarks.md, session 29]
  double track_distance = 0.0;
  double track_gate = 0.04;  ///< [m, > 0] (docs/method/backend.md, "Tracked landmarks")
};

/// The keyframe factor graph.
struct GraphConfig {
  double odometry_sigma_translation = 0.0015;  ///< relative-pose std per keyframe edge [m, > 0]
  double odometry_sigma_translation_per_m = 0.0015;  ///< added per metre travelled [m/m, >= 0]
  double odometry_sigma_rotation = 0.0003;  ///< relative-pose rotation std per edge [rad, > 0]
  double odometry_sigma_rotation_per_m = 0.0003;  ///< added per metre travelled [rad/m, >= 0]
  /// Added per radian turned and per metre climbed (backend/odometry_information.h).
  double odometry_sigma_translation_per_rad = 0.004;        ///< [m/rad, >= 0]
  double odometry_sigma_translation_per_m_climbed = 0.012;  ///< [m/m, >= 0]
  double odometry_sigma_rotation_per_rad = 0.0003;          ///< [rad/rad, >= 0]
  double odometry_sigma_rotation_per_m_climbed = 0.001;     ///< [rad/m, >= 0]
  /// Height spans: each keyframe also gets the odometry's height difference
  /// to the keyframe this many keyframes before it, with a standard deviation
  /// that does not grow with the span (height_span_sigma): the odometry's
  /// height error is bounded by its map and gravity, not a random walk over
  /// its edges [>= 0; 0 = off]
  int height_span_keyframes = 0;
  double height_span_sigma = 0.01;  ///< [m, > 0]
  /// The span's height from the odometry's translation in keyframe a's frame,
  /// turned by the graph's attitude of a (KeyframeHeightDifferenceCost), not
  /// from the odometry's map frame levelled once for the log
  bool height_span_keyframe_frame = false;
  double plane_sigma_rotation =
      0.002;  ///< added to a plane observation's normal std (model error) [rad]
  double plane_sigma_distance = 0.01;  ///< added to its distance std [m]
  double plane_loss_width = 3.0;       ///< Cauchy loss scale on the whitened plane residual [> 0]
  double level_prior_sigma = 0.004;  ///< floors level and walls plumb in the gravity-aligned world:
                                     ///< prior std on their normals [rad]; 0 = off
  double level_tolerance_deg = 5.0;  ///< planes this close to level or plumb get the prior [deg]
  double first_tilt_sigma = 0.01;    ///< roll/pitch std of the first keyframe (IMU initialisation)
                                     ///< [rad]; its position and yaw are held (gauge); 0 = all held
  double tilt_prior_sigma = 0.0;     ///< every keyframe's roll/pitch held to the odometry's
                                     ///< gravity-levelled attitude with this std [rad]; 0 = off
  /// The odometry edges' translation in each keyframe's heading frame
  /// (turned by its yaw only; the odometry's displacement levelled) instead
  /// of its body frame, so a keyframe the graph tilts does not turn the
  /// odometry's horizontal displacements into height (needs the odometry's
  /// attitudes: setTiltReference)
  bool heading_frame_edges = false;
  int max_iterations = 6;     ///< Levenberg-Marquardt iterations per keyframe [>= 1]
  int window_keyframes = 20;  ///< newest keyframes optimised at each keyframe (older ones
                              ///< held fixed); 0 = always the whole graph [>= 0]
  /// Per plane free in a windowed solve, its observations by keyframes older
  /// than the window (held fixed) kept in the solve: the newest n [>= 0; 0 = all].
  int window_held_observations = 100;
  int full_every = 25;             ///< the whole graph every n optimisations [>= 1]
  double full_every_share = 0.04;  ///< ...or after the graph grew by this share of its
                                   ///< keyframes, whichever is later (bounded whole-graph
                                   ///< work per keyframe, solve_schedule.h) [0, 1]; 0 = off
  int final_iterations = 50;       ///< iterations of the whole-graph solve at the end [>= 0]
  double outlier_chi2 = 16.27;     ///< observations with a larger whitened residual after the
                                   ///< end's whole-graph solve are wrong associations: left out,
                                   ///< the graph solved again, and reported [> 0]
  /// Views of a floor or ceiling (a landmark within level_tolerance_deg of
  /// level) whose normal, turned by its keyframe's solved attitude, is
  /// farther than this from vertical leave the end's whole-graph solve:
  /// mixed fits (backend/level_view.h) [deg, [0, 45)]; 0 = off. 0.43 deg
  /// (7.5 mrad) is about 3 sigma of a view's modelled normal uncertainty.
  double level_view_max_tilt_deg = 0.43;
};

/// The back end (SRP constraints, keyframe graph).
struct BackendConfig {
  bool srp = true;  ///< SRP back end on; off (`--no-srp`): trajectory = odometry
  /// Scans queued between the odometry and the back end, which then runs on
  /// a thread of its own (with the map scan selection); 0: on the odometry's
  /// thread. The results are the same bytes either way [0, 64].
  int queue_scans = 4;
  KeyframeConfig keyframes;
  SrpExtractionConfig extraction;
  AssociationConfig association;
  GraphConfig graph;

  /// Checks value ranges; throws storey::Error naming the key (under `backend.`) at fault.
  void validate() const;
};

}  // namespace storey
