#include "Entities.h"

#include <ccHObject.h>
#include <ccPlane.h>
#include <ccPointCloud.h>
#include <ccPolyline.h>
#include <ccScalarField.h>

#include <QColor>
#include <QFileInfo>
#include <QStringList>
#include <QTextStream>
#include <cmath>
#include <cstdio>
#include <limits>

#include "common/error.h"
#include "export/planes_json.h"
#include "export/storey_files.h"

namespace storey::plugin {

namespace {

constexpr const char* kMetaRole = "storey.role";  ///< "map" | "storey" | "trajectory" | "planes"

ccScalarField* addField(ccPointCloud& cloud, const char* name, std::size_t n) {
  const int index = cloud.addScalarField(name);
  if (index < 0) throw Error(std::string("cannot add the scalar field ") + name);
  auto* sf = static_cast<ccScalarField*>(cloud.getScalarField(index));
  if (!sf->resizeSafe(n)) throw Error("not enough memory for the scalar fields");
  return sf;
}

const CCLib::ScalarField* field(const ccPointCloud& cloud, const char* name) {
  const int index = cloud.getScalarFieldIndexByName(name);
  if (index < 0)
    throw Error(QString("cloud '%1' has no scalar field '%2' (not a Storey cloud?)")
                    .arg(cloud.getName(), name)
                    .toStdString());
  return cloud.getScalarField(index);
}

double timeOrigin(const RunOutcome& outcome) {
  if (!outcome.result.trajectory.empty()) return outcome.result.trajectory.front().time;
  if (outcome.result.map && !outcome.result.map->time.empty())
    return outcome.result.map->time.front();
  return 0.0;
}

}  // namespace

ccPointCloud* toCloud(const MapCloud& map, const std::vector<std::uint32_t>* indices,
                      double time_origin, const QString& name) {
  const std::size_t n = indices ? indices->size() : map.size();
  auto cloud = std::make_unique<ccPointCloud>(name);
  if (!cloud->reserve(static_cast<unsigned>(n))) throw Error("not enough memory for the cloud");
  ccScalarField* intensity = addField(*cloud, kSfIntensity, n);
  ccScalarField* storey = addField(*cloud, kSfStorey, n);
  ccScalarField* time = addField(*cloud, kSfTime, n);
  ccScalarField* keyframe = addField(*cloud, kSfKeyframe, n);
  ccScalarField* flags = addField(*cloud, kSfFlags, n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = indices ? (*indices)[k] : k;
    const Eigen::Vector3f& p = map.positions[i];
    cloud->addPoint(CCVector3(p.x(), p.y(), p.z()));
    intensity->setValue(k, map.intensity[i]);
    storey->setValue(k, static_cast<ScalarType>(map.storey[i]));
    time->setValue(k, static_cast<ScalarType>(map.time[i] - time_origin));
    keyframe->setValue(k, static_cast<ScalarType>(map.keyframe[i]));
    flags->setValue(k, static_cast<ScalarType>(map.flags[i]));
  }
  for (ccScalarField* sf : {intensity, storey, time, keyframe, flags}) sf->computeMinAndMax();
  cloud->setMetaData(kMetaTimeOrigin, time_origin);
  cloud->setCurrentDisplayedScalarField(cloud->getScalarFieldIndexByName(kSfIntensity));
  cloud->showSF(true);
  return cloud.release();
}

MapCloud fromCloud(const ccPointCloud& cloud) {
  const CCLib::ScalarField* intensity = field(cloud, kSfIntensity);
  const CCLib::ScalarField* storey = field(cloud, kSfStorey);
  const CCLib::ScalarField* time = field(cloud, kSfTime);
  const int keyframe_index = cloud.getScalarFieldIndexByName(kSfKeyframe);
  const int flags_index = cloud.getScalarFieldIndexByName(kSfFlags);
  const double origin = cloud.getMetaData(kMetaTimeOrigin).toDouble();
  MapCloud map;
  const unsigned n = cloud.size();
  map.reserve(n);
  for (unsigned i = 0; i < n; ++i) {
    const CCVector3* p = cloud.getPoint(i);
    map.positions.emplace_back(p->x, p->y, p->z);
    map.intensity.push_back(intensity->getValue(i));
    map.storey.push_back(static_cast<std::int16_t>(std::lround(storey->getValue(i))));
    map.time.push_back(origin + static_cast<double>(time->getValue(i)));
    map.keyframe.push_back(keyframe_index < 0
                               ? -1
                               : static_cast<std::int32_t>(std::lround(
                                     cloud.getScalarField(keyframe_index)->getValue(i))));
    map.flags.push_back(flags_index < 0 ? 0
                                        : static_cast<std::uint8_t>(std::lround(
                                              cloud.getScalarField(flags_index)->getValue(i))));
  }
  return map;
}

ccPolyline* toPolyline(const Trajectory& trajectory, const QString& name) {
  auto* vertices = new ccPointCloud("vertices");
  vertices->reserve(static_cast<unsigned>(trajectory.size()));
  for (const StampedPose& s : trajectory) {
    const Eigen::Vector3d& t = s.pose.translation();
    vertices->addPoint(
        CCVector3(static_cast<float>(t.x()), static_cast<float>(t.y()), static_cast<float>(t.z())));
  }
  vertices->setEnabled(false);
  auto* polyline = new ccPolyline(vertices);
  if (!trajectory.empty()) polyline->addPointIndex(0, static_cast<unsigned>(trajectory.size()));
  polyline->setClosed(false);
  polyline->addChild(vertices);
  polyline->setName(name);
  polyline->setColor(ccColor::Rgb(255, 200, 0));
  polyline->showColors(true);
  polyline->setWidth(2);
  polyline->setMetaData(kMetaRole, "trajectory");
  return polyline;
}

void srpColour(int id, unsigned char rgb[3]) {
  const QColor c = QColor::fromHsv((id * 137 + 20) % 360, 190 + (id * 53) % 60, 230);
  rgb[0] = static_cast<unsigned char>(c.red());
  rgb[1] = static_cast<unsigned char>(c.green());
  rgb[2] = static_cast<unsigned char>(c.blue());
}

ccHObject* toPlaneEntities(const std::vector<GlobalPlane>& planes, const Trajectory& keyframes,
                           const QString& name) {
  auto* group = new ccHObject(name);
  group->setMetaData(kMetaRole, "planes");
  for (const GlobalPlane& plane : planes) {
    const PlanePatch patch = planePatch(plane, keyframes);
    auto f = [](const Eigen::Vector3d& v) {
      return CCVector3(static_cast<float>(v.x()), static_cast<float>(v.y()),
                       static_cast<float>(v.z()));
    };
    const ccGLMatrix pose(f(patch.u), f(patch.v), f(patch.normal), f(patch.center));
    const std::string kind = planeKind(plane, keyframes);
    auto* entity =
        new ccPlane(static_cast<PointCoordinateType>(patch.width),
                    static_cast<PointCoordinateType>(patch.height), &pose,
                    QString("SRP %1 (%2)").arg(plane.id).arg(QString::fromStdString(kind)));
    // Ceilings would hide the map seen from above: listed, unticked.
    if (kind == "ceiling") entity->setEnabled(false);
    unsigned char rgb[3];
    srpColour(plane.id, rgb);
    entity->setColor(ccColor::Rgb(rgb[0], rgb[1], rgb[2]));
    entity->showColors(true);
    entity->setMetaData(kMetaSrpId, plane.id);
    entity->setMetaData("storey.observations", static_cast<int>(plane.observations.size()));
    entity->setMetaData("storey.sized_from_hulls", patch.from_hulls);
    group->addChild(entity);
  }
  return group;
}

QString trajectoryToText(const Trajectory& trajectory) {
  QString text;
  QTextStream out(&text);
  out.setRealNumberPrecision(10);
  for (const StampedPose& s : trajectory) {
    const Eigen::Vector3d& t = s.pose.translation();
    const Eigen::Quaterniond& q = s.pose.rotation();
    out << qSetRealNumberPrecision(16) << s.time << ' ' << qSetRealNumberPrecision(10) << t.x()
        << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << ' '
        << q.w() << '\n';
  }
  return text;
}

Trajectory trajectoryFromText(const QString& text) {
  Trajectory trajectory;
  for (const QString& line : text.split('\n', Qt::SkipEmptyParts)) {
    const QStringList v = line.split(' ', Qt::SkipEmptyParts);
    if (v.size() != 8) continue;
    StampedPose s;
    s.time = v[0].toDouble();
    s.pose =
        Pose(Eigen::Quaterniond(v[7].toDouble(), v[4].toDouble(), v[5].toDouble(), v[6].toDouble()),
             Eigen::Vector3d(v[1].toDouble(), v[2].toDouble(), v[3].toDouble()));
    trajectory.push_back(s);
  }
  return trajectory;
}

RunEntities toRunEntities(const RunOutcome& outcome) {
  const PipelineResult& r = outcome.result;
  const QString stem = QFileInfo(QString::fromStdString(outcome.log_path)).completeBaseName();
  RunEntities e;
  e.group = new ccHObject(QString("Storey: %1").arg(stem));
  e.group->setMetaData(kMetaRun, QString::fromStdString(outcome.log_path));
  e.group->setMetaData(kMetaKeyframes, trajectoryToText(r.keyframes));
  if (r.planes)
    e.group->setMetaData(kMetaPlanesJson, QString::fromStdString(planesJsonText(*r.planes)));
  const double origin = timeOrigin(outcome);

  if (r.map) {
    e.map = toCloud(*r.map, nullptr, origin, QString("%1 map").arg(stem));
    e.map->setMetaData(kMetaRole, "map");
    // Coloured by storey when there are several, else by intensity.
    if (r.storeys.size() > 1)
      e.map->setCurrentDisplayedScalarField(e.map->getScalarFieldIndexByName(kSfStorey));
    e.group->addChild(e.map);
    auto* storeys = new ccHObject("storeys");
    for (const int s : storeyIndices(*r.map)) {
      const std::vector<std::uint32_t> indices = pointsOfStorey(*r.map, s);
      ccPointCloud* cloud = toCloud(*r.map, &indices, origin,
                                    QString("%1 storey %2").arg(stem).arg(s, 2, 10, QChar('0')));
      cloud->setMetaData(kMetaRole, "storey");
      cloud->setMetaData("storey.index", s);
      cloud->setEnabled(false);  // the map shows them all; switch one on to see it alone
      storeys->addChild(cloud);
      e.storeys.push_back(cloud);
    }
    if (storeys->getChildrenNumber() > 0)
      e.group->addChild(storeys);
    else
      delete storeys;
  }
  e.trajectory = toPolyline(r.trajectory, QString("%1 trajectory").arg(stem));
  e.group->addChild(e.trajectory);
  if (r.planes) {
    const std::vector<GlobalPlane>& planes = r.planes->planes;
    e.planes = toPlaneEntities(planes, r.keyframes, QString("SRPs (%1)").arg(planes.size()));
    e.group->addChild(e.planes);
  }
  return e;
}

ccHObject* findRunGroup(ccHObject* entity) {
  for (ccHObject* o = entity; o != nullptr; o = o->getParent())
    if (o->hasMetaData(kMetaRun)) return o;
  return nullptr;
}

ccPointCloud* findStoreyCloud(ccHObject* entity) {
  if (entity == nullptr) return nullptr;
  if (entity->isA(CC_TYPES::POINT_CLOUD)) {
    auto* cloud = static_cast<ccPointCloud*>(entity);
    if (cloud->getScalarFieldIndexByName(kSfStorey) >= 0) return cloud;
  }
  ccHObject* group = findRunGroup(entity);
  if (group == nullptr) return nullptr;
  ccHObject::Container clouds;
  group->filterChildren(clouds, true, CC_TYPES::POINT_CLOUD, true);
  for (ccHObject* c : clouds)
    if (c->getMetaData(kMetaRole).toString() == "map") return static_cast<ccPointCloud*>(c);
  return nullptr;
}

}  // namespace storey::plugin
