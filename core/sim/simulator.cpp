#include "sim/simulator.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <future>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/log.h"
#include "io/calibration_file.h"
#include "io/velodyne/frame_assembler.h"
#include "io/velodyne/velodyne_scan_decoder.h"
#include "sim/bag_writer.h"
#include "sim/imu_csv_writer.h"
#include "sim/imu_simulator.h"
#include "sim/lidar_simulator.h"
#include "sim/ros2_bag_writer.h"
#include "sim/velodyne_packet_builder.h"
#include "sim/velodyne_pcap_writer.h"
#include "sim/velodyne_scan_stream.h"
#include "sim/world.h"

namespace storey::sim {
namespace {

namespace fs = std::filesystem;

/// "sec.nanosec" of an absolute stamp, exact.
std::string stampText(std::int64_t ns) {
  char buffer[48];
  std::snprintf(buffer, sizeof(buffer), "%" PRId64 ".%09" PRId64, ns / 1000000000, ns % 1000000000);
  return buffer;
}

void writeTumLine(std::ostream& out, std::int64_t stamp_ns, const Pose& pose) {
  const Eigen::Vector3d& t = pose.translation();
  const Eigen::Quaterniond& q = pose.rotation();
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), " %.9f %.9f %.9f %.12f %.12f %.12f %.12f\n", t.x(), t.y(),
                t.z(), q.x(), q.y(), q.z(), q.w());
  out << stampText(stamp_ns) << buffer;
}

std::string numberText(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.6f", value);
  return buffer;
}

void writeStoreys(const std::string& path, const BuildingSpec& spec, const Building& building) {
  writeFileAtomically(path, [&](std::ostream& out) {
    out << "# Storey simulator ground truth: the storeys of the building.\n"
        << "# World frame: z up, origin at the LiDAR's start position. Metres.\n"
        << "# floor_z: top of the floor slab; ceiling_z: underside of the slab above.\n"
        << "building: " << spec.name << "\n"
        << "seed: " << spec.seed << "\n"
        << "storeys:\n";
    for (const StoreyTruth& s : building.storeys) {
      out << "  - index: " << s.index << "\n"
          << "    floor_z: " << numberText(s.floor_z) << "\n"
          << "    ceiling_z: " << numberText(s.ceiling_z) << "\n";
    }
  });
}

/// The true sensor set-up. With perfect sensors the spec's noise is still
/// reported: a pipeline needs non-zero weights. A log with Velodyne packets
/// (`velodyne_packets`: a capture or VelodyneScan topics) gets the cut angle
/// that decodes them into the point-cloud scans (kScanStartAzimuthDeg).
void writeCalibration(const std::string& path, const BuildingSpec& spec, bool packets,
                      bool velodyne_packets) {
  Calibration calibration;
  const SensorsSpec& s = spec.sensors;
  calibration.sensor.T_imu_lidar = s.T_body_imu.inverse() * s.T_body_lidar;
  calibration.sensor.time_offset_lidar_to_imu = 0.0;
  calibration.sensor.lidar_model = s.lidar.model;
  calibration.sensor.imu.rate_hz = s.imu.rate;
  calibration.sensor.imu.gravity = s.imu.gravity;
  calibration.sensor.imu.gyro_noise_density = s.imu.gyro_noise_density;
  calibration.sensor.imu.accel_noise_density = s.imu.accel_noise_density;
  calibration.sensor.imu.gyro_random_walk = s.imu.gyro_random_walk;
  calibration.sensor.imu.accel_random_walk = s.imu.accel_random_walk;
  calibration.points_topic = packets ? kPacketsTopic : s.points_topic;
  calibration.imu_topic = s.imu_topic;
  if (velodyne_packets) calibration.velodyne_cut_angle_deg = kScanStartAzimuthDeg;
  writeCalibrationFile(calibration, path);
}

/// A temporary sibling folder that is removed unless committed.
class StagingDir {
 public:
  explicit StagingDir(const fs::path& target) : target_(target) {
    const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::error_code ec;
    fs::create_directories(parent, ec);
    if (ec) throw Error(target.string() + ": cannot create the parent folder: " + ec.message());
    path_ = parent / ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid()));
    fs::remove_all(path_, ec);
    if (!fs::create_directory(path_, ec) || ec)
      throw Error(path_.string() + ": cannot create the temporary output folder: " + ec.message());
  }
  ~StagingDir() {
    std::error_code ec;
    if (!committed_) fs::remove_all(path_, ec);
  }
  std::string file(const char* name) const { return (path_ / name).string(); }

  /// Moves the files into the target folder (created when missing).
  void commit() {
    std::error_code ec;
    if (!fs::exists(target_, ec)) {
      fs::rename(path_, target_, ec);
      if (ec)
        throw Error(target_.string() +
                    ": cannot move the finished output into place: " + ec.message());
      committed_ = true;
      return;
    }
    if (!fs::is_directory(target_, ec))
      throw Error(target_.string() + ": exists and is not a folder");
    for (const auto& entry : fs::directory_iterator(path_)) {
      // A folder (the ROS 2 bag's) replaces the one of an earlier simulation:
      // rename() moves a file over a file, not a folder over a non-empty one.
      const fs::path destination = target_ / entry.path().filename();
      if (entry.is_directory() && fs::is_directory(destination, ec))
        fs::remove_all(destination, ec);
      fs::rename(entry.path(), destination, ec);
      if (ec) throw Error(destination.string() + ": cannot move into place: " + ec.message());
    }
    fs::remove_all(path_, ec);
    committed_ = true;
  }

 private:
  fs::path target_, path_;
  bool committed_ = false;
};

void report(const ProgressFn& progress, double fraction, const std::string& stage) {
  if (progress && !progress(std::clamp(fraction, 0.0, 1.0), stage)) throw Cancelled();
}

}  // namespace

SimulationResult simulate(const BuildingSpec& spec, const SimulationOptions& options,
                          const std::string& out_dir, const ProgressFn& progress) {
  const auto wall_start = std::chrono::steady_clock::now();
  spec.validate();
  if (out_dir.empty()) throw Error("simulator: no output folder given");
  const SimulationFormats& formats = options.formats;
  if (!formats.bag && !formats.pcap && formats.ros2 == Ros2Format::kNone)
    throw Error("simulator: no log format chosen (a ROS1 bag, a ROS 2 bag or a pcap)");
  if ((formats.pcap || formats.packets) && !velodyneModel(spec.sensors.lidar.model)) {
    throw Error(spec.source + ": " +
                (formats.pcap ? "a Velodyne capture (pcap)" : "Velodyne packets (--packets)") +
                " needs a Velodyne LiDAR (VLP-16, VLP-32C, HDL-32E); sensors.lidar.model is " +
                toString(spec.sensors.lidar.model));
  }
  if (formats.packets && !formats.bag && formats.ros2 == Ros2Format::kNone) {
    throw Error("simulator: Velodyne packets go into a bag: write a ROS1 or a ROS 2 bag");
  }
  report(progress, 0.0, "building");
  const World world = makeWorld(spec);
  const Trajectory& trajectory = world.trajectory;
  const SensorsSpec& sensors = spec.sensors;

  SimulationResult result;
  result.out_dir = out_dir;
  result.walk_duration = trajectory.duration();
  result.duration = options.max_duration > 0.0
                        ? std::min(options.max_duration, trajectory.duration())
                        : trajectory.duration();
  result.path_length = trajectory.pathLength();
  result.triangles = world.building.mesh.triangles().size();
  result.storeys = static_cast<int>(world.building.storeys.size());
  const std::int64_t start_ns = static_cast<std::int64_t>(std::llround(sensors.start_time * 1e9));
  if (!(options.start_at >= 0.0) || options.start_at >= result.duration)
    throw Error("simulator: start_at (" + std::to_string(options.start_at) +
                " s) must be at least 0 and before the end of the log (" +
                std::to_string(result.duration) + " s)");
  // Logs cut to start at options.start_at: nothing measured before it is written.
  const std::int64_t cut_ns = static_cast<std::int64_t>(std::llround(options.start_at * 1e9));

  StagingDir staging(out_dir);
  world.building.mesh.writePly(staging.file(kMeshFile));
  writeStoreys(staging.file(kStoreysFile), spec, world.building);
  writeCalibration(staging.file(kCalibrationFile), spec, formats.packets,
                   formats.packets || formats.pcap);
  // Where the calibration's cut angle makes a reader start the packets' frames.
  const int cut_azimuth = velodyne::cutAzimuth(kScanStartAzimuthDeg);
  writeFileAtomically(staging.file(kSpecFile), buildingSpecYaml(spec));

  report(progress, 0.0, "IMU");
  const ImuSimulation imu =
      simulateImu(trajectory, sensors, result.duration, options.perfect_sensors, spec.seed);
  result.imu_samples = std::count_if(imu.samples.begin(), imu.samples.end(),
                                     [&](const ImuSample& s) { return s.stamp_ns >= cut_ns; });
  // Faults: which samples the logs leave out or hold as full-range readings.
  std::vector<double> imu_stamps(imu.samples.size());
  for (std::size_t i = 0; i < imu.samples.size(); ++i)
    imu_stamps[i] = imu.samples[i].stamp_ns * 1e-9;
  const SampleFaults imu_faults = imuSampleFaults(options.faults, imu_stamps);
  auto loggedImu = [&](std::size_t i, ImuSample& sample) {
    if (imu_faults.drop[i] || imu.samples[i].stamp_ns < cut_ns) return false;
    sample = imu.samples[i];
    if (imu_faults.spike[i]) {
      sample.gyro = Eigen::Vector3d(kSpikeGyro, -kSpikeGyro, kSpikeGyro);
      sample.accel = Eigen::Vector3d(kSpikeAccel, -kSpikeAccel, kSpikeAccel);
    }
    if (imu_faults.saturate[i]) {
      sample.gyro.x() = kSpikeGyro;
      sample.accel.z() = kSpikeAccel;
    }
    if (imu_faults.nan[i]) sample.gyro.setConstant(std::numeric_limits<double>::quiet_NaN());
    sample.stamp_ns += imu_faults.shift_ns[i];  // the record time stays imu.samples[i]'s
    return true;
  };
  const bool lidar_gaps = hasFault(options.faults, SimFaultKind::kLidarGap);
  const bool occlusions = hasFault(options.faults, SimFaultKind::kOcclusion);
  const bool lidar_jumps = hasFault(options.faults, SimFaultKind::kLidarClockJump);
  const bool duplicates = hasFault(options.faults, SimFaultKind::kDuplicate);
  const bool nan_points = hasFault(options.faults, SimFaultKind::kNan);
  for (const auto& [kind, name] : {std::pair{SimFaultKind::kLidarGap, "lidar_gap"},
                                   {SimFaultKind::kOcclusion, "occlusion"},
                                   {SimFaultKind::kLidarClockJump, "lidar_clock_jump"},
                                   {SimFaultKind::kDuplicate, "duplicate"},
                                   {SimFaultKind::kReorder, "reorder"},
                                   {SimFaultKind::kNan, "nan"}}) {
    if (hasFault(options.faults, kind) && (formats.pcap || formats.packets))
      throw Error(std::string("--fault ") + name +
                  ": only for point clouds (not with --pcap or --packets)");
  }
  if (hasFault(options.faults, SimFaultKind::kImuClockJump) && formats.pcap)
    throw Error("--fault imu_clock_jump: only for bags (an IMU CSV has no record times)");
  writeFileAtomically(staging.file(kImuTruthFile), [&](std::ostream& out) {
    out << "# timestamp x y z qx qy qz qw (IMU frame in the world frame)\n";
    for (std::size_t i = 0; i < imu.samples.size(); ++i)
      if (imu.samples[i].stamp_ns >= cut_ns)
        writeTumLine(out, start_ns + imu.samples[i].stamp_ns, imu.T_world_imu[i]);
  });

  LidarNoise noise;
  if (!options.perfect_sensors) {
    noise.range_sigma = sensors.lidar.range_noise;
    noise.dropout = sensors.lidar.dropout;
    noise.intensity_sigma = sensors.lidar.intensity_noise;
    noise.quantize = true;
  }
  const LidarSimulator lidar(world.building.mesh, trajectory, sensors, noise, spec.seed);
  if ((occlusions || lidar_jumps || duplicates || nan_points) &&
      lidar.beams().layout == CloudLayout::kOuster)
    throw Error(
        "--fault occlusion, lidar_clock_jump, duplicate and nan: only for Velodyne-layout point "
        "clouds (not the Ouster layout)");
  const int scan_count = lidar.scanCount(result.duration);

  if (options.formats.pcap) {
    std::vector<ImuSample> logged;
    logged.reserve(imu.samples.size());
    for (std::size_t i = 0; i < imu.samples.size(); ++i) {
      ImuSample sample;
      if (loggedImu(i, sample)) logged.push_back(sample);
    }
    writeImuCsv(
        staging.file(kImuCsvFile), logged, start_ns,
        {"Storey simulator: IMU samples of " + spec.name + " (seed " + std::to_string(spec.seed) +
             "), the clock of " + std::string(kPcapFile),
         "time [s]; gyro [rad/s]; accel [m/s^2] (specific force, +g up at rest); IMU frame"});
  }
  std::vector<std::unique_ptr<SimLogWriter>> logs;
  if (formats.bag) {
    logs.push_back(std::make_unique<BagWriter>(
        staging.file(kBagFile), options.compress ? BagCompression::kLz4 : BagCompression::kNone));
  }
  if (formats.ros2 != Ros2Format::kNone) {
    McapWriterOptions mcap;
    mcap.compression = formats.mcap_compression;
    logs.push_back(std::make_unique<Ros2BagWriter>(
        staging.file(kRos2BagDir),
        formats.ros2 == Ros2Format::kDb3 ? Ros2Storage::kSqlite3 : Ros2Storage::kMcap, mcap));
  }
  const bool bag = !logs.empty();
  const bool organised = lidar.beams().layout == CloudLayout::kOuster;
  // A Velodyne LiDAR in a bag: its packets in VelodyneScan messages, written
  // as they are (formats.packets) or as the point clouds the driver decodes
  // from them (velodyne_scan_stream.h), so the two bags carry the same points.
  std::unique_ptr<VelodyneScanStream> velodyne_stream;
  std::unique_ptr<VelodyneScanDecoder> velodyne_driver;
  if (bag && !organised) {
    velodyne_stream = std::make_unique<VelodyneScanStream>(
        start_ns, sensors.lidar.rotation_rate, *velodyneModel(sensors.lidar.model),
        sensors.lidar_frame_id, kPacketsTopic, cut_azimuth);
    if (!formats.packets) {
      VelodyneScanOptions driver;
      driver.model = *velodyneModel(sensors.lidar.model);
      driver.cut_angle_deg = kScanStartAzimuthDeg;
      velodyne_driver = std::make_unique<VelodyneScanDecoder>("simulator: Velodyne driver", driver);
    }
  }
  std::unique_ptr<VelodynePcapWriter> pcap;
  if (options.formats.pcap) {
    pcap = std::make_unique<VelodynePcapWriter>(staging.file(kPcapFile), start_ns,
                                                sensors.lidar.rotation_rate,
                                                *velodyneModel(sensors.lidar.model), cut_azimuth);
  }
  const double gyro_variance = std::pow(sensors.imu.gyro_noise_density, 2) * sensors.imu.rate;
  const double accel_variance = std::pow(sensors.imu.accel_noise_density, 2) * sensors.imu.rate;
  std::size_t next_imu = 0;
  // A sample recorded after the next one (--fault reorder) waits here.
  struct HeldImu {
    ImuSample sample;
    ImuOrientation orientation;
  };
  std::optional<HeldImu> held_imu;
  auto recordImu = [&](const ImuSample& sample, const ImuOrientation& orientation,
                       std::int64_t record_ns) {
    for (auto& log : logs) {
      log->writeImu(sensors.imu_topic, sensors.imu_frame_id, sample, record_ns, gyro_variance,
                    accel_variance, sensors.imu.orientation ? &orientation : nullptr);
    }
  };
  auto writeImuUntil = [&](std::int64_t t_ns) {
    if (!bag) return;
    while (next_imu < imu.samples.size() && imu.samples[next_imu].stamp_ns <= t_ns) {
      ImuOrientation orientation;
      if (sensors.imu.orientation) {
        orientation.q_world_imu = imu.T_world_imu[next_imu].rotation();
        orientation.variance = sensors.imu.orientation_sigma.cwiseAbs2();
      }
      ImuSample sample;
      const std::size_t i = next_imu++;
      const std::int64_t record_ns = start_ns + imu.samples[i].stamp_ns;
      if (!loggedImu(i, sample)) continue;
      sample.stamp_ns += start_ns;
      if (imu_faults.late[i] && !held_imu) {
        held_imu = HeldImu{sample, orientation};
        continue;
      }
      for (int copy = 0; copy < (imu_faults.duplicate[i] ? 2 : 1); ++copy)
        recordImu(sample, orientation, record_ns);
      if (held_imu) {  // recorded now, after the sample that follows it
        recordImu(held_imu->sample, held_imu->orientation, record_ns);
        held_imu.reset();
      }
    }
  };
  std::ostringstream lidar_truth;
  lidar_truth
      << "# timestamp x y z qx qy qz qw (LiDAR frame in the world frame, at each scan's stamp)\n";
  // The LiDAR's true pose at an absolute stamp, as a TUM line.
  auto writeLidarTruth = [&](std::ostream& out, std::int64_t stamp_ns) {
    writeTumLine(
        out, stamp_ns,
        trajectory.frame((stamp_ns - start_ns) * 1e-9, sensors.T_body_lidar).T_world_frame);
  };
  // A scan of the log: its truth and its counts.
  auto countScan = [&](const Scan& scan) {
    writeLidarTruth(lidar_truth, scan.stamp_ns);
    ++result.scans;
    result.points += static_cast<std::int64_t>(scan.points.size());
  };
  // One point cloud into the bags, with the LiDAR faults of its time
  // (`organised`: the Ouster layout's scan, else the Velodyne layout's).
  auto writeCloud = [&](Scan& scan, std::int64_t record_ns, const OrganisedScan* organised_scan) {
    countScan(scan);
    const double scan_time = (scan.stamp_ns - start_ns) * 1e-9;
    if (lidar_gaps && inLidarGap(options.faults, scan_time)) return;
    if (occlusions && inOcclusion(options.faults, scan_time)) {
      // A body in front of the sensor: the rays of the forward sector end on it.
      for (ScanPoint& point : scan.points) {
        const float range = point.p.norm();
        if (range > 0.0f && std::abs(std::atan2(point.p.y(), point.p.x())) <= kOcclusionHalfSector)
          point.p *= kOcclusionRange / range;
      }
    }
    if (lidar_jumps) scan.stamp_ns += lidarClockShiftNs(options.faults, scan_time);
    if (nan_points && inFault(options.faults, SimFaultKind::kNan, scan_time)) {
      for (std::size_t p = 0; p < scan.points.size(); p += 20)
        scan.points[p].p.setConstant(std::numeric_limits<float>::quiet_NaN());
    }
    const int copies =
        duplicates && inFault(options.faults, SimFaultKind::kDuplicate, scan_time) ? 2 : 1;
    for (auto& log : logs) {
      for (int copy = 0; copy < copies; ++copy) {
        if (organised_scan != nullptr) {
          log->writeOrganisedScan(sensors.points_topic, scan.frame_id, *organised_scan,
                                  scan.stamp_ns, record_ns);
        } else {
          log->writeScan(sensors.points_topic, scan, record_ns);
        }
      }
    }
  };
  // The Velodyne messages completed so far: written as packets, or decoded
  // into the driver's clouds, each recorded with the message that completes it.
  std::vector<VelodyneScanMessage> velodyne_messages;
  std::vector<Scan> driver_clouds;
  std::map<std::string, std::int64_t> driver_dropped;
  std::int64_t last_message_ns = 0;
  auto writeDriverClouds = [&](std::int64_t record_ns) {
    for (Scan& cloud : driver_clouds) {
      cloud.frame_id = sensors.lidar_frame_id;
      writeCloud(cloud, record_ns, nullptr);
    }
  };
  auto writeVelodyneMessages = [&]() {
    for (const VelodyneScanMessage& message : velodyne_messages) {
      writeImuUntil(message.stamp_ns - start_ns);
      last_message_ns = message.stamp_ns;
      if (!velodyne_driver) {
        for (auto& log : logs) log->writeVelodyneScan(kPacketsTopic, message, message.stamp_ns);
        continue;
      }
      driver_clouds.clear();
      velodyne_driver->add(message, driver_clouds, driver_dropped);
      writeDriverClouds(message.stamp_ns);
    }
    velodyne_messages.clear();
  };

  const int threads =
      options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  const int chunk = std::max(8, 4 * threads);
  // Ray-cast the next chunk of scans while this thread writes the previous one.
  struct Chunk {
    std::vector<Scan> scans;
    std::vector<std::vector<VelodyneFiring>> firings;  ///< per scan, for the pcap
    std::vector<OrganisedScan> organised;              ///< per scan, Ouster layout
  };
  const bool want_firings = pcap != nullptr || velodyne_stream != nullptr;
  const bool want_organised = organised && bag;
  auto castChunk = [&](int first) {
    Chunk out;
    const auto size = static_cast<std::size_t>(std::max(0, std::min(chunk, scan_count - first)));
    out.scans.resize(size);
    if (want_firings) out.firings.resize(size);
    if (want_organised) out.organised.resize(size);
    arena.execute([&] {
      tbb::parallel_for(0, static_cast<int>(size), [&](int i) {
        out.scans[i] = lidar.simulateScan(first + i, want_firings ? &out.firings[i] : nullptr,
                                          want_organised ? &out.organised[i] : nullptr);
      });
    });
    return out;
  };
  std::future<Chunk> pending = std::async(std::launch::async, castChunk, 0);
  for (int first = 0; first < scan_count; first += chunk) {
    report(progress, static_cast<double>(first) / std::max(1, scan_count), "ray-casting scans");
    Chunk cast = pending.get();
    std::vector<Scan>& scans = cast.scans;
    if (first + chunk < scan_count)
      pending = std::async(std::launch::async, castChunk, first + chunk);
    for (std::size_t i = 0; i < scans.size(); ++i) {
      Scan& scan = scans[i];
      const int n = first + static_cast<int>(i);
      const std::int64_t receipt_ns = lidar.scanEndNs(n);
      writeImuUntil(receipt_ns);
      if (scan.stamp_ns < cut_ns) continue;  // before the cut (--start-at)
      scan.stamp_ns += start_ns;
      if (organised && bag) {
        writeCloud(scan, start_ns + receipt_ns, &cast.organised[i]);
      } else if (!velodyne_driver) {  // packets or a capture: the truth at the scans' stamps
        countScan(scan);
      }
      if (pcap) {
        for (const VelodyneFiring& firing : cast.firings[i]) pcap->add(firing);
      }
      if (velodyne_stream) {
        for (const VelodyneFiring& firing : cast.firings[i])
          velodyne_stream->add(firing, velodyne_messages);
        writeVelodyneMessages();
      }
    }
  }
  if (velodyne_stream) {
    velodyne_stream->finish(velodyne_messages);
    writeVelodyneMessages();
    if (velodyne_driver) {
      driver_clouds.clear();
      velodyne_driver->flush(driver_clouds);
      // The last frame, recorded with the last message (its packet completed by no-returns).
      writeDriverClouds(last_message_ns);
    }
  }
  writeImuUntil(INT64_MAX / 2);
  if (held_imu)
    recordImu(held_imu->sample, held_imu->orientation, start_ns + held_imu->sample.stamp_ns);
  report(progress, 1.0, bag ? "writing the bag" : "writing the capture");
  for (auto& log : logs) log->close();
  if (pcap) {
    pcap->close();
    result.pcap_packets = pcap->packets();
  }
  if (pcap || formats.packets) {
    const std::vector<std::int64_t>& frame_starts =
        pcap ? pcap->frameStarts() : velodyne_stream->frameStarts();
    // The packets' frames (cut at the calibration's angle) start at a block
    // boundary, within one firing sequence of a scan's stamp (a VLP-16 block
    // holds two; the block azimuth is rounded to 0.01 deg): their own ground
    // truth, at their stamps.
    writeFileAtomically(staging.file(kPcapLidarTruthFile), [&](std::ostream& out) {
      out << "# timestamp x y z qx qy qz qw (LiDAR frame in the world frame, at the stamp of each "
             "frame of "
          << kPcapFile << ")\n";
      for (const std::int64_t t_ns : frame_starts) writeLidarTruth(out, t_ns);
    });
  }
  writeFileAtomically(staging.file(kLidarTruthFile), lidar_truth.str());
  staging.commit();
  result.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace storey::sim
