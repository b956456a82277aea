// fuzz_common.h — shared pieces of the libFuzzer targets (docs/FUZZING.md): a private temporary
// directory that the loaders read their input from, and the rule that only caustica::Error is an
// acceptable failure. Any other exception is reported and aborts, so libFuzzer records a crash.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <typeinfo>

#include "caustica/util/error.h"

namespace caustica::fuzz {

/// A directory private to this process (mkdtemp under the system temp dir), removed at exit.
inline const std::filesystem::path& tempDir() {
    static const std::filesystem::path dir = [] {
        std::string pattern = (std::filesystem::temp_directory_path() / "caustica_fuzz_XXXXXX");
        if (!mkdtemp(pattern.data())) {
            std::perror("caustica fuzz: mkdtemp");
            std::abort();
        }
        std::filesystem::path p(pattern);
        static struct Cleanup {
            std::filesystem::path p;
            ~Cleanup() {
                std::error_code ec;
                std::filesystem::remove_all(p, ec);
            }
        } cleanup{p};
        return p;
    }();
    return dir;
}

/// Writes `data` (binary-exact) to `name` in the private directory and returns the full path.
inline std::string writeFile(const std::string& name, std::string_view data) {
    std::filesystem::path p = tempDir() / name;
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(data.data(), std::streamsize(data.size()));
    out.close();
    if (!out) {
        std::fprintf(stderr, "caustica fuzz: cannot write %s\n", p.c_str());
        std::abort();
    }
    return p.string();
}

/// Runs `load()`: returning or throwing caustica::Error is fine; any other exception is a bug.
template <class F>
void expectLoadOrError(F&& load) {
    try {
        load();
    } catch (const caustica::Error&) {
        // A clean refusal.
    } catch (const std::exception& e) {
        std::fprintf(stderr, "caustica fuzz: unexpected exception %s: %s\n", typeid(e).name(),
                     e.what());
        std::abort();
    } catch (...) {
        std::fprintf(stderr, "caustica fuzz: unexpected non-std exception\n");
        std::abort();
    }
}

}  // namespace caustica::fuzz
