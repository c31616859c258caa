#include "geardyn/output_files.hpp"

#include <fstream>
#include <system_error>

#include "geardyn/common/check.hpp"

namespace geardyn::app {

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
