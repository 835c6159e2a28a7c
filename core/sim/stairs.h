#pragma once
/// The stairs of a simulated building, north of its corridor, in the
/// building's frame (x along the corridor [0, length], y north with the
/// corridor in [-yc, yc], z up): where they are, what they are made of, and
/// how the walk goes up and down them. Two kinds (StairKind):
/// - switchback: an enclosed stairwell, per storey flight 1 (east half) up
///   towards +y to a half landing, flight 2 (west half) back to the next
///   floor's landing at the corridor;
/// - straight: one flight per storey along the corridor, behind a glazed
///   corridor wall, in two lanes side by side (lane A next to the corridor
///   climbs east on even storeys, lane B behind it climbs west on odd ones),
///   with floor landings at both ends open to the corridor;
/// - l_shaped: round an open well, per storey flight 1 (east column) up
///   towards +y to a quarter landing in the north-east corner, flight 2 west
///   along the back wall to the next floor, and a walkway down the west
///   column back to the corridor.
#include <string>
#include <vector>

#include "sim/building.h"
#include "sim/building_spec.h"
#include "sim/mesh.h"
#include "sim/plan_shapes.h"

namespace storey::sim {

class Stairs {
 public:
  /// Lays the stairs out between the storeys of `storey_heights` (floor to
  /// floor, bottom up; the ground floor's top at z = 0) north of a corridor
  /// `length` long and 2 yc wide with walls `wall_thickness` thick. Throws
  /// storey::Error naming `source` when they do not fit the corridor.
  Stairs(const StairwellSpec& spec, const std::vector<double>& storey_heights, double length,
         double yc, double wall_thickness, const std::string& source);

  double x0() const { return x0_; }         ///< the west wall of the stairs (centreline)
  double x1() const { return x1_; }         ///< the east wall (centreline)
  double yBack() const { return y_back_; }  ///< the back wall (centreline)

  /// Where the walk leaves the corridor to climb from floor k, and where it
  /// comes back onto the corridor on floor k+1 [x].
  double entryX(int k) const;
  double exitX(int k) const;
  /// The westmost of all entries and exits [x].
  double westmostX() const;

  /// The openings of the corridor's north wall onto the stairs, on a storey
  /// with its floor at zf and its ceiling (slab underside) at `ceiling`.
  std::vector<Opening> corridorOpenings(double zf, double ceiling) const;
  /// The openings of floor j's slab (none in the ground floor and the roof).
  std::vector<Rect> slabHoles(int j) const;
  /// Steps, landings and partition walls between floor k and floor k+1.
  void addFlights(int k, TriangleMesh& mesh) const;

  /// The route (body centre `body_height` above the floor or stair line) up
  /// from floor k: from beside the corridor point (entryX(k), lane) to the
  /// point on floor k+1 from which the walk goes south onto the corridor at
  /// exitX(k). `walk` and `climb` are the speeds on floors and stairs.
  std::vector<RouteVertex> climb(int k, double body_height, double walk, double climb) const;
  /// Down to floor k from floor k+1: from beside (exitX(k), lane) on floor
  /// k+1 (or where descend(k + 1, ..., true) ended) to beside (entryX(k),
  /// lane) on floor k; `more` adds the way to the start of descend(k - 1).
  std::vector<RouteVertex> descend(int k, double body_height, double walk, double climb,
                                   bool more) const;

 private:
  /// Per flight k, the numbers the mesh and the route share.
  struct Flight {
    int risers = 0;           ///< total risers of the storey
    int risers_first = 0;     ///< switchback: in flight 1 (up to the half landing)
    double riser = 0.0;       ///< actual riser [m]
    double run = 0.0;         ///< straight: horizontal run of the storey's flight [m]
    double run_first = 0.0;   ///< switchback: of flight 1 [m]
    double run_second = 0.0;  ///< switchback: of flight 2 [m]
    double landing_z = 0.0;   ///< switchback: half landing above the storey floor [m]
  };
  bool straight() const { return spec_.kind == StairKind::kStraight; }
  bool lShaped() const { return spec_.kind == StairKind::kLShaped; }
  void addLShaped(int k, TriangleMesh& mesh) const;
  void addSwitchback(int k, TriangleMesh& mesh) const;
  void addStraight(int k, TriangleMesh& mesh) const;

  StairwellSpec spec_;
  std::vector<double> z_;  ///< floor tops, roof last
  double yc_ = 0.0, wt_ = 0.0;
  std::vector<Flight> flights_;
  double x0_ = 0.0, x1_ = 0.0, y_back_ = 0.0;
  double xs_ = 0.0;  ///< centre along x
  // Switchback.
  double y_flights_ = 0.0;                        ///< the flights' foot (floor landing's back edge)
  double x_east_lane_ = 0.0, x_west_lane_ = 0.0;  ///< the walk on flight 1 and flight 2
  // Straight.
  double x_west_foot_ = 0.0, x_east_foot_ = 0.0;  ///< the flights' ends (landings' inner edges)
  double x_west_land_ = 0.0, x_east_land_ = 0.0;  ///< the walk across the landings
  double ya0_ = 0.0, ya1_ = 0.0, yb0_ = 0.0, yb1_ = 0.0;  ///< lanes A and B
  // L-shaped (and y_flights_).
  double walk_x0_ = 0.0, walk_x1_ = 0.0;  ///< the walkway column
  double col_x0_ = 0.0, col_x1_ = 0.0;    ///< flight 1's column; flight 2 starts at col_x0_
  double y_row0_ = 0.0, y_row1_ = 0.0;    ///< flight 2's row along the back wall
};

}  // namespace storey::sim
