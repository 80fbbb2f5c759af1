// libFuzzer's entry point for one target, chosen by TSR_FUZZ_BODY at build time.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  TSR_FUZZ_BODY(tsr::fuzz::Bytes(data, size));
  return 0;
}
