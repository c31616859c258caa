/// @file
/// @brief Writing result files into the `--out` directory.
#pragma once

#include <filesystem>
#include <string>

namespace geardyn::app {

/// @brief Makes sure `dir` can receive result files before any computation runs: creates it if
/// missing, and checks that it is a directory and that a file can be created in it (a probe file,
/// removed again).
/// @param[in] dir the `--out` directory.
/// @return "" when the directory is usable, else the reason (naming the path), for the `--out`
/// validator of every scene command (commands.cpp), so that a bad `--out` fails in milliseconds.
std::string PrepareOutputDirectory(const std::filesystem::path& dir);

/// @brief `text` of the file `name` marked as partial, by its extension: a `"partial": true`
/// first member of a JSON object, an XML comment in an SVG, a leading `# partial: …` line in a
/// CSV or text file.
std::string MarkPartial(const std::string& name, const std::string& text);

/// @brief Writes `text` to DIR/name atomically (a temporary file renamed over it), creating DIR if
/// needed. After an interrupt (interrupt.hpp) the text is marked as partial (MarkPartial).
/// @throws InvalidInput naming the path and the reason when the directory or file cannot be
/// written.
std::filesystem::path WriteOutputFile(const std::filesystem::path& dir, const std::string& name,
                                      const std::string& text);

}  // namespace geardyn::app
