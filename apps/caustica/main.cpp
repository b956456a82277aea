// caustica — command line entry point: render, compare, info, denoise.
#include <cstdio>
#include <exception>

#include "commands.h"
#include "caustica/util/error.h"
#ifdef CAUSTICA_WITH_CUDA
#include "cuda/cuda_backend.h"
#endif

int main(int argc, char** argv) {
#ifdef CAUSTICA_WITH_CUDA
    caustica::registerCudaBackend();  // installs the GPU backend's function table; touches no GPU
#endif
    CLI::App app{"caustica — a physically based light-transport renderer for the hard light"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "caustica 0.1.0");
    std::function<int()> run;
    auto render = caustica::cli::addRenderCommand(app);
    auto compare = caustica::cli::addCompareCommand(app);
    auto info = caustica::cli::addInfoCommand(app);
    auto denoise = caustica::cli::addDenoiseCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    try {
        if (app.got_subcommand("render")) return render();
        if (app.got_subcommand("compare")) return compare();
        if (app.got_subcommand("info")) return info();
        if (app.got_subcommand("denoise")) return denoise();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "caustica: error: %s\n", e.what());
        return 1;
    }
    return 1;
}
