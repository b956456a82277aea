// caustica info SCENE — what a scene contains: counts, bounds, camera, film, BVH statistics.
#include <cstdio>

#include "commands.h"
#include "caustica/accel/bvh.h"
#include "caustica/io/scene_loader.h"
#include "caustica/render/integrator_registry.h"

namespace caustica::cli {
namespace {

const char* filterName(FilterType t) {
    switch (t) {
        case FilterType::Box: return "box";
        case FilterType::Tent: return "tent";
        case FilterType::Gaussian: return "gaussian";
    }
    return "?";
}

void printScene(const Scene& scene) {
    size_t meshes = 0, emitters = 0;
    for (const Shape& s : scene.shapes) {
        meshes += s.type == ShapeType::Mesh;
        emitters += s.light >= 0;
    }
    Bounds3f b = scene.bounds();
    std::printf("scene        %s\n", scene.sourceFile.c_str());
    std::printf("shapes       %zu (%zu meshes, %zu spheres, %zu emitting)\n", scene.shapes.size(), meshes,
                scene.spheres.size(), emitters);
    std::printf("triangles    %zu\n", scene.triangles.size());
    std::printf("vertices     %zu\n", scene.positions.size());
    std::printf("bsdfs        %zu\n", scene.bsdfs.size());
    std::printf("lights       %zu%s\n", scene.lights.size(), scene.environmentLight >= 0 ? " (one environment)" : "");
    if (!b.empty())
        std::printf("bounds       (%g, %g, %g) - (%g, %g, %g)\n", b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z);
    std::printf("film         %dx%d, %s filter (radius %g)\n", scene.film.width, scene.film.height,
                filterName(scene.film.filter.type), scene.film.filter.radius);
    std::printf("sampler      %d spp\n", scene.sampleCount);
    // The integrator that will run, with the settings it reads (its warnings too).
    const IntegratorEntry& integrator = findIntegrator(scene.integrator.type);
    IntegratorParams params = integratorParams(scene.integrator, integrator.name, {});
    std::printf("integrator   %s (%s)\n", integrator.name, integrator.describe(params).c_str());
    for (const std::string& w : params.unread()) std::printf("warning      %s\n", w.c_str());
    if (!scene.integrator.aovs.empty()) std::printf("aovs         %s\n", scene.integrator.aovs.c_str());
    Vec3f eye = scene.camera.worldFromCamera.applyPoint(Vec3f(0, 0, 0));
    std::printf("camera       at (%g, %g, %g), horizontal fov %.4g deg\n", eye.x, eye.y, eye.z,
                2 * degrees(std::atan(scene.camera.tanHalfX)));
}

}  // namespace

std::function<int()> addInfoCommand(CLI::App& app) {
    struct Options {
        std::string scene;
        std::vector<std::string> defines;
    };
    auto opt = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand("info", "Print a scene's contents and BVH statistics");
    cmd->add_option("scene", opt->scene, "Scene file (Mitsuba 3 XML)")->required()->check(CLI::ExistingFile);
    cmd->add_option("-D,--define", opt->defines, "Set a scene <default> parameter: -D name=value");
    return [opt] {
        Scene scene = loadScene(opt->scene, parseDefines(opt->defines));
        printScene(scene);
        Bvh bvh = buildBvh(scene);
        const BvhStats& st = bvh.stats;
        std::printf("bvh          %u nodes, %u leaves, max depth %u, %.2f primitives/leaf; %u rectangles "
                    "tested as planes\n",
                    st.nodeCount, st.leafCount, st.maxDepth, st.averageLeafSize, st.directParallelograms);
        std::printf("bvh cost     SAH %.3f, %.2f MiB, built in %.1f ms\n", st.sahCost,
                    double(st.memoryBytes) / (1024.0 * 1024.0), st.buildMilliseconds);
        return 0;
    };
}

}  // namespace caustica::cli
