#include "sim/building.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "common/error.h"
#include "sim/random.h"
#include "sim/stairs.h"

namespace storey::sim {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr double kEndClearance = 1.0;     ///< U-turn apex to the corridor end wall [m]
constexpr double kGlassThickness = 0.02;  ///< [m]
constexpr double kRampRun = 12.0;         ///< horizontal metres per metre of rise (1:12) [1]

/// What a Generator builds: the whole building, or one of its arms (a
/// corridor with rooms, no stairs, open at its west end, no route) in the
/// arm's own frame.
enum class Part { kBuilding, kArm };

/// An arm's place along the main corridor.
struct ArmLayout {
  double x = 0.0;       ///< its axis [m]
  double half = 0.0;    ///< half its width, rooms included (to the outer walls' centrelines) [m]
  double length = 0.0;  ///< from the main corridor's south wall line [m]
  double rise = 0.0;    ///< its floors above the main building's, up a ramp [m]
};

class Generator {
 public:
  /// `rise`: an arm's floors above the main building's (a ramp at its start).
  explicit Generator(const BuildingSpec& spec, Part part = Part::kBuilding,
                     std::uint64_t stream = 0x5eed0001ULL, double rise = 0.0)
      : spec_(spec),
        b_(spec.building),
        part_(part),
        rise_(rise),
        rng_(spec.seed, stream),
        route_rng_(spec.seed, 0x726f7574ULL) {}  // "rout"

  Building run() {
    layout();
    for (int k = 0; k <= storeyCount(); ++k) addSlab(k);
    for (int k = 0; k < storeyCount(); ++k) {
      storey_ = k;
      addStoreyWalls(k);
      addCorridorClutter(k);
      addRoomFurniture(k);
      if (hasStairs() && k + 1 < storeyCount()) stairs_->addFlights(k, out_.mesh);
      out_.storeys.push_back({k, z_[k], z_[k + 1] - b_.slab_thickness});
    }
    if (part_ == Part::kBuilding) {
      addArms();
      addRoute();
      repeatRoute(spec_.robot.rounds);
    }
    return std::move(out_);
  }

 private:
  struct Room {
    double x0, x1;        ///< partition wall centrelines
    double door0, door1;  ///< door opening along x
    bool glass_front;
    bool atrium = false;  ///< part of the atrium (south side only)
    bool north = false;   ///< on the north side of the corridor
  };

  int storeyCount() const { return static_cast<int>(b_.storey_heights.size()); }
  bool hasStairs() const { return part_ == Part::kBuilding && storeyCount() > 1; }

  void layout() {
    z_.assign(1, rise_);
    ramp_length_ = rise_ * kRampRun;
    for (double h : b_.storey_heights) z_.push_back(z_.back() + h);
    L_ = b_.corridor_length;
    yc_ = b_.corridor_width / 2;
    wt_ = b_.wall_thickness;
    if (hasStairs()) stairs_.emplace(b_.stairwell, b_.storey_heights, L_, yc_, wt_, spec_.source);
    y_north_ = yc_ + std::max(b_.room_depth, hasStairs() ? stairs_->yBack() - yc_ : 0.0);
    y_south_ = -yc_ - b_.room_depth;
    x_turn_west_ = wt_ / 2 + kEndClearance;
    x_turn_east_ = L_ - wt_ / 2 - kEndClearance;
    x_start_ = std::max(spec_.robot.start_offset, x_turn_west_ + 1.2);
    if (part_ == Part::kBuilding &&
        x_start_ > std::min(x_turn_east_, hasStairs() ? stairs_->westmostX() : x_turn_east_) - 1.5)
      throw Error(spec_.source +
                  ": key 'robot.start_offset' leaves no room to walk east of the start");
    if (b_.single_loaded) y_south_ = -yc_;
    layoutArms();

    // Rooms: south side over the corridor but for the arms (none when single
    // loaded), north side on both sides of the stairwell.
    if (!b_.single_loaded) {
      double x0 = 0.0;
      for (const ArmLayout& arm : arms_) {
        splitRooms(x0, arm.x - arm.half, south_rooms_);
        x0 = arm.x + arm.half;
      }
      splitRooms(x0, L_, south_rooms_);
    }
    if (hasStairs()) {
      splitRooms(0.0, stairs_->x0(), north_rooms_);
      splitRooms(stairs_->x1(), L_, north_rooms_);
    } else {
      splitRooms(0.0, L_, north_rooms_);
    }
    for (auto* rooms : {&south_rooms_, &north_rooms_}) {
      for (Room& r : *rooms) {
        r.north = rooms == &north_rooms_;
        const double w = r.x1 - r.x0;
        const double offset = std::max(0.45, 0.25 * w - b_.door_width / 2);
        r.door0 = r.x0 + wt_ / 2 + offset;
        r.door1 = r.door0 + b_.door_width;
        r.glass_front = rng_.uniform() < b_.glass_front_fraction;
      }
    }
    layoutAtrium();
    // Partitions at an angle: the offset along x between a partition's ends.
    const double angle = b_.partition_angle;
    cot_ = std::abs(angle - M_PI / 2) < 1e-9 ? 0.0 : std::cos(angle) / std::sin(angle);
    if (cot_ != 0.0) {
      double narrowest = 1e300;
      for (const auto* rooms : {&south_rooms_, &north_rooms_})
        for (const Room& r : *rooms) narrowest = std::min(narrowest, r.x1 - r.x0);
      const double offset = std::max(y_north_ - yc_, -y_south_ - yc_) * cot_;
      if (offset > 0.45 * narrowest)
        throw Error(spec_.source + ": key 'building.partition_angle_deg' is too oblique for " +
                    "rooms this deep and narrow (the partitions would cross)");
    }
    chooseEnteredRooms();
  }

  /// Half the width of the loop the walk makes inside `r`: it keeps 0.95 m
  /// from the partitions (a cabinet 0.5 m deep and the sensors' reach), more
  /// where they lean (a cabinet moves along with them over its depth).
  double roomLoopHalfWidth(const Room& r) const {
    return (r.x1 - r.x0 - wt_) / 2 - 0.95 - 2.0 * std::abs(cot_);
  }

  /// The rooms the walk goes into on each storey: robot.rooms_entered of
  /// those whose doors are on the corridor the walk covers (not the atrium),
  /// drawn from their own random stream (the building's draw is unchanged).
  void chooseEnteredRooms() {
    entered_.assign(storeyCount(), {});
    if (part_ != Part::kBuilding || spec_.robot.rooms_entered == 0) return;
    const double x_hi = !hasStairs() || b_.wings == 2 ? x_turn_east_ : stairs_->westmostX();
    std::vector<const Room*> eligible;
    for (const auto* rooms : {&south_rooms_, &north_rooms_})
      for (const Room& r : *rooms) {
        const double door = (r.door0 + r.door1) / 2;
        // The loop reaches 1.5 m past the wall's face; the desk is 0.75 m deep.
        const bool deep_enough = b_.room_depth - wt_ >= 2.75;
        if (!r.atrium && deep_enough && roomLoopHalfWidth(r) >= 0.1 && door > x_turn_west_ + 0.6 &&
            door < x_hi - 0.6)
          eligible.push_back(&r);
      }
    for (int k = 0; k < storeyCount(); ++k) {
      std::vector<const Room*> pool = eligible;
      for (int i = 0; i < spec_.robot.rooms_entered && !pool.empty(); ++i) {
        const auto pick = static_cast<std::size_t>(route_rng_.uniform() * pool.size());
        entered_[k].push_back(pool[std::min(pick, pool.size() - 1)]);
        pool.erase(pool.begin() + static_cast<std::ptrdiff_t>(std::min(pick, pool.size() - 1)));
      }
    }
  }

  bool entered(int k, const Room& r) const {
    return std::find(entered_[k].begin(), entered_[k].end(), &r) != entered_[k].end();
  }

  /// Whether the boundary of a room at x (its x0 or x1) is a partition that
  /// leans, rather than an end wall or a stairwell wall.
  bool leans(bool north, double x) const {
    if (cot_ == 0.0 || x <= 1e-9 || x >= L_ - 1e-9) return false;
    if (!north && atArmEdge(x)) return false;
    if (north && hasStairs() &&
        (std::abs(x - stairs_->x0()) < 1e-9 || std::abs(x - stairs_->x1()) < 1e-9))
      return false;
    return true;
  }
  /// x of a room boundary (centreline) at distance `y` from the corridor axis.
  double boundaryAt(bool north, double x, double y) const {
    return leans(north, x) ? x + (y - yc_) * cot_ : x;
  }

  /// A partition from the corridor wall line to the outer wall, leaning when cot_ != 0.
  void addPartition(bool north, double x, double z0, double z1) {
    const double y_outer = north ? y_north_ : y_south_, y_corridor = north ? yc_ : -yc_;
    if (cot_ == 0.0) {
      addWall(false, x, std::min(y_outer, y_corridor), std::max(y_outer, y_corridor), z0, z1, {});
      return;
    }
    const Vector2d p(x, y_corridor), q(x + std::abs(y_outer - y_corridor) * cot_, y_outer);
    const Vector2d u = (q - p).normalized(), n(-u.y(), u.x());
    out_.mesh.addPrism({p - n * wt_ / 2, q - n * wt_ / 2, q + n * wt_ / 2, p + n * wt_ / 2}, z0, z1,
                       Surface::kWall, surfaceReflectivity(Surface::kWall));
  }

  /// The south rooms the atrium replaces: `rooms` consecutive ones centred
  /// as near as they can be to atrium.position.
  void layoutAtrium() {
    const AtriumSpec& a = b_.atrium;
    if (a.rooms == 0) return;
    const int n = static_cast<int>(south_rooms_.size());
    if (a.rooms > n - 1)
      throw Error(spec_.source + ": key 'building.atrium.rooms' (" + std::to_string(a.rooms) +
                  ") must leave at least one of the " + std::to_string(n) + " south rooms");
    const double centre = a.position * L_;
    int first = 0;
    double best = 1e300;
    for (int i = 0; i + a.rooms <= n; ++i) {
      bool adjacent = true;  // not across an arm
      for (int j = i + 1; j < i + a.rooms; ++j)
        adjacent = adjacent && std::abs(south_rooms_[j].x0 - south_rooms_[j - 1].x1) < 1e-9;
      if (!adjacent) continue;
      const double mid = (south_rooms_[i].x0 + south_rooms_[i + a.rooms - 1].x1) / 2;
      if (std::abs(mid - centre) < best) {
        best = std::abs(mid - centre);
        first = i;
      }
    }
    if (best == 1e300)
      throw Error(spec_.source + ": key 'building.atrium.rooms' (" + std::to_string(a.rooms) +
                  ") finds no run of that many adjacent south rooms between the arms");
    for (int i = first; i < first + a.rooms; ++i) south_rooms_[i].atrium = true;
    atrium_x0_ = south_rooms_[first].x0;
    atrium_x1_ = south_rooms_[first + a.rooms - 1].x1;
  }

  bool hasAtrium() const { return b_.atrium.rooms > 0; }

  /// The arms along the corridor, west to east; refuses arms that do not fit
  /// or overlap.
  void layoutArms() {
    const ArmsSpec& a = b_.arms;
    for (std::size_t i = 0; i < a.positions.size(); ++i) {
      ArmLayout arm;
      arm.half = yc_ + b_.room_depth;
      arm.length = a.lengths[i];
      arm.rise = a.rises.empty() ? 0.0 : a.rises[i];
      if (L_ < 2 * arm.half)
        throw Error(spec_.source + ": key 'building.arms.positions': an arm (" +
                    std::to_string(2 * arm.half) + " m wide with its rooms) is wider than " +
                    "the corridor is long");
      arm.x = std::clamp(a.positions[i] * L_, arm.half, L_ - arm.half);
      if (arm.length < std::max(b_.room_depth, arm.rise * kRampRun) + 2 * kEndClearance + 2.0)
        throw Error(spec_.source + ": key 'building.arms.lengths' is too short to walk into");
      arms_.push_back(arm);
    }
    std::sort(arms_.begin(), arms_.end(),
              [](const ArmLayout& l, const ArmLayout& r) { return l.x < r.x; });
    for (std::size_t i = 1; i < arms_.size(); ++i)
      if (arms_[i].x - arms_[i].half < arms_[i - 1].x + arms_[i - 1].half - 1e-9)
        throw Error(spec_.source + ": key 'building.arms.positions': two arms overlap");
  }

  /// Whether x is on an arm's outer wall (the edge of its span).
  bool atArmEdge(double x) const {
    for (const ArmLayout& arm : arms_)
      if (std::abs(x - (arm.x - arm.half)) < 1e-9 || std::abs(x - (arm.x + arm.half)) < 1e-9)
        return true;
    return false;
  }

  /// Each arm, built in its own frame (x along it, from the main corridor's
  /// south wall), turned to point south and moved to its place.
  void addArms() {
    for (std::size_t i = 0; i < arms_.size(); ++i) {
      BuildingSpec arm_spec = spec_;
      BuildingLayoutSpec& a = arm_spec.building;
      a.corridor_length = arms_[i].length;
      a.wings = 1;
      a.single_loaded = false;
      a.partition_angle = M_PI / 2;
      a.atrium = AtriumSpec{};
      a.arms = ArmsSpec{};
      const Building arm =
          Generator(arm_spec, Part::kArm, 0x61726d00ULL + i, arms_[i].rise).run();  // "arm"
      Eigen::Matrix3d R_main_arm;
      R_main_arm << 0, 1, 0, -1, 0, 0, 0, 0, 1;  // arm x -> main -y, arm y -> main x
      out_.mesh.append(arm.mesh, R_main_arm, Vector3d(arms_[i].x, -yc_, 0.0));
    }
  }

  void splitRooms(double x0, double x1, std::vector<Room>& rooms) {
    const double length = x1 - x0;
    if (length < 2.5) return;
    const int count = std::max(1, static_cast<int>(std::lround(length / b_.room_width)));
    for (int i = 0; i < count; ++i)
      rooms.push_back({x0 + length * i / count, x0 + length * (i + 1) / count, 0, 0, false});
  }

  // ---- mesh helpers -------------------------------------------------------

  /// Wall along x (at y = c) or along y (at x = c) from u = a to b, z in [z0, z1], with openings.
  void addWall(bool along_x, double c, double a, double b, double z0, double z1,
               std::vector<Opening> openings, Surface surface = Surface::kWall) {
    std::sort(openings.begin(), openings.end(),
              [](const Opening& l, const Opening& r) { return l.u0 < r.u0; });
    auto box = [&](double u0, double u1, double zz0, double zz1, double thickness, Surface s) {
      if (u1 - u0 < 1e-6 || zz1 - zz0 < 1e-6) return;
      if (along_x)
        out_.mesh.addBox(Vector3d(u0, c - thickness / 2, zz0), Vector3d(u1, c + thickness / 2, zz1),
                         s);
      else
        out_.mesh.addBox(Vector3d(c - thickness / 2, u0, zz0), Vector3d(c + thickness / 2, u1, zz1),
                         s);
    };
    double u = a;
    for (const Opening& o : openings) {
      const double u0 = std::max(o.u0, u), u1 = std::min(o.u1, b);
      if (u1 <= u0) continue;
      box(u, u0, z0, z1, wt_, surface);
      box(u0, u1, z0, o.z0, wt_, surface);
      box(u0, u1, o.z1, z1, wt_, surface);
      if (o.glass) box(u0, u1, o.z0, o.z1, kGlassThickness, Surface::kGlass);
      u = u1;
    }
    box(u, b, z0, z1, wt_, surface);
  }

  void addSlab(int k) {
    const double top = z_[k], t = b_.slab_thickness;
    const Rect outer{-wt_ / 2, y_south_ - wt_ / 2, L_ + wt_ / 2, y_north_ + wt_ / 2};
    std::vector<Rect> holes;
    if (hasStairs() && k > 0 && k < storeyCount()) {
      holes = stairs_->slabHoles(k);
    }
    if (hasAtrium() && k > 0 && k < storeyCount())
      holes.push_back(
          {atrium_x0_ + wt_ / 2, y_south_ + wt_ / 2, atrium_x1_ - wt_ / 2, -yc_ - wt_ / 2});
    // Where the arms cross the south rooms' band, their own floors (at their level).
    for (const ArmLayout& arm : arms_)
      if (y_south_ < -yc_ - wt_ / 2)
        holes.push_back({arm.x - arm.half, y_south_ - wt_ / 2, arm.x + arm.half, -yc_ - wt_ / 2});
    // A split-level arm's corridor starts with its ramp, not its floor.
    if (ramp_length_ > 0.0 && k < storeyCount()) {
      holes.push_back({-wt_ / 2, -yc_, ramp_length_, yc_});
      addRamp(k);
    }
    std::vector<Rect> parts{outer};
    for (const Rect& hole : holes) {
      std::vector<Rect> cut;
      for (const Rect& part : parts)
        for (const Rect& piece : rectMinus(part, hole)) cut.push_back(piece);
      parts = std::move(cut);
    }
    for (const Rect& r : parts) {
      // Upper half reads as floor, lower half as ceiling.
      out_.mesh.addBox(Vector3d(r.x0, r.y0, top - t / 2), Vector3d(r.x1, r.y1, top),
                       Surface::kFloor);
      out_.mesh.addBox(Vector3d(r.x0, r.y0, top - t), Vector3d(r.x1, r.y1, top - t / 2),
                       Surface::kCeiling);
    }
  }

  /// The ramp up a split-level arm's corridor on storey k: from the main
  /// building's floor at x = 0 to the arm's at the ramp's end, a sloping
  /// slab as thick as the others.
  void addRamp(int k) {
    const double top = z_[k], bottom = top - rise_, t = b_.slab_thickness;
    const float floor = surfaceReflectivity(Surface::kFloor);
    const float ceiling = surfaceReflectivity(Surface::kCeiling);
    const double x1 = ramp_length_;
    out_.mesh.addQuad(Vector3d(0, -yc_, bottom), Vector3d(x1, -yc_, top), Vector3d(x1, yc_, top),
                      Vector3d(0, yc_, bottom), Surface::kFloor, floor);
    out_.mesh.addQuad(Vector3d(0, yc_, bottom - t), Vector3d(x1, yc_, top - t),
                      Vector3d(x1, -yc_, top - t), Vector3d(0, -yc_, bottom - t), Surface::kCeiling,
                      ceiling);
  }

  void addStoreyWalls(int k) {
    const double zf = z_[k], t = b_.slab_thickness;
    // Walls pass through the slab below (a split-level arm's down to the
    // main building's, so its ramp leaves no gap under them).
    const double z0 = zf - t - rise_, z1 = z_[k + 1] - t;
    const double ceiling = z1;
    const double window_z0 = zf + b_.window_sill, window_z1 = window_z0 + b_.window_height;

    // Outer walls with windows at room centres; corridor ends glazed.
    auto windows = [&](const std::vector<Room>& rooms, bool north) {
      std::vector<Opening> o;
      const double y_outer = north ? y_north_ : -y_south_;
      for (const Room& r : rooms) {
        const double m = (boundaryAt(north, r.x0, y_outer) + boundaryAt(north, r.x1, y_outer)) / 2;
        o.push_back({m - b_.window_width / 2, m + b_.window_width / 2, window_z0, window_z1, true});
      }
      return o;
    };
    if (!b_.single_loaded) {
      // The south outer wall, but where the arms leave.
      const std::vector<Opening> south_windows = windows(south_rooms_, false);
      double x0 = -wt_ / 2;
      for (const ArmLayout& arm : arms_) {
        addWall(true, y_south_, x0, arm.x - arm.half, z0, z1, south_windows);
        x0 = arm.x + arm.half;
      }
      addWall(true, y_south_, x0, L_ + wt_ / 2, z0, z1, south_windows);
    }
    addWall(true, y_north_, -wt_ / 2, L_ + wt_ / 2, z0, z1, windows(north_rooms_, true));
    const double glass_top = std::min(zf + 2.5, ceiling - 0.15);
    const std::vector<Opening> corridor_end{{-yc_ + 0.35, yc_ - 0.35, zf + 0.05, glass_top, true}};
    // An arm is open at its west end, to the main corridor.
    if (part_ != Part::kArm)
      addWall(false, 0.0, y_south_ + wt_ / 2, y_north_ - wt_ / 2, z0, z1, corridor_end);
    addWall(false, L_, y_south_ + wt_ / 2, y_north_ - wt_ / 2, z0, z1, corridor_end);

    // Corridor walls: doors, glass fronts, the stairwell entrance.
    auto corridorOpenings = [&](const std::vector<Room>& rooms) {
      std::vector<Opening> o;
      for (const Room& r : rooms) {
        if (r.atrium) continue;  // one opening over the whole atrium, below
        o.push_back({r.door0, r.door1, zf, zf + b_.door_height, false});
        if (r.glass_front) {
          const double g0 = r.x0 + wt_ / 2 + 0.2, g1 = r.x1 - wt_ / 2 - 0.2;
          const double gz0 = zf + 0.1, gz1 = std::min(zf + 2.6, ceiling - 0.1);
          if (r.door0 - 0.1 - g0 > 0.3) o.push_back({g0, r.door0 - 0.1, gz0, gz1, true});
          if (g1 - (r.door1 + 0.1) > 0.3) o.push_back({r.door1 + 0.1, g1, gz0, gz1, true});
        }
      }
      return o;
    };
    std::vector<Opening> north = corridorOpenings(north_rooms_);
    if (hasStairs())
      for (const Opening& o : stairs_->corridorOpenings(zf, ceiling)) north.push_back(o);
    std::vector<Opening> south = corridorOpenings(south_rooms_);
    if (b_.single_loaded) {
      // The corridor's south wall is an outer wall: windows at room spacing, but not onto the arms.
      const int count = std::max(1, static_cast<int>(std::lround(L_ / b_.room_width)));
      for (int i = 0; i < count; ++i) {
        const double m = L_ * (i + 0.5) / count;
        const double w0 = m - b_.window_width / 2, w1 = m + b_.window_width / 2;
        bool onto_arm = false;
        for (const ArmLayout& arm : arms_)
          onto_arm = onto_arm || (w1 > arm.x - arm.half - 0.1 && w0 < arm.x + arm.half + 0.1);
        if (!onto_arm) south.push_back({w0, w1, window_z0, window_z1, true});
      }
    }
    for (const ArmLayout& arm : arms_) {  // into the arm's corridor
      south.push_back({arm.x - yc_ + wt_ / 2, arm.x + yc_ - wt_ / 2, zf, z1, false});
      // Up to a split-level arm's ceiling above its rooms (above its
      // corridor the ramp of the storey above meets this ceiling).
      if (arm.rise > 0.0)
        for (const auto& [x0, x1] :
             {std::pair(arm.x - arm.half, arm.x - yc_), std::pair(arm.x + yc_, arm.x + arm.half)})
          out_.mesh.addBox(Vector3d(x0, -yc_ - wt_ / 2, z1),
                           Vector3d(x1, -yc_ + wt_ / 2, z1 + arm.rise), Surface::kWall);
    }
    if (hasAtrium()) {
      // Open to the hall on the ground floor; above it a balustrade: a solid
      // parapet (the wall below the opening) or a glass pane in the opening.
      const AtriumSpec& a = b_.atrium;
      const double ax0 = atrium_x0_ + wt_ / 2, ax1 = atrium_x1_ - wt_ / 2;
      const bool parapet = k > 0 && !a.glass_balustrade;
      south.push_back({ax0, ax1, parapet ? zf + a.balustrade_height : zf, z1, false});
      if (k > 0 && a.glass_balustrade)
        out_.mesh.addBox(Vector3d(ax0, -yc_ - kGlassThickness / 2, zf),
                         Vector3d(ax1, -yc_ + kGlassThickness / 2, zf + a.balustrade_height),
                         Surface::kGlass);
    }
    addWall(true, -yc_, 0.0, L_, z0, z1, south);
    addWall(true, yc_, 0.0, L_, z0, z1, north);

    // Partitions between rooms.
    for (std::size_t i = 1; i < south_rooms_.size(); ++i) {
      if (south_rooms_[i - 1].atrium && south_rooms_[i].atrium) continue;  // inside the atrium
      if (std::abs(south_rooms_[i].x0 - south_rooms_[i - 1].x1) > 1e-9) continue;  // an arm's wall
      addPartition(false, south_rooms_[i].x0, z0, z1);
    }
    for (std::size_t i = 1; i < north_rooms_.size(); ++i) {
      if (hasStairs() && std::abs(north_rooms_[i].x0 - stairs_->x1()) < 1e-9) continue;
      addPartition(true, north_rooms_[i].x0, z0, z1);
    }

    if (hasStairs()) {
      const double x0 = stairs_->x0(), x1 = stairs_->x1(), y_back = stairs_->yBack();
      addWall(false, x0, yc_, y_north_, z0, z1, {});
      addWall(false, x1, yc_, y_north_, z0, z1, {});
      if (y_back < y_north_ - 1e-6) addWall(true, y_back, x0, x1, z0, z1, {});
    }

    // Ceiling lamps along the corridor axis.
    for (double x = 2.0; x < L_ - 1.0; x += 3.0) {
      out_.mesh.addBox(Vector3d(x - 0.6, -0.15, ceiling - 0.06), Vector3d(x + 0.6, 0.15, ceiling),
                       Surface::kClutter, 120.0f);
    }
  }

  /// Free intervals along a corridor wall: not in doors, glass, the stairwell, the ends.
  bool corridorSpotFree(bool north, double x0, double x1) const {
    if (x0 < std::max(x_turn_west_ + 0.8, ramp_length_ + 0.3) || x1 > x_turn_east_ - 0.8)
      return false;
    for (const Room& r : north ? north_rooms_ : south_rooms_) {
      if (x1 > r.door0 - 0.15 && x0 < r.door1 + 0.15) return false;
      if (r.glass_front && x1 > r.x0 && x0 < r.x1) {
        // Objects in front of glass are fine, but keep the view: allow only low ones (checked by
        // caller).
      }
    }
    if (north && hasStairs() && x1 > stairs_->x0() - 0.2 && x0 < stairs_->x1() + 0.2) return false;
    if (!north && hasAtrium() && x1 > atrium_x0_ - 0.2 && x0 < atrium_x1_ + 0.2) return false;
    for (const ArmLayout& arm : arms_)  // clear of the turn into the arm
      if (!north && x1 > arm.x - yc_ - 0.6 && x0 < arm.x + yc_ + 0.6) return false;
    for (const Room* room : entered_[storey_])  // clear of the walk through the door
      if (room->north == north && x1 > room->door0 - 0.8 && x0 < room->door1 + 0.8) return false;
    return true;
  }

  void addCorridorClutter(int k) {
    const double zf = z_[k];
    const double ceiling = z_[k + 1] - b_.slab_thickness;
    const double face = yc_ - wt_ / 2;  // wall face distance from the axis
    for (bool north : {false, true}) {
      const double side = north ? 1.0 : -1.0;
      std::vector<std::pair<double, double>> used;
      auto overlaps = [&](double x0, double x1) {
        for (const auto& u : used)
          if (x1 > u.first - 0.1 && x0 < u.second + 0.1) return true;
        return false;
      };
      // Pillars: structural, every pillar_spacing, protruding from the wall.
      if (b_.pillar_spacing > 0.0) {
        for (double x = b_.pillar_spacing; x < L_ - 1.0; x += b_.pillar_spacing) {
          const double x0 = x - 0.2, x1 = x + 0.2;
          if (!corridorSpotFree(north, x0, x1)) continue;
          const double y_in = side * (face - 0.12), y_out = side * (face + wt_ / 2);
          out_.mesh.addBox(Vector3d(x0, std::min(y_in, y_out), zf),
                           Vector3d(x1, std::max(y_in, y_out), ceiling), Surface::kPillar);
          used.push_back({x0, x1});
        }
      }
      // Cabinets, bins and notice boards against the wall.
      const int count = static_cast<int>(std::lround(b_.clutter_density * L_));
      for (int i = 0, attempts = 0; i < count && attempts < 20 * count + 20; ++attempts) {
        const double kind = rng_.uniform();
        const double width = kind < 0.2 ? 0.35 : rng_.uniform(0.4, 1.3);
        const double x0 = rng_.uniform(0.0, L_ - width), x1 = x0 + width;
        if (!corridorSpotFree(north, x0, x1) || overlaps(x0, x1)) continue;
        used.push_back({x0, x1});
        ++i;
        const float reflectivity = static_cast<float>(rng_.uniform(15.0, 110.0));
        if (kind < 0.2) {  // round bin
          const double r = 0.17;
          const double y = side * (face - r - 0.02);
          out_.mesh.addCylinder(Vector2d((x0 + x1) / 2, y), r, zf, zf + rng_.uniform(0.5, 0.8), 12,
                                Surface::kClutter, reflectivity);
        } else if (kind < 0.4) {  // notice board / fire hose cabinet on the wall
          const double depth = rng_.uniform(0.03, 0.15);
          const double bz0 = zf + rng_.uniform(0.8, 1.2), bz1 = bz0 + rng_.uniform(0.4, 0.9);
          const double y_in = side * (face - depth), y_out = side * face;
          out_.mesh.addBox(Vector3d(x0, std::min(y_in, y_out), bz0),
                           Vector3d(x1, std::max(y_in, y_out), bz1), Surface::kClutter,
                           reflectivity);
        } else {  // cabinet / shelf
          const double depth = rng_.uniform(0.2, 0.3);
          const double height = rng_.uniform(0.5, 2.0);
          const double y_in = side * (face - depth), y_out = side * face;
          out_.mesh.addBox(Vector3d(x0, std::min(y_in, y_out), zf),
                           Vector3d(x1, std::max(y_in, y_out), zf + height), Surface::kClutter,
                           reflectivity);
        }
      }
    }
  }

  void addRoomFurniture(int k) {
    const double zf = z_[k];
    for (bool north : {false, true}) {
      room_north_ = north;
      const double side = north ? 1.0 : -1.0;
      const double y_near = yc_ + wt_ / 2, y_far = (north ? y_north_ : -y_south_) - wt_ / 2;
      for (const Room& r : north ? north_rooms_ : south_rooms_) {
        if (r.atrium && k > 0) continue;  // the void; the hall below keeps its furniture
        const double rx0 = r.x0 + wt_ / 2, rx1 = r.x1 - wt_ / 2;
        room_ = &r;
        // Desk against the outer wall.
        const double dw = std::min(rng_.uniform(1.2, 1.8), rx1 - rx0 - 0.4);
        const double dx = rng_.uniform(rx0 + 0.1, rx1 - dw - 0.1);
        box2(side, dx, dx + dw, y_far - 0.75, y_far, zf, zf + 0.75, rng_.uniform(20.0, 90.0));
        // Tall cabinet against a partition, away from the door.
        const bool left = rng_.uniform() < 0.5;
        const double cx0 = left ? rx0 : rx1 - 0.5;
        const double cy = rng_.uniform(y_near + 1.3, std::max(y_near + 1.35, y_far - 1.8));
        box2(side, cx0, cx0 + 0.5, cy, cy + rng_.uniform(0.8, 1.6), zf, zf + rng_.uniform(1.6, 2.1),
             rng_.uniform(20.0, 90.0));
        // A chair-sized box and a round bin; in a room the walk enters, no
        // chair and the bin in the corner away from the door (same draws).
        const bool walked_in = entered(k, r);
        const double chx = rng_.uniform(rx0 + 0.8, std::max(rx0 + 0.85, rx1 - 0.8));
        const double chair_reflectivity = rng_.uniform(20.0, 60.0);
        if (!walked_in)
          box2(side, chx - 0.25, chx + 0.25, y_far - 1.4, y_far - 0.9, zf, zf + 0.9,
               chair_reflectivity);
        const double by = y_near + 0.45;
        const double bin_x = rng_.uniform(rx0 + 0.4, std::max(rx0 + 0.45, rx1 - 0.4));
        const double bx = (walked_in ? rx1 - 0.35 : bin_x) + leanShift(r, by);
        out_.mesh.addCylinder(Vector2d(bx, side * by), 0.16, zf, zf + 0.55, 12, Surface::kClutter,
                              static_cast<float>(rng_.uniform(20.0, 90.0)));
      }
    }
  }

  /// How far the partitions of `r` have moved along x at distance `y` from
  /// the corridor axis (their mean; 0 without leaning partitions).
  double leanShift(const Room& r, double y) const {
    return (boundaryAt(r.north, r.x0, y) - r.x0 + boundaryAt(r.north, r.x1, y) - r.x1) / 2;
  }

  /// Box in room coordinates: y measured from the corridor axis on `side`.
  /// With leaning partitions it moves along x with them (by their offset at
  /// its middle) and is kept inside the room over its whole depth.
  void box2(double side, double x0, double x1, double y0, double y1, double z0, double z1,
            double reflectivity) {
    if (cot_ != 0.0 && room_ != nullptr) {
      const bool north = room_north_;
      const double lo = std::min(y0, y1), hi = std::max(y0, y1);
      const double shift = (boundaryAt(north, room_->x0, (lo + hi) / 2) - room_->x0 +
                            boundaryAt(north, room_->x1, (lo + hi) / 2) - room_->x1) /
                           2;
      const double left =
          std::max(boundaryAt(north, room_->x0, lo), boundaryAt(north, room_->x0, hi)) + wt_ / 2;
      const double right =
          std::min(boundaryAt(north, room_->x1, lo), boundaryAt(north, room_->x1, hi)) - wt_ / 2;
      const double width = x1 - x0;
      x0 = std::clamp(x0 + shift, left, right - width);
      x1 = x0 + width;
      if (x0 < left - 1e-9) return;  // no room for it at this depth
    }
    const double ya = side * y0, yb = side * y1;
    out_.mesh.addBox(Vector3d(x0, std::min(ya, yb), z0), Vector3d(x1, std::max(ya, yb), z1),
                     Surface::kClutter, static_cast<float>(reflectivity));
  }

  // ---- route ----------------------------------------------------------------

  /// A side trip off a corridor lane, at `x` along it: into an arm or a room.
  struct Detour {
    double x = 0.0;
    const ArmLayout* arm = nullptr;
    const Room* room = nullptr;
  };

  std::vector<Detour> detoursOf(int k) const {
    std::vector<Detour> d;
    for (const ArmLayout& arm : arms_) d.push_back({arm.x, &arm, nullptr});
    for (const Room* room : entered_[k])
      d.push_back({(room->door0 + room->door1) / 2, nullptr, room});
    return d;
  }

  void at(double x, double y, double z, double speed) {
    out_.route.push_back({Vector3d(x, y, z), speed});
  }

  /// Walks along the lane at y from where the route is to x_to, taking the
  /// side trips of pending_ that lie on the way (each once).
  void along(double x_to, double y, double z) {
    const double x_from = out_.route.back().p.x(), dir = x_to >= x_from ? 1.0 : -1.0;
    std::vector<Detour> here;
    for (auto it = pending_.begin(); it != pending_.end();) {
      if ((it->x - x_from) * dir > 0.0 && (x_to - it->x) * dir > 0.0) {
        here.push_back(*it);
        it = pending_.erase(it);
      } else {
        ++it;
      }
    }
    std::sort(here.begin(), here.end(),
              [&](const Detour& l, const Detour& r) { return (l.x - r.x) * dir < 0.0; });
    for (const Detour& d : here) {
      if (d.arm != nullptr)
        armTrip(*d.arm, dir, y, z);
      else
        roomTrip(*d.room, y, z);
    }
    at(x_to, y, z, spec_.robot.walk_speed);
  }

  /// Down the arm on one lane, round its end, back on the other.
  void armTrip(const ArmLayout& arm, double dir, double y, double z) {
    const double lane = spec_.robot.lane_offset, walk = spec_.robot.walk_speed;
    const double y_end = -yc_ - (arm.length - wt_ / 2 - kEndClearance);
    const double y_ramp = -yc_ - arm.rise * kRampRun, z_arm = z + arm.rise;
    at(arm.x - dir * lane, y, z, walk);
    if (arm.rise > 0.0) {  // up the ramp
      at(arm.x - dir * lane, -yc_, z, walk);
      at(arm.x - dir * lane, y_ramp, z_arm, walk);
    }
    at(arm.x - dir * lane, y_end, z_arm, walk);
    at(arm.x + dir * lane, y_end, z_arm, walk);
    if (arm.rise > 0.0) {  // down it
      at(arm.x + dir * lane, y_ramp, z_arm, walk);
      at(arm.x + dir * lane, -yc_, z, walk);
    }
    at(arm.x + dir * lane, y, z, walk);
  }

  /// Through the door, a loop round the middle of the room, out again.
  void roomTrip(const Room& r, double y, double z) {
    const double walk = spec_.robot.walk_speed, side = r.north ? 1.0 : -1.0;
    const double door = (r.door0 + r.door1) / 2, centre = (r.x0 + r.x1) / 2;
    const double half = std::min(0.5, roomLoopHalfWidth(r));
    const double y_in = yc_ + wt_ / 2 + 0.6, y_loop = y_in + 0.9;  // from the corridor axis
    at(door, y, z, walk);
    at(door + leanShift(r, y_in), side * y_in, z, walk);
    at(centre + half + leanShift(r, y_loop), side * y_loop, z, walk);
    at(centre - half + leanShift(r, y_loop), side * y_loop, z, walk);
    at(door + leanShift(r, y_in), side * y_in, z, walk);
    at(door, y, z, walk);
  }

  void addRoute() {
    const RobotSpec& robot = spec_.robot;
    const double lane = robot.lane_offset;
    const double walk = robot.walk_speed, climb = robot.stair_speed;
    auto floorZ = [&](int k) { return z_[k] + robot.body_height; };
    const int top = storeyCount() - 1;

    pending_ = detoursOf(0);
    at(x_start_, lane, floorZ(0), walk);
    if (!hasStairs()) {
      along(x_turn_east_, lane, floorZ(0));
      at(x_turn_east_, -lane, floorZ(0), walk);
      along(x_turn_west_, -lane, floorZ(0));
      at(x_turn_west_, lane, floorZ(0), walk);
      along(x_start_, lane, floorZ(0));
      return;
    }
    // The walk on a storey goes round the east end too when there is a wing
    // or an arm east of the stairs.
    bool east_loop = b_.wings == 2;
    // (The top storey's walk ends at the west flight, the others' at the east one.)
    for (const ArmLayout& arm : arms_) east_loop = east_loop || arm.x >= stairs_->westmostX();
    // Ground floor: east along the north lane (and round the east end), then up.
    double lane_to_stairs = lane;
    if (east_loop) {
      along(x_turn_east_, lane, floorZ(0));
      at(x_turn_east_, -lane, floorZ(0), walk);
      lane_to_stairs = -lane;
    }
    std::vector<Detour> ground_left;
    for (int k = 0; k < top; ++k) {
      const double zn = floorZ(k + 1);
      along(stairs_->entryX(k), lane_to_stairs, floorZ(k));
      if (k == 0) ground_left = std::move(pending_);
      for (const RouteVertex& v : stairs_->climb(k, robot.body_height, walk, climb))
        out_.route.push_back(v);
      // Storey k+1: out to the south lane, west wing, back east.
      pending_ = detoursOf(k + 1);
      at(stairs_->exitX(k), -lane, zn, walk);
      along(x_turn_west_, -lane, zn);
      at(x_turn_west_, lane, zn, walk);
      lane_to_stairs = lane;
      if (east_loop) {
        along(x_turn_east_, lane, zn);
        at(x_turn_east_, -lane, zn, walk);
        lane_to_stairs = -lane;
      }
    }
    // Down from the top storey, flight by flight.
    along(stairs_->exitX(top - 1), lane_to_stairs, floorZ(top));
    pending_.clear();
    for (int k = top - 1; k >= 0; --k)
      for (const RouteVertex& v : stairs_->descend(k, robot.body_height, walk, climb, k > 0))
        out_.route.push_back(v);
    // Ground floor: to the south lane, round the west end, back to the start.
    pending_ = std::move(ground_left);
    at(stairs_->entryX(0), -lane, floorZ(0), walk);
    along(x_turn_west_, -lane, floorZ(0));
    at(x_turn_west_, lane, floorZ(0), walk);
    along(x_start_, lane, floorZ(0));
  }

  /// robot.rounds > 1: the route walked again from its start, round after
  /// round. It ends where it starts, heading east on the north lane as it
  /// started, so the rounds join without a stop or a reversal.
  void repeatRoute(int rounds) {
    const std::vector<RouteVertex> once = out_.route;
    for (int r = 1; r < rounds; ++r)
      out_.route.insert(out_.route.end(), once.begin() + 1, once.end());
  }

  const BuildingSpec& spec_;
  const BuildingLayoutSpec& b_;
  Part part_;
  double rise_ = 0.0;         ///< kArm: its floors above the main building's [m]
  double ramp_length_ = 0.0;  ///< kArm: the ramp at the start of its corridor [m]
  Random rng_;
  Random route_rng_;  ///< which rooms the walk enters
  Building out_;
  std::vector<double> z_;         ///< floor top of storey k; z_[N] = roof top
  std::optional<Stairs> stairs_;  ///< when there are two storeys or more
  std::vector<Room> south_rooms_, north_rooms_;
  double L_ = 0, yc_ = 0, wt_ = 0;
  double y_north_ = 0, y_south_ = 0;
  double x_turn_west_ = 0, x_turn_east_ = 0, x_start_ = 0;
  double atrium_x0_ = 0, atrium_x1_ = 0;  ///< partition centrelines at the atrium's ends
  double cot_ = 0.0;            ///< cot(partition angle): x offset per metre away from the corridor
  const Room* room_ = nullptr;  ///< the room box2() furnishes
  std::vector<ArmLayout> arms_;                    ///< west to east
  std::vector<std::vector<const Room*>> entered_;  ///< per storey, the rooms the walk enters
  int storey_ = 0;                                 ///< the storey being built
  std::vector<Detour> pending_;  ///< side trips of the storey being walked, not yet taken
  bool room_north_ = false;
};

}  // namespace

void Building::translate(const Eigen::Vector3d& offset) {
  mesh.translate(offset);
  for (StoreyTruth& s : storeys) {
    s.floor_z += offset.z();
    s.ceiling_z += offset.z();
  }
  for (RouteVertex& v : route) v.p += offset;
}

void Building::rotateZ(double yaw) {
  mesh.rotateZ(yaw);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (RouteVertex& v : route) v.p = R * v.p;
}

Building generateBuilding(const BuildingSpec& spec) {
  return Generator(spec).run();
}

}  // namespace storey::sim
