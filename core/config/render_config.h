#pragma once
/// Parameters of the off-screen renders (render/, docs/renders.md), the one
/// face whose settings live in the configuration file.

namespace storey {

/// Off-screen PNG renders of a run's output (render/, docs/renders.md).
struct RenderViews {
  bool elevation = true;     ///< elevation_front.png, elevation_side.png: whole building by storey
  bool storeys = true;       ///< storey_NN_top.png: each storey from above, coloured by height
  bool srp = true;           ///< srp_map.png: global SRPs as patches over the grey map, per storey
  bool keyframe = true;      ///< srp_keyframe_NNNN.png: one keyframe's SRPs
  bool trajectories = true;  ///< trajectories_front/top.png: estimate vs ground truth (needs --gt)
};

struct RenderConfig {
  bool enabled = true;  ///< `storey run` renders at the end (`--no-render` clears it)
  int width = 1600;     ///< image width [px], [320, 8192]
  int height = 1000;    ///< image height [px], [240, 8192]
  RenderViews views;
  int max_display_points = 2000000;  ///< map points drawn at most (uniform subsample) [>= 1000]
  double point_size = 2.0;           ///< map point size [px], (0, 20]
  double line_width = 3.0;           ///< trajectory line width [px], (0, 20]
  int keyframe = -1;  ///< keyframe of the SRP keyframe view; -1 = the one with most SRPs
  double keyframe_radius = 15.0;  ///< map shown around that keyframe (xy) [m, > 0]
  double srp_point_distance =
      0.05;                   ///< map points this close to an SRP patch get its colour [m, > 0]
  double ceiling_cut = 0.15;  ///< storey views leave out points above ceiling - this [m, >= 0]

  /// Checks value ranges; throws storey::Error naming the key (under `render.`) at fault.
  void validate() const;
};

}  // namespace storey
