#pragma once
/// The command-line face inside CloudCompare:
///   CloudCompare -SILENT -STOREY_SLAM LOG [-STOREY_CONFIG FILE]
///                [-STOREY_CALIBRATION FILE] [-STOREY_OUT DIR] ...
/// After it, the map cloud and one cloud per storey are CloudCompare's
/// current clouds, so -C_EXPORT_FMT / -SAVE_CLOUDS and other commands apply.
#include <ccCommandLineInterface.h>

namespace storey::plugin {

class StoreyCommand : public ccCommandLineInterface::Command {
 public:
  StoreyCommand();
  bool process(ccCommandLineInterface& cmd) override;
};

}  // namespace storey::plugin
