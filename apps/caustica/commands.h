// commands.h — the subcommands of the `caustica` command line.
#pragma once

#include <CLI/CLI.hpp>

#include "caustica/distributed/communicator.h"

namespace caustica::cli {

/// Each registers its options on `app` and returns the function to run when it was chosen.
/// `render` renders with the ranks of `comm` (ranks.h): every rank runs it.
std::function<int()> addRenderCommand(CLI::App& app, Communicator& comm);
std::function<int()> addCompareCommand(CLI::App& app);
std::function<int()> addInfoCommand(CLI::App& app);
std::function<int()> addDenoiseCommand(CLI::App& app);

/// Parses "-D name=value" strings into a map; throws caustica::Error on a malformed entry.
std::map<std::string, std::string> parseDefines(const std::vector<std::string>& defines);

}  // namespace caustica::cli
