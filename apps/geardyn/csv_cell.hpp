// CSV cells shared by the commands' tables. A value that does not exist (a failed point, an
// undetermined verdict, a non-finite number) is an empty cell, as the JSON's null: "nan" or "inf"
// text is not a number to a spreadsheet or to a reader that trusts the column's type
// (docs/design.md "Three-valued verdict").
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace geardyn::app {

/// `v` printed with the printf `format`, or "" when `v` is NaN or ±∞.
inline std::string CsvNumber(double v, const char* format = "%.9g") {
  if (!std::isfinite(v)) return std::string();
  char buffer[48];
  std::snprintf(buffer, sizeof(buffer), format, v);
  return buffer;
}

/// A verdict column: "1" stable, "0" unstable, "" undetermined (not decided: not 0, which would
/// read as unstable).
inline const char* CsvVerdict(bool determined, bool stable) {
  return !determined ? "" : stable ? "1" : "0";
}

}  // namespace geardyn::app
