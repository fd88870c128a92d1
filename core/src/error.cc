#include "ltp/core/error.h"

#include <sstream>

namespace ltp {

std::string MessageNumber(double x, int significant) {
  std::ostringstream s;
  s.precision(significant);
  s << x;
  return s.str();
}

}  // namespace ltp
