/// @file
/// @brief Writing result files into the `--out` directory.
#pragma once

#include <filesystem>
#include <string>

namespace geardyn::app {

/// @brief Writes `text` to DIR/name, creating DIR if needed.
/// @throws InvalidInput naming the path and the reason when the directory or file cannot be
/// written.
std::filesystem::path WriteOutputFile(const std::filesystem::path& dir, const std::string& name,
                                      const std::string& text);

}  // namespace geardyn::app
