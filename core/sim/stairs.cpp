#include "sim/stairs.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace storey::sim {
namespace {

using Eigen::Vector3d;

constexpr double kPartitionThickness = 0.1;  ///< wall between the two flights or lanes [m]
constexpr double kLandingThickness = 0.2;    ///< half-landing slab [m]
constexpr double kStepUnderside = 0.12;      ///< concrete below each step [m]

}  // namespace

Stairs::Stairs(const StairwellSpec& spec, const std::vector<double>& storey_heights, double length,
               double yc, double wall_thickness, const std::string& source)
    : spec_(spec), z_(1, 0.0), yc_(yc), wt_(wall_thickness) {
  for (double h : storey_heights) z_.push_back(z_.back() + h);
  double run_max = 0.0, run_second_max = 0.0;
  for (std::size_t k = 0; k + 2 < z_.size(); ++k) {
    Flight f;
    const double h = storey_heights[k];
    f.risers = std::max(4, static_cast<int>(std::lround(h / spec_.riser)));
    f.riser = h / f.risers;
    f.run = (f.risers - 1) * spec_.tread;
    f.risers_first = (f.risers + 1) / 2;
    f.run_first = (f.risers_first - 1) * spec_.tread;
    f.run_second = (f.risers - f.risers_first - 1) * spec_.tread;
    f.landing_z = f.risers_first * f.riser;
    run_max = std::max(run_max, straight() ? f.run : f.run_first);
    run_second_max = std::max(run_second_max, f.run_second);
    flights_.push_back(f);
  }
  // Half the stairs' extent along the corridor: the flights and landings
  // (straight); the walkway, flight 2 and the quarter landing (L-shaped).
  const double lane = (spec_.width - kPartitionThickness) / 2;
  double half = spec_.width / 2;
  if (straight()) half = run_max / 2 + spec_.floor_landing_depth;
  if (lShaped()) half = (2 * lane + run_second_max + wt_) / 2;
  if (length < 2 * half + 3.7)
    throw Error(source + ": key 'building.corridor_length' is too short for the stairwell");
  xs_ = std::clamp(spec_.position * length, half + 2.5, length - half - 1.2);
  x0_ = xs_ - half;
  x1_ = xs_ + half;
  if (straight()) {
    ya0_ = yc_ + wt_ / 2;
    ya1_ = ya0_ + lane;
    yb0_ = ya1_ + kPartitionThickness;
    yb1_ = yb0_ + lane;
    y_back_ = yb1_ + wt_ / 2;
    x_west_foot_ = xs_ - run_max / 2;
    x_east_foot_ = xs_ + run_max / 2;
    x_west_land_ = (x0_ + wt_ / 2 + x_west_foot_) / 2;
    x_east_land_ = (x_east_foot_ + x1_ - wt_ / 2) / 2;
  } else if (lShaped()) {
    y_flights_ = yc_ + spec_.floor_landing_depth;
    y_row0_ = y_flights_ + run_max;
    y_row1_ = y_row0_ + lane;
    y_back_ = y_row1_ + wt_ / 2;
    walk_x0_ = x0_ + wt_ / 2;
    walk_x1_ = walk_x0_ + lane;
    col_x1_ = x1_ - wt_ / 2;
    col_x0_ = col_x1_ - lane;
  } else {
    y_flights_ = yc_ + spec_.floor_landing_depth;
    y_back_ = y_flights_ + run_max + spec_.half_landing_depth;
    x_east_lane_ = xs_ + (kPartitionThickness / 2 + half - wt_ / 2) / 2;
    x_west_lane_ = xs_ - (kPartitionThickness / 2 + half - wt_ / 2) / 2;
  }
}

double Stairs::entryX(int k) const {
  if (lShaped()) return (col_x0_ + col_x1_) / 2;
  if (!straight()) return x_east_lane_;
  return k % 2 == 0 ? x_west_land_ : x_east_land_;
}

double Stairs::exitX(int k) const {
  if (lShaped()) return (walk_x0_ + walk_x1_) / 2;
  if (!straight()) return x_west_lane_;
  return k % 2 == 0 ? x_east_land_ : x_west_land_;
}

double Stairs::westmostX() const {
  if (lShaped()) return exitX(0);
  return straight() ? x_west_land_ : x_west_lane_;
}

std::vector<Opening> Stairs::corridorOpenings(double zf, double ceiling) const {
  if (!straight()) return {{x0_ + wt_ / 2, x1_ - wt_ / 2, zf, zf + 2.3, false}};
  // Open at the landings; glazed along the flights.
  return {{x0_ + wt_ / 2, x_west_foot_, zf, zf + 2.3, false},
          {x_west_foot_, x_east_foot_, zf + 0.05, std::min(zf + 2.5, ceiling - 0.15), true},
          {x_east_foot_, x1_ - wt_ / 2, zf, zf + 2.3, false}};
}

std::vector<Rect> Stairs::slabHoles(int j) const {
  if (j <= 0 || j >= static_cast<int>(z_.size()) - 1) return {};
  if (lShaped()) {
    // Over flight 1's column and the well, and over flight 2 up to its head
    // (the floor reaches it there, and the walkway is floor).
    const double head = col_x0_ - flights_[j - 1].run_second;
    return {{walk_x1_, y_flights_, col_x1_, y_row0_}, {head, y_row0_, col_x1_, y_row1_}};
  }
  if (!straight()) return {{x0_ + wt_ / 2, y_flights_, x1_ - wt_ / 2, y_back_ - wt_ / 2}};
  // Over the flight that comes up through this floor.
  const Flight& f = flights_[j - 1];
  if ((j - 1) % 2 == 0) return {{x_west_foot_, ya0_, x_west_foot_ + f.run, ya1_}};
  return {{x_east_foot_ - f.run, yb0_, x_east_foot_, yb1_}};
}

void Stairs::addFlights(int k, TriangleMesh& mesh) const {
  if (straight())
    addStraight(k, mesh);
  else if (lShaped())
    addLShaped(k, mesh);
  else
    addSwitchback(k, mesh);
}

void Stairs::addSwitchback(int k, TriangleMesh& mesh) const {
  const Flight& st = flights_[k];
  const double zf = z_[k], tread = spec_.tread, half = spec_.width / 2;
  const double ex0 = xs_ + kPartitionThickness / 2, ex1 = xs_ + half - wt_ / 2;  // east flight
  const double wx0 = xs_ - half + wt_ / 2, wx1 = xs_ - kPartitionThickness / 2;  // west flight
  const double landing_back = y_back_ - wt_ / 2;
  const double r = st.riser;
  // Flight 1: east half, up towards +y.
  for (int i = 1; i < st.risers_first; ++i) {
    const double top = zf + i * r;
    mesh.addBox(Vector3d(ex0, y_flights_ + (i - 1) * tread, top - r - kStepUnderside),
                Vector3d(ex1, y_flights_ + i * tread, top), Surface::kStairs);
  }
  const double zl = zf + st.landing_z;
  mesh.addBox(Vector3d(ex0, y_flights_ + st.run_first, zl - kLandingThickness),
              Vector3d(ex1, landing_back, zl), Surface::kStairs);
  mesh.addBox(Vector3d(wx0, y_flights_ + st.run_second, zl - kLandingThickness),
              Vector3d(wx1, landing_back, zl), Surface::kStairs);
  // Partition between the landing and the flights' shared wall line (the gap).
  mesh.addBox(
      Vector3d(wx1, y_flights_ + std::min(st.run_first, st.run_second), zl - kLandingThickness),
      Vector3d(ex0, landing_back, zl), Surface::kStairs);
  // Flight 2: west half, up towards -y, from the half landing to the next floor.
  const int second = st.risers - st.risers_first;
  for (int j = 1; j < second; ++j) {
    const double top = zl + j * r;
    mesh.addBox(Vector3d(wx0, y_flights_ + st.run_second - j * tread, top - r - kStepUnderside),
                Vector3d(wx1, y_flights_ + st.run_second - (j - 1) * tread, top), Surface::kStairs);
  }
  // Wall between the flights, through the whole storey.
  mesh.addBox(Vector3d(xs_ - kPartitionThickness / 2, y_flights_, zf),
              Vector3d(xs_ + kPartitionThickness / 2,
                       y_flights_ + std::min(st.run_first, st.run_second), z_[k + 1]),
              Surface::kWall);
}

void Stairs::addStraight(int k, TriangleMesh& mesh) const {
  const Flight& f = flights_[k];
  const double zf = z_[k], tread = spec_.tread, r = f.riser;
  for (int i = 1; i < f.risers; ++i) {
    const double top = zf + i * r;
    if (k % 2 == 0)  // lane A, up towards +x
      mesh.addBox(Vector3d(x_west_foot_ + (i - 1) * tread, ya0_, top - r - kStepUnderside),
                  Vector3d(x_west_foot_ + i * tread, ya1_, top), Surface::kStairs);
    else  // lane B, up towards -x
      mesh.addBox(Vector3d(x_east_foot_ - i * tread, yb0_, top - r - kStepUnderside),
                  Vector3d(x_east_foot_ - (i - 1) * tread, yb1_, top), Surface::kStairs);
  }
  // Wall between the lanes, through the whole storey.
  mesh.addBox(Vector3d(x_west_foot_, ya1_, zf), Vector3d(x_east_foot_, yb0_, z_[k + 1]),
              Surface::kWall);
}

void Stairs::addLShaped(int k, TriangleMesh& mesh) const {
  const Flight& f = flights_[k];
  const double zf = z_[k], tread = spec_.tread, r = f.riser;
  // Flight 1: up the east column towards +y.
  for (int i = 1; i < f.risers_first; ++i) {
    const double top = zf + i * r;
    mesh.addBox(Vector3d(col_x0_, y_flights_ + (i - 1) * tread, top - r - kStepUnderside),
                Vector3d(col_x1_, y_flights_ + i * tread, top), Surface::kStairs);
  }
  // The quarter landing in the north-east corner.
  const double zl = zf + f.landing_z;
  mesh.addBox(Vector3d(col_x0_, y_flights_ + f.run_first, zl - kLandingThickness),
              Vector3d(col_x1_, y_row1_, zl), Surface::kStairs);
  // Flight 2: west along the back wall, to the next floor.
  for (int j = 1; j < f.risers - f.risers_first; ++j) {
    const double top = zl + j * r;
    mesh.addBox(Vector3d(col_x0_ - j * tread, y_row0_, top - r - kStepUnderside),
                Vector3d(col_x0_ - (j - 1) * tread, y_row1_, top), Surface::kStairs);
  }
}

std::vector<RouteVertex> Stairs::climb(int k, double body_height, double walk, double climb) const {
  const Flight& f = flights_[k];
  const double zf = z_[k] + body_height, zn = z_[k + 1] + body_height;
  if (lShaped()) {
    const double zl = zf + f.landing_z, y_row = (y_row0_ + y_row1_) / 2;
    const double x_col = entryX(k), x_walk = exitX(k);
    return {{Vector3d(x_col, y_flights_, zf), climb},
            {Vector3d(x_col, y_flights_ + f.run_first, zl), walk},
            {Vector3d(x_col, y_row, zl), walk},
            {Vector3d(col_x0_, y_row, zl), climb},
            {Vector3d(col_x0_ - f.run_second, y_row, zn), walk},
            {Vector3d(x_walk, y_row, zn), walk}};
  }
  if (straight()) {
    const bool even = k % 2 == 0;
    const double y = even ? (ya0_ + ya1_) / 2 : (yb0_ + yb1_) / 2;
    const double foot = even ? x_west_foot_ : x_east_foot_;
    const double head = even ? x_west_foot_ + f.run : x_east_foot_ - f.run;
    return {{Vector3d(entryX(k), y, zf), walk},
            {Vector3d(foot, y, zf), climb},
            {Vector3d(head, y, zn), walk},
            {Vector3d(exitX(k), y, zn), walk}};
  }
  const double zl = zf + f.landing_z;
  const double y_landing = (y_flights_ + f.run_first + y_back_ - wt_ / 2) / 2;
  return {{Vector3d(x_east_lane_, y_flights_, zf), climb},
          {Vector3d(x_east_lane_, y_flights_ + f.run_first, zl), walk},
          {Vector3d(x_east_lane_, y_landing, zl), walk},
          {Vector3d(x_west_lane_, y_landing, zl), walk},
          {Vector3d(x_west_lane_, y_flights_ + f.run_second, zl), climb},
          {Vector3d(x_west_lane_, y_flights_, zn), walk}};
}

std::vector<RouteVertex> Stairs::descend(int k, double body_height, double walk, double climb,
                                         bool more) const {
  // The climb walked backwards: each segment keeps its speed (a vertex's
  // speed is that of the segment starting at it).
  const std::vector<RouteVertex> up = this->climb(k, body_height, walk, climb);
  std::vector<RouteVertex> route;
  for (std::size_t i = up.size(); i-- > 0;)
    route.push_back({up[i].p, i > 0 ? up[i - 1].speed : walk});
  if (more && !straight()) {
    // Across the floor landing to where the next flight down starts (a
    // straight flight's starts at the same end, in the other lane).
    const double y_turn = yc_ + spec_.floor_landing_depth / 2;
    const double z = route.back().p.z();
    route.push_back({Vector3d(entryX(k), y_turn, z), walk});
    route.push_back({Vector3d(exitX(k - 1), y_turn, z), walk});
  }
  return route;
}

}  // namespace storey::sim
