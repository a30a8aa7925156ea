// libFuzzer's entry point for one harness, chosen at build time by GLINT_FUZZ_TARGET.
#include "harnesses.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    GLINT_FUZZ_TARGET(data, size);
    return 0;
}
