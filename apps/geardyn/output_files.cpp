#include "geardyn/output_files.hpp"

#include <unistd.h>

#include <fstream>
#include <string>
#include <system_error>

#include "geardyn/common/check.hpp"
#include "geardyn/interrupt.hpp"

namespace geardyn::app {
namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::string MarkPartial(const std::string& name, const std::string& text) {
  constexpr const char* kWhy =
      "partial: the run was interrupted (SIGINT/SIGTERM); only the points "
      "computed before it are here";
  if (EndsWith(name, ".json")) {
    // Every geardyn JSON file is one object: "partial" becomes its first member.
    const std::size_t brace = text.find('{');
    if (brace == std::string::npos) return text;
    const bool empty = text.find_first_not_of(" \t\r\n", brace + 1) == text.find('}', brace);
    return text.substr(0, brace + 1) + "\"partial\": true" + (empty ? "" : ", ") +
           text.substr(brace + 1);
  }
  if (EndsWith(name, ".svg")) {
    // After the XML declaration, if any (nothing may precede it).
    std::size_t at = 0;
    if (text.rfind("<?xml", 0) == 0)
      at = text.find('\n') == std::string::npos ? text.size() : text.find('\n') + 1;
    return text.substr(0, at) + "<!-- " + kWhy + " -->\n" + text.substr(at);
  }
  // CSV and text: a leading comment line (pandas: comment="#").
  return std::string("# ") + kWhy + "\n" + text;
}

std::string PrepareOutputDirectory(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    return dir.string() + ": exists and is not a directory (a file is in the way)";
  }
  std::filesystem::create_directories(dir, ec);
  if (ec) return dir.string() + ": cannot create directory (" + ec.message() + ")";
  const std::filesystem::path probe = dir / ".geardyn-write-probe";
  {
    std::ofstream file(probe);
    if (!file.good()) return dir.string() + ": directory is not writable";
  }
  std::filesystem::remove(probe, ec);
  return "";
}

std::filesystem::path WriteOutputFile(const std::filesystem::path& dir, const std::string& name,
                                      const std::string& text) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  GEARDYN_THROW_UNLESS(
      !ec, "--out " << dir.string() << ": cannot create directory (" << ec.message() << ")");
  const std::filesystem::path path = dir / name;
  // Atomic: the text goes to a temporary file in the same directory, renamed over `path` only
  // once complete, so a crash or a kill never leaves a half file that looks complete.
  const std::filesystem::path temporary =
      dir / ("." + name + ".tmp-" + std::to_string(static_cast<long>(::getpid())));
  {
    std::ofstream file(temporary, std::ios::binary);
    GEARDYN_THROW_UNLESS(file.good(), "--out " << path.string() << ": cannot open for writing");
    file << (Interrupted() ? MarkPartial(name, text) : text);
    file.close();
    if (!file.good()) {
      std::filesystem::remove(temporary, ec);
      GEARDYN_THROW_UNLESS(false, "--out " << path.string() << ": write failed");
    }
  }
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    GEARDYN_THROW_UNLESS(false,
                         "--out " << path.string() << ": cannot replace (" << ec.message() << ")");
  }
  return path;
}

}  // namespace geardyn::app
