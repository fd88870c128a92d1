// Fuzz target: time data for `ltp identify` — ltp's own CSV and a DAQ's export, read as
// `ltp identify FILE` reads them (the text goes through a file: the readers take paths), then
// identified (step-sine, or broadband when every record says so), with the first aux column as a
// tacho when there is one.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "daq_csv.h"
#include "fuzz_target.h"
#include "ltp/htf/identify.h"
#include "ltp/htf/rotor_angle.h"
#include "time_data_csv.h"
#include "uff58.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = "/tmp/ltp-fuzz-time-data-" + std::to_string(getpid()) + ".csv";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  ltp::fuzz::RefuseOnlyWithLtpErrors([&] {
    ltp::TimeData d;
    const bool ltp_format = ltp::cli::IsLtpTimeData(path);
    if (ltp_format) {
      d = ltp::cli::ReadTimeDataCsv(path, 0, false);
    } else if (ltp::cli::IsUffFile(path)) {
      const std::vector<ltp::cli::ChannelTable> t = ltp::cli::ReadUffTimeRecords(path);
      if (t.front().names.size() < 2) return;
      d = ltp::cli::TimeDataFromTables(t, "0", {"1"}, 0);
    } else {
      const ltp::cli::ChannelTable t = ltp::cli::ReadDaqCsv(path, 100);
      if (t.names.size() < 2) return;
      d = ltp::cli::TimeDataFromTables({t}, "0", {"1"}, 0);
    }
    if (!d.records.empty() && d.records[0].auxiliary.cols() > 0 && d.period == 0)
      ltp::SetMeasuredAngles(d, ltp::AngleChannel{});
    if (d.period == 0) d.period = 1;
    bool broadband = true;
    for (const ltp::TimeRecord& r : d.records) broadband = broadband && r.excitation_hz == 0;
    ltp::IdentifyOptions o;
    if (broadband && ltp_format)
      (void)ltp::IdentifyBroadband(d, o);
    else
      (void)ltp::IdentifyStepSine(d, o);
  });
  return 0;
}
