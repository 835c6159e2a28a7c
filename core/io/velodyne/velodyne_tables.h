#pragma once
/// Laser tables and firing timing of the Velodyne sensors Storey decodes,
/// written from the manufacturers' manuals:
///   VLP-16 User Manual (63-9243), "Laser Firing Sequence Timing" and
///   "Vertical Angles": 16 lasers fired one every 2.304 us, a firing sequence
///   every 55.296 us, two sequences per data block (dual-firing blocks);
///   HDL-32E User's Manual (63-9113), Appendix A/B: 32 lasers fired one every
///   1.152 us, a firing sequence (one data block) every 46.080 us;
///   VLP-32C User Manual (63-9325), "Laser Firing Sequence Timing" and the
///   vertical-angle / azimuth-offset table: 32 lasers fired in pairs (laser
///   ids 2k and 2k + 1 together) every 2.304 us, a firing sequence (one data
///   block) every 55.296 us, distances in 4 mm steps.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace storey::velodyne {

enum class Model { kVlp16, kVlp32c, kHdl32e };
const char* toString(Model model);

/// Return mode byte (packet byte 1204) of data packets.
enum class ReturnMode : std::uint8_t {
  kStrongest = 0x37,
  kLast = 0x38,
  kDual = 0x39,
};
const char* toString(ReturnMode mode);

/// Product id byte (packet byte 1205). Early VLP-16 firmware sends 0x21 (HDL-32E)
/// or 0x00; the reader then tells the two models apart by the packet period.
inline constexpr std::uint8_t kProductHdl32e = 0x21;
inline constexpr std::uint8_t kProductVlp16 = 0x22;
inline constexpr std::uint8_t kProductVlp32c = 0x28;

inline constexpr std::size_t kDataPacketSize = 1206;  ///< UDP payload of a data packet [bytes]
inline constexpr std::size_t kPositionPacketSize =
    512;  ///< HDL-32E / VLP-16 position packet [bytes]
inline constexpr int kBlocksPerPacket = 12;
inline constexpr int kChannelsPerBlock = 32;
inline constexpr std::uint16_t kBlockFlag = 0xEEFF;  ///< 0xFF 0xEE read little-endian
inline constexpr std::uint16_t kDefaultDataPort = 2368;
inline constexpr std::uint16_t kDefaultPositionPort = 8308;

/// Timing constants from the manuals [s].
inline constexpr double kVlp16FiringS = 2.304e-6;      ///< between two lasers of a sequence
inline constexpr double kVlp16SequenceS = 55.296e-6;   ///< between two firing sequences
inline constexpr double kHdl32eFiringS = 1.152e-6;     ///< between two lasers
inline constexpr double kHdl32eSequenceS = 46.080e-6;  ///< between two data blocks
inline constexpr double kVlp32cFiringS = 2.304e-6;     ///< between two laser pairs of a sequence
inline constexpr double kVlp32cSequenceS = 55.296e-6;  ///< between two data blocks

/// One laser of a calibration.
struct Laser {
  double elevation_deg = 0.0;       ///< vertical angle [deg], positive up
  double azimuth_offset_deg = 0.0;  ///< rotational correction [deg], subtracted from the azimuth
  double distance_offset_m = 0.0;   ///< added to the measured distance [m]
  std::uint16_t ring = 0;           ///< rank by elevation, 0 = lowest
};

/// Laser table of a model: index = laser id (channel within a firing sequence).
struct Calibration {
  Model model = Model::kVlp16;
  std::vector<Laser> lasers;             ///< 16 (VLP-16) or 32 (VLP-32C, HDL-32E)
  double distance_resolution_m = 0.002;  ///< one distance LSB [m]
};

/// Lasers in one firing sequence of `model` (16 or 32).
int laserCount(Model model);
/// Firing time of laser `id` after the start of its firing sequence [s]
/// (VLP-16: id x 2.304 us; VLP-32C: (id / 2) x 2.304 us; HDL-32E: id x 1.152 us).
double laserFiringOffset(Model model, int id);
/// Between the starts of two firing sequences [s].
double sequencePeriod(Model model);

/// The manual's table for `model` (elevations as printed there, in degrees
/// with two decimals for the HDL-32E and three for the VLP-32C; the VLP-32C's
/// azimuth offsets, as VeloView's rotational corrections; no distance
/// corrections) and its distance step (VLP-32C 4 mm, the others 2 mm).
Calibration defaultCalibration(Model model);

/// Reads VeloView's calibration XML (boost serialization, `<DB>` with `points_`
/// items holding `vertCorrection_`, `rotCorrection_`, `distCorrection_` [cm],
/// and `distLSB_` [cm]) for `model`; only the first laserCount(model) lasers are used.
/// Throws storey::Error naming the file on a file that cannot be read or lacks them.
Calibration readVeloViewCalibration(const std::string& path, Model model);

/// The calibration a reader decodes `model` with: the VeloView XML at
/// `calibration_xml`, or the manual's table when it is empty.
Calibration calibrationFor(Model model, const std::string& calibration_xml);

/// Sets each laser's ring from the ranks of the elevations (0 = lowest).
void assignRings(Calibration& calibration);

}  // namespace storey::velodyne
