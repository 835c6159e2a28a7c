// The PLY reader of `storey eval` (eval/ply_reader.h): as a mesh and as points.
#include "eval/ply_reader.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string path = storey::fuzz::writeInputFile(data, size, "input.ply");
  storey::fuzz::expectOnlyStoreyErrors([&] { storey::eval::readPlyMesh(path, true); });
  storey::fuzz::expectOnlyStoreyErrors([&] { storey::eval::readPlyPoints(path); });
  return 0;
}
