// storeys.json (export/storeys_json.h): parsed, then written back.
#include "export/storeys_json.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string text(reinterpret_cast<const char*>(data), size);
  storey::fuzz::expectOnlyStoreyErrors([&] {
    const auto storeys = storey::parseStoreysJson(text, "storeys.json");
    storey::storeysJson(storeys, 0.05);
  });
  return 0;
}
