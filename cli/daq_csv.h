#pragma once
// Time records as a data-acquisition system exports them: one record per file, a header of
// channel names (units in brackets or parentheses allowed: "Force [N]"), a time column or a
// sample rate, separated by commas, semicolons (then a decimal comma is read too) or tabs:
//
//   Time [s];Force [N];Accel [m/s^2];Tacho [V]
//   0,000000;0,1234;-0,0021;0,01
//
// Lines before the header that hold no numbers (a DAQ's preamble) and lines starting with '#'
// or '%' are skipped. `ltp identify A.csv B.csv …` reads each file as one step-sine record.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "ltp/htf/time_data.h"

namespace ltp::cli {

/// One file's channels.
struct ChannelTable {
  std::string path;
  std::vector<std::string> names;  ///< as in the header, units stripped ("Force")
  std::vector<double> time;        ///< s
  Eigen::MatrixXd values;          ///< samples × channels (the time column left out)
  double time_error = 0;           ///< bound on the error of the written times (s)
};

/// True when the file's first line that is not a comment is ltp's own header (record,…).
bool IsLtpTimeData(const std::string& path);

/// @throws InputError naming the file and line: no header, a cell that is not a number, rows
/// of another length, no time column and no `sample_rate` (Hz, > 0).
ChannelTable ReadDaqCsv(const std::string& path, double sample_rate);

/// Step-sine records from DAQ files: the input and the output channels named (index or name),
/// every channel also kept as an auxiliary one (a tacho may be any of them), excitation_hz 0
/// (found from the input). @throws InputError for channels missing from a file.
TimeData TimeDataFromTables(const std::vector<ChannelTable>& tables, const std::string& input,
                            const std::vector<std::string>& outputs, double period);

}  // namespace ltp::cli
