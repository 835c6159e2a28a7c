#include "Inspect.h"

#include <ccHObject.h>
#include <ccPlane.h>
#include <ccPointCloud.h>
#include <ccScalarField.h>

#include <limits>

#include "Entities.h"
#include "PlanePatch.h"
#include "common/error.h"
#include "export/planes_json.h"

namespace storey::plugin {

namespace {

struct RunPlanes {
  std::vector<GlobalPlane> planes;
  Trajectory keyframes;
};

RunPlanes runPlanes(const ccHObject& group) {
  if (!group.hasMetaData(kMetaPlanesJson))
    throw Error("this Storey run has no SRPs (the back end was off)");
  return {parsePlanesJson(group.getMetaData(kMetaPlanesJson).toString().toStdString(),
                          "the run's planes")
              .planes,
          trajectoryFromText(group.getMetaData(kMetaKeyframes).toString())};
}

}  // namespace

std::size_t colourBySrp(ccPointCloud& cloud, double tolerance) {
  const ccHObject* group = findRunGroup(&cloud);
  if (group == nullptr) throw Error("the cloud is not part of a Storey run");
  const RunPlanes run = runPlanes(*group);
  std::vector<PlanePatch> patches;
  for (const GlobalPlane& p : run.planes) patches.push_back(planePatch(p, run.keyframes));

  int index = cloud.getScalarFieldIndexByName(kSfSrp);
  if (index < 0) index = cloud.addScalarField(kSfSrp);
  if (index < 0) throw Error("cannot add the scalar field srp");
  auto* sf = static_cast<ccScalarField*>(cloud.getScalarField(index));
  if (!sf->resizeSafe(cloud.size()) || !cloud.resizeTheRGBTable(false))
    throw Error("not enough memory to colour the cloud");

  std::size_t labelled = 0;
  for (unsigned i = 0; i < cloud.size(); ++i) {
    const CCVector3* p = cloud.getPoint(i);
    const Eigen::Vector3d x(p->x, p->y, p->z);
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < patches.size(); ++k) {
      if (!onPatch(patches[k], x, tolerance, 0.1)) continue;
      const double d = std::abs((x - patches[k].center).dot(patches[k].normal));
      if (d < best_distance) best_distance = d, best = run.planes[k].id;
    }
    sf->setValue(i, static_cast<ScalarType>(best));
    unsigned char rgb[3] = {150, 150, 150};
    if (best >= 0) {
      srpColour(best, rgb);
      ++labelled;
    }
    cloud.setPointColor(i, ccColor::Rgba(rgb[0], rgb[1], rgb[2], ccColor::MAX));
  }
  sf->computeMinAndMax();
  cloud.showSF(false);
  cloud.showColors(true);
  return labelled;
}

QStringList showPlanesOfKeyframe(ccHObject& run_group, int keyframe) {
  const RunPlanes run = runPlanes(run_group);
  ccHObject::Container planes;
  run_group.filterChildren(planes, true, CC_TYPES::PLANE, true);
  QStringList lines;
  if (keyframe >= static_cast<int>(run.keyframes.size()))
    throw Error("keyframe " + std::to_string(keyframe) + " out of range (the run has " +
                std::to_string(run.keyframes.size()) + ")");
  for (ccHObject* entity : planes) {
    if (!entity->hasMetaData(kMetaSrpId)) continue;
    const int id = entity->getMetaData(kMetaSrpId).toInt();
    bool seen = keyframe < 0;
    for (const GlobalPlane& p : run.planes) {
      if (p.id != id) continue;
      for (const PlaneObservation& o : p.observations) {
        if (o.keyframe != keyframe) continue;
        seen = true;
        lines << QString(
                     "SRP %1: %2 points, n = (%3, %4, %5), d = %6 m in the keyframe's LiDAR "
                     "frame, fit rms %7 m, chi2 %8%9")
                     .arg(id)
                     .arg(o.points)
                     .arg(o.normal_keyframe.x(), 0, 'f', 3)
                     .arg(o.normal_keyframe.y(), 0, 'f', 3)
                     .arg(o.normal_keyframe.z(), 0, 'f', 3)
                     .arg(o.distance_keyframe, 0, 'f', 3)
                     .arg(o.fit_rms, 0, 'f', 3)
                     .arg(o.residual_chi2, 0, 'f', 2)
                     .arg(o.outlier ? " (outlier)" : "");
      }
    }
    entity->setVisible(seen);
    if (keyframe >= 0 && seen) entity->setEnabled(true);  // a ceiling it saw is shown too
  }
  return lines;
}

int keyframeCount(const ccHObject& run_group) {
  return static_cast<int>(
      trajectoryFromText(run_group.getMetaData(kMetaKeyframes).toString()).size());
}

}  // namespace storey::plugin
