// commands.h — the subcommands of the `caustica` command line.
#pragma once

#include <CLI/CLI.hpp>

namespace caustica::cli {

/// Each registers its options on `app` and returns the function to run when it was chosen.
std::function<int()> addRenderCommand(CLI::App& app);
std::function<int()> addCompareCommand(CLI::App& app);
std::function<int()> addInfoCommand(CLI::App& app);
std::function<int()> addDenoiseCommand(CLI::App& app);

/// Parses "-D name=value" strings into a map; throws caustica::Error on a malformed entry.
std::map<std::string, std::string> parseDefines(const std::vector<std::string>& defines);

}  // namespace caustica::cli
