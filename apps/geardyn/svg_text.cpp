#include "geardyn/svg_text.hpp"

#include <cmath>
#include <sstream>

namespace geardyn::app {

double NiceTickStep(double span, int target) {
  const double raw = span / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  return (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * mag;
}

std::string EscapeSvgText(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else if (c == '&') {
      out += "&amp;";
    } else {
      out += c;
    }
  }
  return out;
}

std::string FormatTickNumber(double v) {
  std::ostringstream s;
  s.precision(4);
  s << (std::abs(v) < 1e-300 ? 0.0 : v);
  return s.str();
}

}  // namespace geardyn::app
