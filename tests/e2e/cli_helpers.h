// cli_helpers.h — running the `caustica` binary from tests and reading what it printed.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace caustica::test {

struct CliResult {
    int exitCode;
    std::string output;  // stdout and stderr
};

/// Runs a shell command line and captures its exit code and output.
inline CliResult runCliCommand(const std::string& cmd) {
    CliResult r{-1, {}};
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, p)) r.output.append(buf, n);
    int status = pclose(p);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

/// Runs `caustica ARGS` and captures its exit code and output.
inline CliResult runCli(const std::string& args) {
    return runCliCommand(std::string(CAUSTICA_BINARY) + " " + args + " 2>&1");
}

/// Runs a shell script (sh -c) and captures its exit code and output; $CAUSTICA names the binary.
inline CliResult runShell(const std::string& script) {
    std::string quoted;
    for (char c : script) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return runCliCommand("CAUSTICA=" + std::string(CAUSTICA_BINARY) + " sh -c '" + quoted + "' 2>&1");
}

/// A fresh temporary directory per test, named after the test and the process: two runs of the
/// same test at once (two checkouts on one machine) must not share or delete each other's files.
class CliFixture : public ::testing::Test {
protected:
    void SetUp() override {
        dir = std::filesystem::temp_directory_path() /
              ("caustica_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_suite()->name()) +
               "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
               std::to_string(::getpid()));
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
    }
    void TearDown() override { std::filesystem::remove_all(dir); }
    std::string path(const std::string& name) const { return (dir / name).string(); }
    std::filesystem::path dir;
};

}  // namespace caustica::test
