// planes.json (export/planes_json.h): parsed, then written back.
#include "export/planes_json.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string text(reinterpret_cast<const char*>(data), size);
  storey::fuzz::expectOnlyStoreyErrors([&] {
    const storey::PlaneMap planes = storey::parsePlanesJson(text, "planes.json");
    storey::planesJsonText(planes);
  });
  return 0;
}
