#include "geardyn/output_files.hpp"

#include <fstream>
#include <string>
#include <system_error>

#include "geardyn/common/check.hpp"

namespace geardyn::app {

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
  std::ofstream file(path);
  GEARDYN_THROW_UNLESS(file.good(), "--out " << path.string() << ": cannot open for writing");
  file << text;
  file.close();
  GEARDYN_THROW_UNLESS(file.good(), "--out " << path.string() << ": write failed");
  return path;
}

}  // namespace geardyn::app
