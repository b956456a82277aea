// bench_rays.cpp — single-threaded ray throughput: the own BVH's traversals (full stack, short
// stack, stackless) against Embree on the same rays.
//
// Ray sets, precomputed once per scene and shared by both backends:
//   camera  one primary ray per pixel centre (closest hit)
//   bounce  cosine-distributed diffuse rays from the camera rays' first hits (closest hit)
//   shadow  any-hit rays from the same hit points to the light (or a point above the scene)
// Scenes: a procedural displaced icosphere (327,680 triangles) on a ground quad, and
// scenes/cornell-water/scene.xml when it loads (skipped with the reason printed otherwise).
//
//   bench_rays [--benchmark_filter=...] [--benchmark_repetitions=N]
// ends with a table: scene, ray type, Mrays/s of each BVH traversal and of Embree, and the
// ratios of the short-stack and stackless rates to the full-stack one.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "caustica/accel/bvh.h"
#include "caustica/accel/embree_accel.h"
#include "caustica/accel/intersector.h"
#include "caustica/scene/camera.h"
#include "caustica/scene/interaction.h"
#include "caustica/util/rng.h"
#include "caustica/util/sampling.h"
#include "bench_scenes.h"

#if __has_include("caustica/io/scene_loader.h")
#include "caustica/io/scene_loader.h"
#define CAUSTICA_BENCH_HAS_LOADER 1
#endif

using namespace caustica;

namespace {

struct BenchScene {
    std::string name;
    Scene scene;
    Bvh bvh;
    std::unique_ptr<EmbreeScene> embree;
    std::vector<Ray> camera, bounce, shadow;
};

/// The shared ray sets (bench_scenes.h) of the scene.
void makeRays(BenchScene& b) {
    bench::RaySets sets = bench::makeRaySets(b.scene, b.bvh);
    b.camera = std::move(sets.camera);
    b.bounce = std::move(sets.bounce);
    b.shadow = std::move(sets.shadow);
}

std::vector<std::unique_ptr<BenchScene>> gScenes;

template <class Intersector>
void traceRays(benchmark::State& state, const Intersector& it, const std::vector<Ray>& rays,
               bool anyHit) {
    uint64_t hits = 0;
    for (auto _ : state) {
        hits = 0;
        if (anyHit) {
            for (const Ray& ray : rays) hits += it.occluded(ray);
        } else {
            for (const Ray& ray : rays) {
                Hit hit;
                hits += it.intersect(ray, hit);
            }
        }
        benchmark::DoNotOptimize(hits);
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(rays.size()));
    state.counters["rays/s"] =
        benchmark::Counter(double(rays.size()), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["hit%"] = 100.0 * double(hits) / double(max<size_t>(rays.size(), 1));
}

double maxOf(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }

void registerScene(const BenchScene& b) {
    const std::pair<const char*, const std::vector<Ray>*> sets[] = {
        {"camera", &b.camera}, {"bounce", &b.bounce}, {"shadow", &b.shadow}};
    for (const auto& [type, rays] : sets) {
        const bool anyHit = std::string(type) == "shadow";
        const std::string prefix = "rays/" + b.name + "/" + type + "/";
        auto add = [&](const std::string& name, auto intersector) {
            benchmark::RegisterBenchmark((prefix + name).c_str(),
                                         [&b, rays, anyHit, intersector](auto& st) {
                                             auto it = intersector;
                                             it.bvh = b.bvh.view();
                                             it.scene = b.scene.view();
                                             traceRays(st, it, *rays, anyHit);
                                         })
                ->Unit(benchmark::kMillisecond)
                ->MinTime(1.0)
                ->ComputeStatistics("max", maxOf);
        };
        add("bvh", BvhIntersectorT<BvhTraversal::Stack>{});
        add("bvh-short", BvhIntersectorT<BvhTraversal::ShortStack>{});
        add("bvh-stackless", BvhIntersectorT<BvhTraversal::Stackless>{});
        benchmark::RegisterBenchmark(
            (prefix + "embree").c_str(),
            [&b, rays, anyHit](auto& st) { traceRays(st, b.embree->intersector(), *rays, anyHit); })
            ->Unit(benchmark::kMillisecond)
            ->MinTime(1.0)
            ->ComputeStatistics("max", maxOf);
    }
}

void addScene(std::string name, Scene scene) {
    auto b = std::make_unique<BenchScene>();
    b->name = std::move(name);
    b->scene = std::move(scene);
    b->bvh = buildBvh(b->scene);
    b->embree = std::make_unique<EmbreeScene>(b->scene);
    makeRays(*b);
    const BvhStats& s = b->bvh.stats;
    std::printf(
        "%s: %u triangles, %zu spheres; BVH %u nodes, depth %u, %.2f prims/leaf, SAH %.1f, "
        "%.1f MiB, built in %.0f ms; Embree built in %.0f ms; rays: %zu camera, %zu bounce, "
        "%zu shadow\n",
        b->name.c_str(), uint32_t(b->scene.triangles.size()), b->scene.spheres.size(), s.nodeCount,
        s.maxDepth, s.averageLeafSize, s.sahCost, double(s.memoryBytes) / (1 << 20),
        s.buildMilliseconds, b->embree->buildMilliseconds(), b->camera.size(), b->bounce.size(),
        b->shadow.size());
    gScenes.push_back(std::move(b));
}

/// Console output as usual, plus every run's rays/s kept for the final table. With
/// --benchmark_repetitions the table takes the "max" aggregate: contention on a shared machine
/// only ever slows a run down, so the best repetition is the least disturbed one.
class TableReporter : public benchmark::ConsoleReporter {
public:
    void ReportRuns(const std::vector<Run>& runs) override {
        ConsoleReporter::ReportRuns(runs);
        for (const Run& run : runs) {
            auto it = run.counters.find("rays/s");
            if (run.error_occurred || it == run.counters.end()) continue;
            const std::string& name = run.run_name.function_name;
            const int rank = run.run_type != Run::RT_Aggregate ? 1
                             : run.aggregate_name == "max"     ? 3
                             : run.aggregate_name == "median"  ? 2
                                                               : 0;
            if (rank == 0) continue;
            const double value = it->second.value;
            auto& [bestRank, rate] = rates_[name];
            if (rank > bestRank) {
                bestRank = rank;
                rate = value;
            } else if (rank == 1 && bestRank == 1) {
                rate = std::max(rate, value);  // repetitions without aggregates
            }
        }
    }
    /// rays/s of a benchmark, or a negative value if it did not run.
    double rate(const std::string& name) const {
        auto it = rates_.find(name);
        return it == rates_.end() ? -1.0 : it->second.second;
    }

private:
    std::map<std::string, std::pair<int, double>> rates_;  // name -> (source rank, rays/s)
};

}  // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

    addScene("icosphere-330k", bench::makeProceduralScene(7));
#ifdef CAUSTICA_BENCH_HAS_LOADER
    const std::string path = std::string(CAUSTICA_SOURCE_DIR) + "/scenes/cornell-water/scene.xml";
    try {
        std::vector<std::string> warnings;
        addScene("cornell-water",
                 loadScene(path, {{"width", "640"}, {"height", "640"}}, &warnings));
    } catch (const std::exception& e) {
        std::printf("cornell-water skipped: %s\n", e.what());
    }
#else
    std::printf("cornell-water skipped: caustica/io/scene_loader.h is not available\n");
#endif
    for (const auto& b : gScenes) registerScene(*b);

    TableReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);

    std::printf("\n%-16s %-8s %9s %9s %9s %9s %7s %7s %7s\n", "scene", "rays", "stack", "short",
                "stackless", "Embree", "short/", "sless/", "stack/");
    std::printf("%-16s %-8s %9s %9s %9s %9s %7s %7s %7s\n", "", "", "Mrays/s", "Mrays/s", "Mrays/s",
                "Mrays/s", "stack", "stack", "Embree");
    for (const auto& b : gScenes)
        for (const char* type : {"camera", "bounce", "shadow"}) {
            const std::string prefix = "rays/" + b->name + "/" + type + "/";
            const double stack = reporter.rate(prefix + "bvh"),
                         shortStack = reporter.rate(prefix + "bvh-short"),
                         stackless = reporter.rate(prefix + "bvh-stackless"),
                         emb = reporter.rate(prefix + "embree");
            if (stack < 0 && shortStack < 0 && stackless < 0 && emb < 0) continue;
            // "-" for what did not run (--benchmark_filter).
            auto fixed2 = [](double v) {
                char buf[32];
                std::snprintf(buf, sizeof buf, "%.2f", v);
                return std::string(buf);
            };
            auto rate = [&](double v) { return v < 0 ? std::string("-") : fixed2(v * 1e-6); };
            auto ratio = [&](double a, double b2) {
                return a < 0 || b2 < 0 ? std::string("-") : fixed2(a / b2);
            };
            std::printf("%-16s %-8s %9s %9s %9s %9s %7s %7s %7s\n", b->name.c_str(), type,
                        rate(stack).c_str(), rate(shortStack).c_str(), rate(stackless).c_str(),
                        rate(emb).c_str(), ratio(shortStack, stack).c_str(),
                        ratio(stackless, stack).c_str(), ratio(stack, emb).c_str());
        }
    benchmark::Shutdown();
    return 0;
}
