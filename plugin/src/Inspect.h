#pragma once
/// "Inspect SRPs": which map points lie on which global SRP, and which planes
/// a keyframe observed. Reads the planes and keyframes kept in the run group's
/// metadata, so it also works on a run saved as a .bin file and reopened.
#include <QStringList>
#include <cstddef>

class ccHObject;
class ccPointCloud;

namespace storey::plugin {

/// Adds (or refreshes) the scalar field "srp" of `cloud` (global SRP id, -1
/// = none: farther than `tolerance` from every SRP rectangle) and colours the
/// cloud with the SRP colours (grey elsewhere). Returns the points labelled.
/// Throws storey::Error when the cloud is not in a Storey run with SRPs.
std::size_t colourBySrp(ccPointCloud& cloud, double tolerance = 0.05);

/// Shows only the SRP planes of `run_group` observed from `keyframe` (all
/// when negative; unticked planes stay unticked then) and returns one line
/// per observation for the console.
QStringList showPlanesOfKeyframe(ccHObject& run_group, int keyframe);

/// Number of keyframes of a run group.
int keyframeCount(const ccHObject& run_group);

}  // namespace storey::plugin
