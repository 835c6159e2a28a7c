#pragma once
/// Shapes of a building plan shared by the generator's parts (building.cpp,
/// stairs.cpp): rectangles on the plan and openings in walls.
#include <algorithm>
#include <vector>

namespace storey::sim {

/// A rectangle on the plan [x0, x1] x [y0, y1].
struct Rect {
  double x0, y0, x1, y1;
};

/// An opening in a wall, in wall coordinates: u along the wall, z absolute;
/// glazed (a pane the LiDAR sees through) or open.
struct Opening {
  double u0, u1, z0, z1;
  bool glass;
};

/// `outer` minus `hole` as up to four rectangles (hole clipped to outer).
inline std::vector<Rect> rectMinus(const Rect& outer, const Rect& hole) {
  const Rect h{std::max(outer.x0, hole.x0), std::max(outer.y0, hole.y0),
               std::min(outer.x1, hole.x1), std::min(outer.y1, hole.y1)};
  if (h.x0 >= h.x1 || h.y0 >= h.y1) return {outer};
  return {{outer.x0, outer.y0, outer.x1, h.y0},
          {outer.x0, h.y1, outer.x1, outer.y1},
          {outer.x0, h.y0, h.x0, h.y1},
          {h.x1, h.y0, outer.x1, h.y1}};
}

}  // namespace storey::sim
