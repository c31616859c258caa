// The per-point warnings of a linear HB sweep and their merge into one line per cause
// (hb_internal.hpp: FormatHz, PointWarningPrefix, MergePointWarnings).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "hb_internal.hpp"

namespace geardyn::internal {

std::string FormatG(double x) {
  std::ostringstream os;
  os << std::setprecision(3) << x;
  return os.str();
}

// A mesh frequency in a warning [Hz]: 6 significant digits ("3287.5", not "3.29e+03").
std::string FormatHz(double f) {
  std::ostringstream os;
  os << std::setprecision(6) << f;
  return os.str();
}

// Per-point warnings that a sweep merges (MergePointWarnings): "harmonic balance at <f_m> Hz: "
// then a body that starts with the varying number (undamped share [%], or 1/cond).
std::string PointWarningPrefix(double f_m) {
  return "harmonic balance at " + FormatHz(f_m) + " Hz: ";
}

// One warning per distinct per-point warning of a sweep instead of one per point: the varying
// number (undamped share, 1/cond) is reduced to its worst, and the mesh-frequency range where the
// warning occurred is given. A warning of a single point is kept as the point gave it; warnings
// without the per-point prefix are kept once each (exact text), in order of first appearance.
std::vector<std::string> MergePointWarnings(const std::vector<HbResult>& points) {
  struct Merged {
    std::string key, first;  // the body without its leading number; the first point's text
    bool share = false;      // undamped share (max) or 1/cond (min)
    double worst = 0.0, lo = 0.0, hi = 0.0;
    int count = 0;  // points (not warnings: a repeated mode warns twice at a point)
    const HbResult* last = nullptr;  // the last point counted
  };
  std::vector<Merged> merged;
  for (const HbResult& point : points) {
    const std::string prefix = PointWarningPrefix(point.mesh_frequency_hz);
    for (const std::string& w : point.summary.warnings) {
      std::string key = w;
      bool share = false, numbered = false;
      double value = 0.0;
      if (w.rfind(prefix, 0) == 0) {
        const std::string body = w.substr(prefix.size());
        const std::size_t at = body.find(kUndampedShareText);
        const std::string ill = kIllConditionedText;
        if (at != std::string::npos && at > 0) {
          share = numbered = true;
          value = std::stod(body.substr(0, at));
          key = body.substr(at);
        } else if (body.rfind(ill, 0) == 0) {
          numbered = true;
          value = std::stod(body.substr(ill.size()));
          key = ill;
        } else {
          key = body;
          numbered = true;  // a per-point text without a number: merged by its body
        }
      }
      auto it =
          std::find_if(merged.begin(), merged.end(), [&](const Merged& m) { return m.key == key; });
      if (it == merged.end()) {
        merged.push_back({key, w, share, value, point.mesh_frequency_hz, point.mesh_frequency_hz,
                          numbered ? 1 : 0, &point});
        continue;
      }
      if (!numbered) continue;
      if (it->last != &point) ++it->count;
      it->last = &point;
      it->worst = share ? std::max(it->worst, value) : std::min(it->worst, value);
      it->lo = std::min(it->lo, point.mesh_frequency_hz);
      it->hi = std::max(it->hi, point.mesh_frequency_hz);
    }
  }
  std::vector<std::string> out;
  for (const Merged& m : merged) {
    if (m.count <= 1) {
      out.push_back(m.first);
      continue;
    }
    std::string text = "harmonic balance at f_m = " + FormatHz(m.lo) + " … " + FormatHz(m.hi) +
                       " Hz (" + std::to_string(m.count) + " of " + std::to_string(points.size()) +
                       " points): ";
    if (m.key.rfind(kIllConditionedText, 0) == 0) {
      text += "ill-conditioned solves (estimated 1/cond down to " + FormatG(m.worst) +
              "): expect to lose up to about " + FormatG(std::round(-std::log10(m.worst))) +
              " digits";
    } else if (m.share) {
      text += "up to " + FormatG(m.worst) + m.key;
    } else {
      text += m.key;
    }
    out.push_back(std::move(text));
  }
  return out;
}

}  // namespace geardyn::internal
