#pragma once
// Time data as CSV, the exchange format of `ltp simulate` and `ltp identify`:
//
//   # ltp time data (comment lines start with '#')
//   # period_s: 3.14159265358979
//   # rotor_speed_rad_s: 100                      (when the system is a rotor)
//   record,excitation_hz,t,in:u,out:y,aux:tacho   (inputs "in:NAME", outputs "out:NAME",
//   1,0.13,471.238898038469,1,0.0123,0             then other channels "aux:NAME")
//
// One row per sample; the rows of a record are consecutive. Measured data written this way
// (one record per step of a step-sine test) can be identified the same way.
#include <optional>
#include <string>

#include "ltp/htf/time_data.h"

namespace ltp::cli {

/// The number `text` spells, the whole of it (trailing blanks allowed); nullopt otherwise.
std::optional<double> NumberIn(const std::string& text);

/// @throws InputError for a path that exists but is not a regular file (/dev/zero, a FIFO).
void RequireRegularFile(const std::string& path);

/// std::getline for text tables, with a bound: a "line" over 1 MiB (a binary file, one without
/// line ends) is refused with `where`, not read into memory to its end. False at the end.
bool ReadTextLine(std::istream& in, std::string& line, const std::string& where);

/// The channel's name, or `fallback` and its number (from 1) when the data name none.
std::string ChannelNameOr(const std::vector<std::string>& names, Eigen::Index i,
                          const std::string& fallback);

/// @throws InputError when the file cannot be written.
void WriteTimeDataCsv(const std::string& path, const TimeData& data, const std::string& comment);

/// @throws InputError naming the line: unreadable file, no period (and `period` <= 0), a row
/// with the wrong number of cells or a cell that is not a number, channels not marked in:/out:.
/// `period` > 0 overrides the file's; without either, `require_period` = false returns the data
/// with period 0 (unvalidated) for a caller that measures it (a tacho).
TimeData ReadTimeDataCsv(const std::string& path, double period = 0, bool require_period = true);

}  // namespace ltp::cli
