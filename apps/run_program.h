#pragma once
// Every program's exit codes, one way (docs/design.md, "Conventions"): a command-line error is one
// line "PROGRAM: what; see --help" and exit 2 (--help itself exits 0); bad input is one line
// "PROGRAM: FILE: where: what" and exit 2; a failure of the machine (a full disk, a folder it may not
// write) or of the program is one line and exit 1. A failed write to standard output (a closed pipe,
// a full disk) is a failure too, not a silent success.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "base/cli_checks.h"
#include "base/error.h"
#include "base/message_line.h"

namespace svbrdf {

// Parses the command line, then runs `body` (which returns the exit status of a run that went to the
// end: 0, or 128 + a signal's number).
template <class Body>
int run_program(const char* program, CLI::App& app, int argc, char** argv, Body&& body) {
  try {
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      return cli::parse_failure(app, e, program);
    }
    const int status = body();
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
      std::fprintf(stderr, "%s: could not write the standard output\n", program);
      return 1;
    }
    return status;
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: %s\n", program, message_line(e.what()).c_str());
    return e.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error: %s\n", program, message_line(e.what()).c_str());
    return 1;
  }
}

}  // namespace svbrdf
