#include "imu/imu_pose_table.h"

#include <algorithm>
#include <utility>

#include "common/error.h"
#include "imu/so3.h"

namespace storey {

ImuPoseTable::ImuPoseTable(const ImuState& start, ImuSignal signal, double gravity)
    : start_ns_(signal.start_ns),
      end_ns_(signal.end_ns),
      bias_(start.bias),
      gravity_world_(gravityWorld(gravity)) {
  if (start.stamp_ns != signal.start_ns) {
    throw Error("ImuPoseTable: the start state's stamp must be the IMU signal's start");
  }
  const std::vector<ImuKnot>& in = signal.knots;
  if (in.size() < 2) throw Error("ImuPoseTable needs at least two IMU knots");
  knots_.resize(in.size());
  Knot& first = knots_[0];
  first.t = in[0].t;
  first.q = start.T_world_imu.rotation();
  first.p = start.T_world_imu.translation();
  first.v = start.v_world_imu;
  first.w = in[0].gyro - bias_.gyro;
  Eigen::Matrix3d R0 = first.q.toRotationMatrix();
  for (std::size_t k = 0; k + 1 < in.size(); ++k) {
    const Knot& k0 = knots_[k];
    Knot& k1 = knots_[k + 1];
    const double dt = in[k + 1].t - in[k].t;
    if (!(dt > 0.0)) throw Error("ImuPoseTable: IMU knot times must increase strictly");
    k1.t = in[k + 1].t;
    k1.w = in[k + 1].gyro - bias_.gyro;
    k1.q = (k0.q * so3::expQuaternion(0.5 * dt * (k0.w + k1.w))).normalized();
    const Eigen::Matrix3d R1 = k1.q.toRotationMatrix();
    const Eigen::Vector3d f0 = R0 * (in[k].accel - bias_.accel);
    const Eigen::Vector3d f1 = R1 * (in[k + 1].accel - bias_.accel);
    k1.p = k0.p + k0.v * dt + 0.5 * dt * dt * gravity_world_ + dt * dt / 6.0 * (2.0 * f0 + f1);
    k1.v = k0.v + gravity_world_ * dt + 0.5 * dt * (f0 + f1);
    R0 = R1;
  }
  knots_per_second_ = static_cast<double>(knots_.size() - 1) / knots_.back().t;
}

ImuPoseTable ImuPoseTable::fromSamples(const ImuState& start, const std::vector<ImuSample>& samples,
                                       std::int64_t end_ns, double gravity) {
  return ImuPoseTable(start, sliceImuSignal(samples, start.stamp_ns, end_ns), gravity);
}

std::size_t ImuPoseTable::intervalOf(double t) const {
  const std::size_t last = knots_.size() - 2;  // index of the last interval
  const double guess = t * knots_per_second_;
  std::size_t k = guess <= 0.0 ? 0 : std::min(last, static_cast<std::size_t>(guess));
  while (k > 0 && t < knots_[k].t) --k;
  while (k < last && t >= knots_[k + 1].t) ++k;
  return k;
}

void ImuPoseTable::interpolate(double t, Eigen::Quaterniond& q_world_imu,
                               Eigen::Vector3d& p_world_imu) const {
  if (t <= 0.0 || t >= knots_.back().t) {  // constant-velocity extrapolation (exact at the ends)
    const Knot& end = t <= 0.0 ? knots_.front() : knots_.back();
    const double tau = t - end.t;
    q_world_imu = end.q * so3::expQuaternion(end.w * tau);
    p_world_imu = end.p + end.v * tau;
    return;
  }
  const std::size_t k = intervalOf(t);
  const Knot& a = knots_[k];
  const Knot& b = knots_[k + 1];
  const double h = b.t - a.t;
  const double tau = t - a.t;
  const double s = tau / h;
  q_world_imu = a.q * so3::expQuaternion(tau * a.w + (0.5 * tau * s) * (b.w - a.w));
  // Cubic Hermite basis.
  const double s2 = s * s;
  const double s3 = s2 * s;
  const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
  const double h10 = (s3 - 2.0 * s2 + s) * h;
  const double h01 = 1.0 - h00;
  const double h11 = (s3 - s2) * h;
  p_world_imu = h00 * a.p + h10 * a.v + h01 * b.p + h11 * b.v;
}

Pose ImuPoseTable::T_world_imu(double t) const {
  Eigen::Quaterniond q;
  Eigen::Vector3d p;
  interpolate(t, q, p);
  return Pose(q, p);
}

ImuState ImuPoseTable::stateAt(double t) const {
  ImuState out;
  out.stamp_ns = start_ns_ + secondsToNs(t);
  out.T_world_imu = T_world_imu(t);
  out.bias = bias_;
  if (t <= 0.0 || t >= knots_.back().t) {
    out.v_world_imu = (t <= 0.0 ? knots_.front() : knots_.back()).v;
    return out;
  }
  const std::size_t k = intervalOf(t);
  const Knot& a = knots_[k];
  const Knot& b = knots_[k + 1];
  const double h = b.t - a.t;
  const double s = (t - a.t) / h;
  // Derivative of the Hermite cubic.
  const double dh00 = 6.0 * s * s - 6.0 * s;
  const double dh10 = 3.0 * s * s - 4.0 * s + 1.0;
  const double dh11 = 3.0 * s * s - 2.0 * s;
  out.v_world_imu = dh00 / h * (a.p - b.p) + dh10 * a.v + dh11 * b.v;
  return out;
}

ImuState ImuPoseTable::stateAtKnot(std::size_t k) const {
  ImuState out;
  out.stamp_ns = k + 1 == knots_.size() ? end_ns_ : start_ns_ + secondsToNs(knots_[k].t);
  out.T_world_imu = Pose(knots_[k].q, knots_[k].p);
  out.v_world_imu = knots_[k].v;
  out.bias = bias_;
  return out;
}

}  // namespace storey
