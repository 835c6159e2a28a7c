#pragma once
/// Conversions between the core's results and CloudCompare entities. The
/// only place that knows both sides.
#include <QString>
#include <cstdint>
#include <vector>

#include "PlanePatch.h"
#include "StoreyRun.h"

class ccHObject;
class ccPointCloud;
class ccPolyline;

namespace storey::plugin {

/// Scalar fields of Storey clouds (docs/plugin.md).
inline constexpr const char* kSfIntensity = "intensity";  ///< mean return intensity
inline constexpr const char* kSfStorey = "storey";        ///< storey index, -1 = none
inline constexpr const char* kSfTime = "time";          ///< first return [s] after the time origin
inline constexpr const char* kSfKeyframe = "keyframe";  ///< keyframe that first saw the point
inline constexpr const char* kSfFlags = "flags";        ///< 1 = stairs, 2 = floor (bits)
inline constexpr const char* kSfSrp = "srp";  ///< "Inspect SRPs": global SRP id, -1 = none

/// Metadata (kept in CloudCompare .bin files).
inline constexpr const char* kMetaRun = "storey.run";  ///< on the run group: the log's path
inline constexpr const char* kMetaPlanesJson = "storey.planes_json";   ///< on the run group
inline constexpr const char* kMetaKeyframes = "storey.keyframes_tum";  ///< on the run group
inline constexpr const char* kMetaTimeOrigin = "storey.time_origin";   ///< on clouds [s]
inline constexpr const char* kMetaSrpId = "storey.srp_id";             ///< on plane entities

/// A cloud of the points of `map` (all, or `indices`) with the scalar fields
/// above; `time` is stored as seconds after `time_origin` (CloudCompare's
/// scalars are floats).
ccPointCloud* toCloud(const MapCloud& map, const std::vector<std::uint32_t>* indices,
                      double time_origin, const QString& name);
/// The core's map back from a Storey cloud (positions and the five fields).
/// Throws storey::Error naming a missing scalar field.
MapCloud fromCloud(const ccPointCloud& cloud);

/// The trajectory as a polyline (its vertices as a hidden child cloud).
ccPolyline* toPolyline(const Trajectory& trajectory, const QString& name);
/// One ccPlane per global SRP, sized by planePatch(), coloured by srpColour(id).
ccHObject* toPlaneEntities(const std::vector<GlobalPlane>& planes, const Trajectory& keyframes,
                           const QString& name);
/// A distinct, stable colour per SRP id (golden-angle hues).
void srpColour(int id, unsigned char rgb[3]);

/// Everything a run brings into the DB tree, under `group`.
struct RunEntities {
  ccHObject* group = nullptr;
  ccPointCloud* map = nullptr;         ///< null when the map was off
  std::vector<ccPointCloud*> storeys;  ///< one per storey, bottom up
  ccPolyline* trajectory = nullptr;
  ccHObject* planes = nullptr;  ///< null when the back end was off
};
RunEntities toRunEntities(const RunOutcome& outcome);

/// The Storey run group holding `entity` (the entity itself or an ancestor), or null.
ccHObject* findRunGroup(ccHObject* entity);
/// A Storey map cloud: the selected entity, or the map cloud of its run group.
ccPointCloud* findStoreyCloud(ccHObject* entity);

/// Keyframes <-> TUM text (metadata of the run group).
QString trajectoryToText(const Trajectory& trajectory);
Trajectory trajectoryFromText(const QString& text);

}  // namespace storey::plugin
