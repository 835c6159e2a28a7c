#include "sim/trajectory.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace storey::sim {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kPathStep = 0.01;         ///< dense path sampling [m]
constexpr double kControlInterval = 0.05;  ///< B-spline knot spacing [s]
constexpr double kGaitFullSpeed = 0.15;    ///< speed at which the gait is fully developed [m/s]

/// One sample of the dense walking path.
struct PathSample {
  Vector3d p;
  double s = 0.0;     ///< arc length [m]
  double vmax = 0.0;  ///< speed limit [m/s]
  double v = 0.0;     ///< planned speed [m/s]
  double t = 0.0;     ///< planned time from the start of the walk [s]
};

double wrapAngle(double a) {
  return std::remainder(a, 2.0 * M_PI);
}

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

Matrix3d skew(const Vector3d& w) {
  Matrix3d K;
  K << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return K;
}

/// Rotation about a unit axis by alpha(t), with its first and second time derivatives.
struct AxisRotation {
  Matrix3d R, dR, ddR;
  AxisRotation(const Vector3d& axis, double a, double da, double dda) {
    R = Eigen::AngleAxisd(a, axis).toRotationMatrix();
    const Matrix3d K = skew(axis);
    dR = R * K * da;
    ddR = R * (K * K * (da * da) + K * dda);
  }
};

/// A scalar and its first and second time derivatives.
struct Jet {
  double v = 0.0, d = 0.0, dd = 0.0;
};

/// g(t) = w(t) * amplitude * sin(omega t + phase) and its two derivatives.
void gaitTerm(double w, double dw, double ddw, double amplitude, double omega, double phase,
              double t, double& g, double& dg, double& ddg) {
  const double s = std::sin(omega * t + phase), c = std::cos(omega * t + phase);
  g = w * amplitude * s;
  dg = amplitude * (dw * s + w * omega * c);
  ddg = amplitude * (ddw * s + 2.0 * dw * omega * c - w * omega * omega * s);
}

Jet gaitJet(double w, double dw, double ddw, double amplitude, double omega, double phase,
            double t) {
  Jet g;
  gaitTerm(w, dw, ddw, amplitude, omega, phase, t, g.v, g.d, g.dd);
  return g;
}

/// The kinematics of R = A B C and position p (derivatives v, a).
FrameKinematics composeKinematics(const AxisRotation& A, const AxisRotation& B,
                                  const AxisRotation& C, const Vector3d& p, const Vector3d& v,
                                  const Vector3d& a) {
  FrameKinematics k;
  k.v_world = v;
  k.a_world = a;
  const Matrix3d R = A.R * B.R * C.R;
  k.dR = A.dR * B.R * C.R + A.R * B.dR * C.R + A.R * B.R * C.dR;
  k.ddR = A.ddR * B.R * C.R + A.R * B.ddR * C.R + A.R * B.R * C.ddR +
          2.0 * (A.dR * B.dR * C.R + A.dR * B.R * C.dR + A.R * B.dR * C.dR);
  const Matrix3d W = R.transpose() * k.dR;  // skew(omega_body)
  k.omega_frame = 0.5 * Vector3d(W(2, 1) - W(1, 2), W(0, 2) - W(2, 0), W(1, 0) - W(0, 1));
  k.T_world_frame = Pose(R, p);
  return k;
}

/// Dense path with rounded corners (circular fillets) and speed limits.
std::vector<PathSample> densePath(const std::vector<RouteVertex>& route, const RobotSpec& robot) {
  std::vector<RouteVertex> v;
  for (const RouteVertex& r : route)
    if (v.empty() || (r.p - v.back().p).norm() > 1e-9) v.push_back(r);
  if (v.size() < 2) throw Error("simulator: the robot's route has fewer than two distinct points");
  const std::size_t n = v.size();
  std::vector<Vector3d> dir(n - 1);
  std::vector<double> len(n - 1);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    len[j] = (v[j + 1].p - v[j].p).norm();
    dir[j] = (v[j + 1].p - v[j].p) / len[j];
  }
  // Fillet tangent length and radius per interior vertex.
  std::vector<double> tangent(n, 0.0), radius(n, 0.0), angle(n, 0.0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double cosine = std::clamp(dir[i - 1].dot(dir[i]), -1.0, 1.0);
    const double theta = std::acos(cosine);
    if (theta < 1e-6) continue;
    if (theta > M_PI * 0.95) throw Error("simulator: the robot's route reverses on itself");
    const double half = std::tan(theta / 2);
    double l = robot.turn_radius * half;
    l = std::min({l, 0.5 * len[i - 1], 0.5 * len[i]});
    tangent[i] = l;
    radius[i] = l / half;
    angle[i] = theta;
  }
  std::vector<PathSample> out;
  auto push = [&](const Vector3d& p, double vmax) {
    PathSample sample;
    sample.p = p;
    sample.s = out.empty() ? 0.0 : out.back().s + (p - out.back().p).norm();
    sample.vmax = vmax;
    out.push_back(sample);
  };
  push(v[0].p, 0.0);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    // Straight part of segment j.
    const Vector3d a = v[j].p + tangent[j] * dir[j];
    const Vector3d b = v[j + 1].p - tangent[j + 1] * dir[j];
    const double straight = (b - a).norm();
    const int steps = std::max(1, static_cast<int>(std::ceil(straight / kPathStep)));
    for (int k = 1; k <= steps; ++k)
      push(k == steps ? b : Vector3d(a + (b - a) * (static_cast<double>(k) / steps)), v[j].speed);
    // Fillet at vertex j+1.
    const std::size_t i = j + 1;
    if (i + 1 >= n || tangent[i] <= 0.0) continue;
    const double r = radius[i], theta = angle[i];
    const Vector3d A = v[i].p - tangent[i] * dir[i - 1];
    const Vector3d towards =
        (dir[i] - dir[i - 1]).normalized();  // from A to the centre, scaled below
    // Centre: from A along the in-plane normal to dir[i-1].
    const Vector3d normal = (towards - towards.dot(dir[i - 1]) * dir[i - 1]).normalized();
    const Vector3d centre = A + r * normal;
    // Horizontal heading change of this fillet, for the yaw-rate limit.
    const Eigen::Vector2d h0 = dir[i - 1].head<2>(), h1 = dir[i].head<2>();
    double heading_change = 0.0;
    if (h0.norm() > 1e-6 && h1.norm() > 1e-6)
      heading_change = std::abs(std::atan2(h0.x() * h1.y() - h0.y() * h1.x(), h0.dot(h1)));
    const double arc = r * theta;
    double vmax = std::min(v[j].speed, v[i].speed);
    vmax = std::min(vmax, std::sqrt(robot.max_lateral_accel * r));
    if (heading_change > 1e-9) vmax = std::min(vmax, robot.max_yaw_rate * arc / heading_change);
    const int arc_steps = std::max(2, static_cast<int>(std::ceil(arc / kPathStep)));
    for (int k = 1; k <= arc_steps; ++k) {
      const double phi = theta * k / arc_steps;
      push(centre - r * std::cos(phi) * normal + r * std::sin(phi) * dir[i - 1], vmax);
    }
  }
  out.back().p = v.back().p;  // exactly the end vertex
  // Speed profile: limits, then acceleration forwards and backwards, zero at both ends.
  out.front().v = 0.0;
  for (std::size_t k = 1; k < out.size(); ++k) {
    const double ds = out[k].s - out[k - 1].s;
    out[k].v =
        std::min(out[k].vmax, std::sqrt(out[k - 1].v * out[k - 1].v + 2 * robot.max_accel * ds));
  }
  out.back().v = 0.0;
  for (std::size_t k = out.size() - 1; k-- > 0;) {
    const double ds = out[k + 1].s - out[k].s;
    out[k].v =
        std::min(out[k].v, std::sqrt(out[k + 1].v * out[k + 1].v + 2 * robot.max_accel * ds));
  }
  out.front().v = 0.0;
  for (std::size_t k = 1; k < out.size(); ++k) {
    const double ds = out[k].s - out[k - 1].s;
    out[k].t = out[k - 1].t + 2.0 * ds / std::max(out[k].v + out[k - 1].v, 1e-9);
  }
  return out;
}

}  // namespace

Trajectory::Trajectory(const std::vector<RouteVertex>& route, const RobotSpec& robot)
    : dt_(kControlInterval),
      still_time_(robot.still_time),
      motion_(robot.motion),
      gait_(robot.gait),
      handheld_gait_(robot.handheld_gait) {
  const std::vector<PathSample> path = densePath(route, robot);
  path_length_ = path.back().s;
  const double walk_time = path.back().t;
  // The walk starts after the still period plus the spline's half support, so
  // the body is exactly still on [0, still_time] and at the end.
  const double walk_start = still_time_ + 3.0 * dt_;
  const double walk_end = walk_start + walk_time;
  duration_ = walk_end + 3.0 * dt_ + still_time_;
  const int count = static_cast<int>(std::ceil(duration_ / dt_)) + 7;
  control_.reserve(count);

  auto heading = [&](std::size_t k) {
    const std::size_t a = std::min(k, path.size() - 2);
    return Vector3d(path[a + 1].p - path[a].p).normalized();
  };
  std::size_t cursor = 0;
  double yaw = 0.0;
  for (int k = 0; k < count; ++k) {
    const double tau = (k - 2) * dt_ - walk_start;  // time into the walk
    Vector3d p, d;
    double speed = 0.0;
    if (tau <= 0.0) {
      p = path.front().p;
      d = heading(0);
    } else if (tau >= walk_time) {
      p = path.back().p;
      d = heading(path.size() - 2);
    } else {
      while (cursor + 2 < path.size() && path[cursor + 1].t <= tau) ++cursor;
      const PathSample& a = path[cursor];
      const PathSample& b = path[cursor + 1];
      const double f = std::clamp((tau - a.t) / (b.t - a.t), 0.0, 1.0);
      p = a.p + f * (b.p - a.p);
      speed = a.v + f * (b.v - a.v);
      d = heading(cursor);
    }
    const double horizontal = d.head<2>().norm();
    const double target_yaw = std::atan2(d.y(), d.x());
    yaw = k == 0 ? target_yaw : yaw + wrapAngle(target_yaw - yaw);
    Channels c;
    c << p.x(), p.y(), p.z(), yaw, -std::atan2(d.z(), horizontal),
        smoothstep(speed / kGaitFullSpeed);
    control_.push_back(c);
  }
}

void Trajectory::evalSpline(double t, Channels& c, Channels& dc, Channels& ddc) const {
  const int n = static_cast<int>(control_.size());
  const double u = t / dt_ + 5.0;
  int i = std::clamp(static_cast<int>(std::floor(u)), 5, n - 1);
  const double f = u - i;
  // Piegl & Tiller A2.2 for uniform integer knots; keeps the degree 3 and 4 bases.
  double N[6] = {1, 0, 0, 0, 0, 0}, N3[4] = {}, N4[5] = {};
  for (int j = 1; j <= 5; ++j) {
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double left = f + (j - r) - 1.0, right = (r + 1) - f;
      const double temp = N[r] / j;
      N[r] = saved + right * temp;
      saved = left * temp;
    }
    N[j] = saved;
    if (j == 3) std::copy(N, N + 4, N3);
    if (j == 4) std::copy(N, N + 5, N4);
  }
  const Channels& ref = control_[i - 5];  // relative to one point: exact when all are equal
  c = ref;
  dc.setZero();
  ddc.setZero();
  for (int m = 0; m < 6; ++m) c += N[m] * (control_[i - 5 + m] - ref);
  for (int m = 0; m < 5; ++m) dc += N4[m] * (control_[i - 4 + m] - control_[i - 5 + m]);
  for (int m = 0; m < 4; ++m)
    ddc += N3[m] * (control_[i - 3 + m] - 2.0 * control_[i - 4 + m] + control_[i - 5 + m]);
  dc /= dt_;
  ddc /= dt_ * dt_;
}

FrameKinematics Trajectory::body(double t) const {
  t = std::clamp(t, 0.0, duration_);
  Channels c, dc, ddc;
  evalSpline(t, c, dc, ddc);
  return motion_ == RobotMotion::kHandheld ? handheld(t, c, dc, ddc) : legged(t, c, dc, ddc);
}

FrameKinematics Trajectory::legged(double t, const Channels& c, const Channels& dc,
                                   const Channels& ddc) const {
  const double omega = 2.0 * M_PI * gait_.frequency;
  double bz, dbz, ddbz, roll, droll, ddroll, gp, dgp, ddgp;
  gaitTerm(c[5], dc[5], ddc[5], gait_.bounce, omega, 0.0, t, bz, dbz, ddbz);
  gaitTerm(c[5], dc[5], ddc[5], gait_.roll, omega, 0.5 * M_PI, t, roll, droll, ddroll);
  gaitTerm(c[5], dc[5], ddc[5], gait_.pitch, omega, 0.25 * M_PI, t, gp, dgp, ddgp);

  const Vector3d p(c[0], c[1], c[2] + bz);
  const AxisRotation A(Vector3d::UnitZ(), c[3], dc[3], ddc[3]);
  const AxisRotation B(Vector3d::UnitY(), c[4] + gp, dc[4] + dgp, ddc[4] + ddgp);
  const AxisRotation C(Vector3d::UnitX(), roll, droll, ddroll);
  return composeKinematics(A, B, C, p, Vector3d(dc[0], dc[1], dc[2] + dbz),
                           Vector3d(ddc[0], ddc[1], ddc[2] + ddbz));
}

FrameKinematics Trajectory::handheld(double t, const Channels& c, const Channels& dc,
                                     const Channels& ddc) const {
  const HandheldGaitSpec& g = handheld_gait_;
  // Steps (bounce, pitch) at the step frequency; sway, roll and yaw once per
  // stride (two steps), swinging towards the stance foot.
  const double step = 2.0 * M_PI * g.frequency, stride = 0.5 * step;
  const double w = c[5], dw = dc[5], ddw = ddc[5];
  const Jet bounce = gaitJet(w, dw, ddw, g.bounce, step, 0.0, t);
  const Jet pitch = gaitJet(w, dw, ddw, g.pitch, step, 0.5 * M_PI, t);
  const Jet sway = gaitJet(w, dw, ddw, g.sway, stride, 0.0, t);
  const Jet roll = gaitJet(w, dw, ddw, g.roll, stride, 0.0, t);
  const Jet yaw = gaitJet(w, dw, ddw, g.yaw, stride, 0.5 * M_PI, t);

  // Sideways along the path's heading: o = H(yaw) e_y sway.
  const AxisRotation H(Vector3d::UnitZ(), c[3], dc[3], ddc[3]);
  const Vector3d e = H.R.col(1), de = H.dR.col(1), dde = H.ddR.col(1);
  const Vector3d o = e * sway.v;
  const Vector3d d_o = de * sway.v + e * sway.d;
  const Vector3d dd_o = dde * sway.v + 2.0 * de * sway.d + e * sway.dd;
  const Vector3d p = Vector3d(c[0], c[1], c[2] + bounce.v) + o;
  const Vector3d v = Vector3d(dc[0], dc[1], dc[2] + bounce.d) + d_o;
  const Vector3d a = Vector3d(ddc[0], ddc[1], ddc[2] + bounce.dd) + dd_o;

  const double k = g.slope_pitch;
  const AxisRotation A(Vector3d::UnitZ(), c[3] + yaw.v, dc[3] + yaw.d, ddc[3] + yaw.dd);
  const AxisRotation B(Vector3d::UnitY(), k * c[4] + pitch.v, k * dc[4] + pitch.d,
                       k * ddc[4] + pitch.dd);
  const AxisRotation C(Vector3d::UnitX(), roll.v, roll.d, roll.dd);
  return composeKinematics(A, B, C, p, v, a);
}

FrameKinematics Trajectory::frame(double t, const Pose& T_body_frame) const {
  const FrameKinematics b = body(t);
  const Matrix3d R_body_frame = T_body_frame.rotationMatrix();
  const Vector3d& lever = T_body_frame.translation();
  FrameKinematics f;
  f.T_world_frame = b.T_world_frame * T_body_frame;
  f.v_world = b.v_world + b.dR * lever;
  f.a_world = b.a_world + b.ddR * lever;
  f.dR = b.dR * R_body_frame;
  f.ddR = b.ddR * R_body_frame;
  f.omega_frame = R_body_frame.transpose() * b.omega_frame;
  return f;
}

Eigen::Vector3d specificForce(const FrameKinematics& k, double gravity) {
  return k.T_world_frame.rotation().conjugate() * (k.a_world + Vector3d(0.0, 0.0, gravity));
}

}  // namespace storey::sim
