#include "config/render_config.h"

#include <string>

#include "common/error.h"

namespace storey {

void RenderConfig::validate() const {
  const RenderConfig& r = *this;
  requireKey(r.width >= 320 && r.width <= 8192, "render.width", "must be within [320, 8192] px");
  requireKey(r.height >= 240 && r.height <= 8192, "render.height", "must be within [240, 8192] px");
  requireKey(r.max_display_points >= 1000, "render.max_display_points", "must be >= 1000");
  requireKey(r.point_size > 0.0 && r.point_size <= 20.0, "render.point_size",
             "must be within (0, 20] px");
  requireKey(r.line_width > 0.0 && r.line_width <= 20.0, "render.line_width",
             "must be within (0, 20] px");
  requireKey(r.keyframe >= -1, "render.keyframe", "must be a keyframe index or -1 (automatic)");
  requireKey(r.keyframe_radius > 0.0, "render.keyframe_radius", "must be positive");
  requireKey(r.srp_point_distance > 0.0, "render.srp_point_distance", "must be positive");
  requireKey(r.ceiling_cut >= 0.0, "render.ceiling_cut", "must be >= 0");
}

}  // namespace storey
