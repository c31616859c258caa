// The geardyn command; all logic is in cli.cpp so that tests can run it in-process.
#include <iostream>
#include <string>
#include <vector>

#include "geardyn/cli.hpp"

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  return geardyn::app::RunCli(args, std::cout, std::cerr);
}
