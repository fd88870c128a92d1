#pragma once
// Universal File Format dataset 58 ("function at nodal DOF"), the exchange format of test and
// modal-analysis software, in ASCII and in the binary variant 58b. One dataset holds one
// function: a time record of one channel, or a frequency response. docs/rig-data.md shows the
// records' layout; what matters here:
//   - a file is a sequence of datasets, each between lines "    -1"; others (151, 164, …) are
//     skipped;
//   - record 6 names the function's type (1 time response, 4 FRF) and its response and
//     reference (entity name, node, direction); record 7 its data form (ordinate type 2/4 real
//     single/double, 5/6 complex; even spacing with start and increment, or uneven with the
//     abscissa beside each value);
//   - ASCII values sit in fixed-width fields (6E13.5, 4E20.12, …); in 58b they are raw IEEE
//     numbers of the byte order the dataset line states, exactly as many bytes as it says.
// The abscissa's start and increment are written in E13.5-wide fields: 6–7 digits. A rig's
// sample rate (51 200 Hz: 1.953125E-05) fits; an arbitrary step loses digits there.
#include <complex>
#include <string>
#include <vector>

#include "daq_csv.h"

namespace ltp::cli {

/// One dataset 58.
struct Uff58Function {
  std::string description;    ///< ID line 1
  std::string id2 = "NONE";   ///< ID line 2 (ltp writes what the function is of)
  int function_type = 1;      ///< 1 time response, 4 frequency response function, 0 general
  int sequence = 0;           ///< record 6 field 3 (version or sequence number)
  std::string response_name;  ///< record 6 field 5 (≤ 10 characters kept)
  int response_node = 0, response_direction = 0;
  std::string reference_name = "NONE";
  int reference_node = 0, reference_direction = 0;
  int abscissa_type = 17;  ///< record 8's specific data type: 17 time, 18 frequency
  std::string abscissa_label = "time", abscissa_unit = "s";
  std::string ordinate_label = "NONE", ordinate_unit = "NONE";
  /// Abscissa: even spacing start + k·increment when `x` is empty, else x[k].
  double start = 0, increment = 0;
  std::vector<double> x;
  double abscissa_error = 0;  ///< read: bound on the abscissa's error from the digits written
  std::vector<double> real;   ///< real ordinates, or
  std::vector<std::complex<double>> complex;  ///< complex ones (exactly one of the two filled)
  size_t size() const { return complex.empty() ? real.size() : complex.size(); }
};

/// True for a file name that asks for UFF (.uff, .unv, any case).
bool IsUffName(const std::string& path);

/// True when the file's first line that is not blank is a dataset separator ("    -1").
bool IsUffFile(const std::string& path);

/// Every dataset 58 of the file (others skipped), in order. @throws InputError naming the file
/// and the line (or byte offset of binary data): a truncated dataset, a field that is not a
/// number, a byte count or ordinate type that does not fit, a file without dataset 58.
std::vector<Uff58Function> ReadUff58(const std::string& path);

/// Time records from a UFF file: its time functions (type 1, or 0 on a time abscissa), each a
/// channel named by its ID line 1 (or "<response> <node>:<direction>" when that is NONE). A
/// channel name met again starts the next record, so one file may hold several records of the
/// same channels. @throws InputError for frequency functions, complex data,
/// and channels of one record sampled differently.
std::vector<ChannelTable> ReadUffTimeRecords(const std::string& path);

/// Time data as UFF: one time function per record and channel (inputs, outputs, auxiliaries;
/// ID line 1 the channel's name, ID line 2 the record and `comment`, the record's number in
/// record 6's sequence field), evenly spaced when the record is. Returns the largest change
/// that writing the abscissa's start and step with 7 digits makes to a sample time (s).
double WriteTimeDataUff(const std::string& path, const TimeData& data, const std::string& comment,
                        bool binary);

/// Writes the functions as datasets 58 (ASCII: double precision, 4E20.12 / E13.5,2E20.12) or
/// 58b (little-endian IEEE doubles). @throws InputError when the file cannot be written.
void WriteUff58(const std::string& path, const std::vector<Uff58Function>& functions, bool binary);

}  // namespace ltp::cli
