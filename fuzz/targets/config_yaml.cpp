// The configuration YAML (config/config.h): applied over the defaults as
// loadConfig does, validated, and written back.
#include "config/config.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  storey::fuzz::quietLogs();
  const std::string text(reinterpret_cast<const char*>(data), size);
  storey::fuzz::expectOnlyStoreyErrors([&] {
    storey::Config config;
    storey::applyConfigYaml(config, text, "fuzz.yaml");
    config.validate();
    storey::configToYaml(config);
  });
  return 0;
}
