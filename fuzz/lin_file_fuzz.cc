// Fuzz target: OpenFAST .lin files. Parses the text and, when it parses, builds the operating
// point from it as `ltp mbc` / `ltp floquet` on one file would (header, tables and matrix sizes
// must agree, every entry finite).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_target.h"
#include "ltp/openfast/linearization.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  ltp::fuzz::RefuseOnlyWithLtpErrors([&] {
    ltp::LinFile file = ltp::ParseLinFile(text, "fuzz.lin");
    std::vector<ltp::LinFile> files;
    files.push_back(std::move(file));
    (void)ltp::MakeLinOperatingPoint(std::move(files));
  });
  return 0;
}
