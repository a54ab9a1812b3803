// The files and folders a command writes: how they are written, told in its --help, and the
// usage errors among them found before any work.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace tinlod::cli {

// An output option of a command: its name for messages, and the variable its path goes to.
struct OutputOption {
    std::string name;
    const std::string *path;
};

// Declares the outputs of `cmd`: its --help tells how they are written (and `more`, when given),
// and once its options are parsed, before any work, two of `outputs` that name the same file are a
// usage error (exit 2), and one that is `-` diverts the standard output (divert_standard_output).
void declare_outputs(CLI::App &cmd, std::vector<OutputOption> outputs,
                     const std::string &more = "");

} // namespace tinlod::cli
