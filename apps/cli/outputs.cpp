// The output rules every writing command shares (see outputs.hpp and tinlod/util.hpp).
#include "outputs.hpp"

#include "tinlod/util.hpp"

#include <algorithm>

namespace tinlod::cli {

static const char *k_outputs_help =
    "Outputs: each file is written to a hidden temporary in its folder, then renamed over it, so a "
    "failed or interrupted run leaves the old file, or none. A symbolic link is followed and "
    "stays: the file it names is replaced (a dangling link's file is created). A character device "
    "or FIFO (/dev/null, /dev/stdout) is written to directly; `-` is the standard output, and the "
    "command's own messages then go to the standard error. No two outputs may name the same file. "
    "Temporaries that a killed tinlod (SIGKILL, a crash, a power cut) left in an output folder "
    "are removed when a later tinlod starts to write there, before its work.";

void declare_outputs(CLI::App &cmd, std::vector<OutputOption> outputs, const std::string &more) {
    cmd.footer(more.empty() ? std::string(k_outputs_help) : k_outputs_help + ("\n" + more));
    cmd.callback([outputs = std::move(outputs)] {
        for (std::size_t i = 0; i < outputs.size(); ++i)
            for (std::size_t j = 0; j < i; ++j)
                if (same_output(*outputs[j].path, *outputs[i].path))
                    throw CLI::ValidationError(outputs[i].name + ": names the same file as " +
                                                   outputs[j].name + " ('" + *outputs[i].path +
                                                   "')",
                                               2);
        if (std::any_of(outputs.begin(), outputs.end(),
                        [](const OutputOption &o) { return *o.path == "-"; }))
            divert_standard_output();
    });
}

} // namespace tinlod::cli
