// caustica — command line entry point: render, compare, info, denoise.
#include <cstdio>
#include <exception>
#include <memory>
#include <string>

#include "commands.h"
#include "ranks.h"
#include "caustica/util/error.h"
#ifdef CAUSTICA_WITH_CUDA
#include "cuda/cuda_backend.h"
#endif

int main(int argc, char** argv) {
#ifdef CAUSTICA_WITH_CUDA
    caustica::registerCudaBackend();  // installs the GPU backend's function table; touches no GPU
#endif
    // Under mpirun / srun (and built with MPI) every rank runs the same command; MPI starts here.
    std::unique_ptr<caustica::cli::Ranks> ranks;
    try {
        ranks = std::make_unique<caustica::cli::Ranks>(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "caustica: error: %s\n", e.what());
        return 1;
    }
    CLI::App app{"caustica — a physically based light-transport renderer for the hard light"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "caustica 0.1.0");
    std::function<int()> run;
    auto render = caustica::cli::addRenderCommand(app, ranks->comm());
    auto compare = caustica::cli::addCompareCommand(app);
    auto info = caustica::cli::addInfoCommand(app);
    auto denoise = caustica::cli::addDenoiseCommand(app);
    caustica::Communicator& comm = ranks->comm();
    int parseExit = -1;
    std::string parseFailure;  // over several ranks: agreed, since one rank may lack a file the others see
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (comm.size() == 1) return app.exit(e);
        // Rank 0 prints the help or the complaint; another rank prints only its own complaint.
        parseExit = comm.isRoot() ? app.exit(e) : e.get_exit_code();
        if (!comm.isRoot() && parseExit != 0) std::fprintf(stderr, "caustica: error: rank %d: %s\n", comm.rank(), e.what());
        parseFailure = parseExit == 0 ? "help" : e.what();
    }
    if (comm.size() > 1) {
        if (const std::string first = comm.firstError(parseFailure); !first.empty()) {
            if (parseExit >= 0) return parseExit;
            std::fprintf(stderr, "caustica: error: %s\n", first.c_str());
            return 1;
        }
    }
    // Only `render` is spread over ranks; another command under mpirun runs once, on rank 0.
    if (comm.size() > 1 && !app.got_subcommand("render") && !comm.isRoot()) return 0;
    try {
        if (app.got_subcommand("render")) return render();
        if (app.got_subcommand("compare")) return compare();
        if (app.got_subcommand("info")) return info();
        if (app.got_subcommand("denoise")) return denoise();
    } catch (const std::exception& e) {
        return ranks->fail(e);  // over several ranks: ends them all, whatever they wait for
    }
    return 1;
}
