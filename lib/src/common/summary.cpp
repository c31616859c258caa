#include "geardyn/common/summary.hpp"

#include <sstream>

namespace geardyn {

const char* StatusName(Status status) {
  switch (status) {
    case Status::kSuccess:
      return "success";
    case Status::kNotConverged:
      return "not_converged";
    case Status::kNumericalIssue:
      return "numerical_issue";
    case Status::kToleranceNotMet:
      return "tolerance_not_met";
    case Status::kInterrupted:
      return "interrupted";
  }
  return "unknown";
}

std::string Summary::BriefReport() const {
  std::ostringstream out;
  out << "status: " << StatusName(status);
  if (!message.empty()) out << " (" << message << ")";
  out << "; error estimate " << error_estimate << "; wall time " << wall_time_s << " s";
  for (const auto& [name, value] : counters) out << "; " << name << " " << value;
  for (const std::string& w : warnings) out << "\nwarning: " << w;
  return out.str();
}

}  // namespace geardyn
