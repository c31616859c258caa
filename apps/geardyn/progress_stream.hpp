/// @file
/// @brief A std::ostream that hands every complete line to a ProgressLine: the runners that write
/// progress to an error stream (simulate, compare) serve the Python package's callbacks with it.
#pragma once

#include <ostream>
#include <streambuf>
#include <string>
#include <utility>

#include "geardyn/analysis_runs.hpp"

namespace geardyn::app {

/// Lines written to it reach `sink` (with their '\n'); a line without '\n' when it is
/// destroyed too. Without a sink, everything is discarded.
class ProgressStream : public std::ostream {
 public:
  explicit ProgressStream(ProgressLine sink) : std::ostream(&buffer_), buffer_(std::move(sink)) {}
  ~ProgressStream() override { buffer_.Flush(); }

 private:
  class Buffer : public std::streambuf {
   public:
    explicit Buffer(ProgressLine sink) : sink_(std::move(sink)) {}
    void Flush() {
      if (!line_.empty() && sink_) sink_(line_ + "\n");
      line_.clear();
    }

   protected:
    int overflow(int c) override {
      if (c == traits_type::eof()) return traits_type::not_eof(c);
      line_.push_back(static_cast<char>(c));
      if (c == '\n') {
        if (sink_) sink_(line_);
        line_.clear();
      }
      return c;
    }

   private:
    ProgressLine sink_;
    std::string line_;
  };
  Buffer buffer_;
};

}  // namespace geardyn::app
