// Fuzz target: chart journals (`ltp chart --csv FILE --resume` reads FILE.journal, a file that a
// kill may have torn or a user may have damaged). Splits the bytes into records and decodes
// each as `--resume` does; every malformed record must be skipped, never read out of bounds.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "chart_journal.h"
#include "fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  ltp::fuzz::RefuseOnlyWithLtpErrors([&] {
    const size_t magic = sizeof(ltp::cli::kJournalMagic) - 1;
    const size_t from = bytes.compare(0, magic, ltp::cli::kJournalMagic) == 0 ? magic : 0;
    ltp::cli::PointReader reader;
    for (const std::string& payload : ltp::cli::FramedPayloads(bytes, from)) {
      (void)ltp::cli::DecodeHeader(payload);
      (void)reader.Read(payload);
    }
  });
  return 0;
}
