// caustica render SCENE — parses the options, loads the scene and hands both to the library's
// render session (render/): budgets, checkpoints, Ctrl-C, progress and outputs all live there.
#include <tbb/global_control.h>

#include <cstdio>
#include <memory>
#include <optional>

#include "commands.h"
#include "render_options.h"
#include "caustica/distributed/agreed_error.h"
#include "caustica/io/scene_loader.h"
#include "caustica/parallel/kernel_stats.h"
#include "caustica/render/render_outputs.h"
#include "caustica/render/render_run.h"

namespace caustica::cli {

std::function<int()> addRenderCommand(CLI::App& app, Communicator& comm) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a Mitsuba 3 XML scene");
    addRenderOptions(*cmd, *o);
    return [o, cmd, &comm] {
        resolveRenderOptions(*o, *cmd);
        std::unique_ptr<tbb::global_control> threads;
        if (o->threads > 0)
            threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                            size_t(o->threads));
        KernelStats::global().reset();
        KernelStats::global().setEnabled(o->kernelStats);
        const bool root = comm.isRoot();  // over MPI ranks (ranks.h) rank 0 prints and writes

        // Ranks may diverge where they read their own files or memory: each such step is agreed,
        // so a failure on one rank ends every rank with its message (distributed/agreed_error.h).
        std::optional<Scene> scene;
        agreeOnFailure(comm, [&] { scene = loadScene(o->scene, o->request.defines); });
        RunControl& control = o->control;
        if (control.outputs.empty()) control.outputs.push_back(defaultOutputPath(o->scene, scene->film));
        control.checkpoint = control.outputs.front() + ".ckpt";
        const std::optional<CheckpointHeader> resume = prepareRun(control, comm);  // before any rendering

        std::unique_ptr<Renderer> made;
        agreeOnFailure(comm, [&] {
            made = std::make_unique<Renderer>(std::move(*scene), o->request, resume ? &*resume : nullptr, comm);
        });
        Renderer& renderer = *made;
        if (root) {
            for (const std::string& w : renderer.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
            if (!control.quiet) std::fputs(renderer.description().c_str(), stderr);
            if (!control.quiet && comm.size() > 1)
                std::fprintf(stderr, "ranks: %d (MPI), rank 0 writes the outputs\n", comm.size());
        }
        const RunResult result = runRender(renderer, control);

        printRenderSummary(renderer, root ? stdout : nullptr);  // collective: summed over the ranks
        if (root && o->kernelStats)
            std::printf("kernel statistics (%s):\n%s", deviceName(renderer.device().kind),
                        KernelStats::global().table().c_str());
        if (root)
            for (const std::string& path : result.written) std::printf("wrote       %s\n", path.c_str());
        return result.cancelled ? 130 : 0;
    };
}

}  // namespace caustica::cli
