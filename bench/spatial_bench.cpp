// spatial_bench.cpp — the photon lookup structures (src/caustica/spatial/) side by side: build
// time, bytes per point and queries per second of every structure for every query type on
// synthetic and real SPPM point sets, written as CSV (plot: bench/spatial_bench_plot.py).
//
// Point sets (--sets, default all), each giving a "points" set (photons: one common radius) and a
// "spheres" set (visible points: each its own radius):
//   uniform        1,000,000 points uniform in the unit cube, radius 0.0193 (about 30 points per
//                  ball); 100,000 random query points; spheres: radii uniform in [0.5, 1.5] r
//   cornell-water  scenes/cornell-water/scene.xml at 256x256 \  after --iterations of an SPPM
//   glass-caustic  scenes/glass-caustic/scene.xml at 256x256  | render (CPU, direction gather):
//   water-1080p    scenes/cornell-water/scene.xml at 1920x1080 / SppmDriverBase::lookupInputs()
// Queries: points sets: "within" (forEachPointWithin at each query's radius) and "knn16"
// (kNearest, k = 16, max radius 2 r); spheres sets: "covering" (forEachSphereCovering) and
// "segment" (forEachSphereOnSegment, a random unit direction, length 10 x the median radius).
//
//   spatial_bench [--sets uniform,cornell-water,glass-caustic,water-1080p] [--repeat 3]
//                 [--iterations 8] [--photons 262144] [--threads N] [--scale 1]
//                 [--structures NAME,...] [--csv FILE]
//
// Every figure is the best (minimum) of --repeat runs. Queries run in parallel (launch over
// CpuExec, all threads or --threads). Each query writes its result count and the sum of its
// result indices into per-query arrays, summed afterwards: the work cannot be optimised away, and
// the totals are a cheap correctness check: every structure must return exactly the same sets
// (point_set.h), so the totals of one set and query must agree between all structures; the
// program says so loudly and exits with status 1 when they do not.
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/sppm/sppm_driver.h"
#include "caustica/integrators/sppm/sppm_settings.h"
#include "caustica/io/scene_loader.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/render/integrator_registry.h"
#include "caustica/spatial/hash_grid.h"
#include "caustica/spatial/kd_tree.h"
#include "caustica/spatial/multi_hash.h"
#include "caustica/spatial/point_set.h"
#include "caustica/spatial/uniform_grid.h"
#include "caustica/util/rng.h"
#include "caustica/util/sampling.h"

using namespace caustica;

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// ---- options ------------------------------------------------------------------------------------

struct Options {
    std::vector<std::string> sets;        // empty: all
    std::vector<std::string> structures;  // name prefixes; empty: all
    int repeat = 3;
    int iterations = 8;
    uint64_t photons = uint64_t(1) << 18;  // photon paths per iteration, unless the scene says
    int threads = 0;                       // 0: all cores
    double scale = 1;                      // point and query counts (and image area) times this
    std::string csv;                       // "": bench/results/spatial-YYYY-MM-DD.csv
};

/// "a,b(c,d),e" -> a, b(c,d), e: commas inside parentheses belong to a structure's name.
std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> items(1);
    int depth = 0;
    for (char c : text) {
        depth += c == '(' ? 1 : c == ')' ? -1 : 0;
        if (c == ',' && depth == 0)
            items.emplace_back();
        else
            items.back() += c;
    }
    std::erase(items, std::string());
    return items;
}

[[noreturn]] void usage(int status) {
    std::fprintf(
        status ? stderr : stdout,
        "usage: spatial_bench [--sets LIST] [--structures LIST] [--repeat N] [--iterations N]\n"
        "                     [--photons N] [--threads N] [--scale X] [--csv FILE]\n"
        "  --sets        uniform,cornell-water,glass-caustic,water-1080p (default: all)\n"
        "  --structures  structure names or prefixes, e.g. kdtree,multihash (default: all)\n"
        "  --repeat      runs of each build and query; the best is reported (3)\n"
        "  --iterations  SPPM iterations before the scenes' point sets are taken (8)\n"
        "  --photons     photon paths per SPPM iteration (262144)\n"
        "  --threads     worker threads (default: all cores)\n"
        "  --scale       point and query counts x X, image area x X (1; 0.1 for a smoke run)\n"
        "  --csv         output (default: bench/results/spatial-YYYY-MM-DD.csv)\n");
    std::exit(status);
}

Options parseOptions(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") usage(0);
        if (i + 1 >= argc) usage(2);
        const std::string value = argv[++i];
        try {
            if (arg == "--sets")
                o.sets = splitList(value);
            else if (arg == "--structures")
                o.structures = splitList(value);
            else if (arg == "--repeat")
                o.repeat = std::max(1, std::stoi(value));
            else if (arg == "--iterations")
                o.iterations = std::max(1, std::stoi(value));
            else if (arg == "--photons")
                o.photons = std::max<uint64_t>(1, std::stoull(value));
            else if (arg == "--threads")
                o.threads = std::max(1, std::stoi(value));
            else if (arg == "--scale")
                o.scale = std::stod(value);
            else if (arg == "--csv")
                o.csv = value;
            else
                usage(2);
        } catch (const std::logic_error&) {  // stoi & co.: not a number
            std::fprintf(stderr, "%s %s: not a number\n", arg.c_str(), value.c_str());
            usage(2);
        }
    }
    if (!(o.scale > 0 && o.scale <= 1)) {
        std::fprintf(stderr, "--scale must be in (0, 1]\n");
        usage(2);
    }
    return o;
}

std::string todaysCsv() {
    const std::time_t now = std::time(nullptr);
    char date[16];
    std::strftime(date, sizeof date, "%Y-%m-%d", std::localtime(&now));
    return std::string(CAUSTICA_SOURCE_DIR) + "/bench/results/spatial-" + date + ".csv";
}

// ---- point sets ---------------------------------------------------------------------------------

/// One set of points to build the structures over, with its queries.
struct BenchSet {
    std::string name;               // `set`: uniform/points, <scene>/photons, <source>/spheres
    std::vector<Vec3f> positions;   // the points (photons; visible points for spheres)
    std::vector<Float> radii;       // spheres: each point's radius; points: empty
    Float radius = 0;               // points: the common (build) radius
    std::vector<Vec3f> queries;     // ball centres, covered points or segment origins
    std::vector<Float> queryRadii;  // points: each query's gather radius
    std::vector<Vec3f> directions;  // spheres: each segment's unit direction
    Float segmentLength = 0;        // spheres: every segment's tMax

    bool spheres() const { return !radii.empty(); }
};

Float median(std::vector<Float> v) {
    if (v.empty()) return 0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

Vec3f extentOf(const std::vector<Vec3f>& points) {
    Bounds3f box;
    for (const Vec3f& p : points) box.extend(p);
    return box.empty() ? Vec3f(0) : box.diagonal();
}

/// The radius that sizes the structures: the common one, or the largest sphere's.
Float buildRadius(const BenchSet& s) {
    return s.spheres() ? *std::max_element(s.radii.begin(), s.radii.end()) : s.radius;
}

/// The typical ball of a query: the median sphere radius (spheres) or query radius (points).
Float typicalRadius(const BenchSet& s) {
    return median(s.spheres() ? s.radii : s.queryRadii);
}

/// `n` uniform values in [0, 1)^3 from stream `seed` (fixed: the same sets on every run).
std::vector<Vec3f> randomUnitCube(size_t n, uint64_t seed) {
    std::vector<Vec3f> p(n);
    for (size_t i = 0; i < n; ++i) {
        IndependentSampler s(i, 0, seed);
        const Float x = s.get1D(), y = s.get1D();
        p[i] = Vec3f(x, y, s.get1D());
    }
    return p;
}

std::vector<Vec3f> randomDirections(size_t n, uint64_t seed) {
    std::vector<Vec3f> d(n);
    for (size_t i = 0; i < n; ++i) {
        IndependentSampler s(i, 0, seed);
        d[i] = sampleUniformSphere(s.get2D());
    }
    return d;
}

/// The spheres set's segments: random directions, length 10 x the median sphere radius.
void addSegments(BenchSet& s) {
    s.directions = randomDirections(s.queries.size(), 0x5e6);
    s.segmentLength = 10 * median(s.radii);
}

size_t scaled(size_t n, double scale) {
    return std::max<size_t>(1, size_t(std::llround(double(n) * scale)));
}

/// 1M points in the unit cube and 100k queries. With --scale the radius grows by scale^(-1/3),
/// so that a ball still holds about 30 points and a smoke run exercises the same code paths.
std::vector<BenchSet> uniformSets(double scale) {
    const Float r = Float(0.0193 / std::cbrt(scale));
    BenchSet points;
    points.name = "uniform/points";
    points.positions = randomUnitCube(scaled(1000000, scale), 1);
    points.radius = r;
    points.queries = randomUnitCube(scaled(100000, scale), 2);
    points.queryRadii.assign(points.queries.size(), r);

    BenchSet spheres;
    spheres.name = "uniform/spheres";
    spheres.positions = points.positions;
    spheres.radii.resize(spheres.positions.size());
    for (size_t i = 0; i < spheres.radii.size(); ++i)
        spheres.radii[i] = r * (Float(0.5) + IndependentSampler(i, 0, 3).get1D());
    spheres.queries = points.queries;
    addSegments(spheres);
    return {std::move(points), std::move(spheres)};
}

struct SceneSource {
    const char* name;  // --sets
    const char* file;  // under the source tree
    int width, height;
};

const SceneSource kScenes[] = {
    {"cornell-water", "scenes/cornell-water/scene.xml", 256, 256},
    {"glass-caustic", "scenes/glass-caustic/scene.xml", 256, 256},
    {"water-1080p", "scenes/cornell-water/scene.xml", 1920, 1080},
};

/// The scene's <integrator> parameters (max_depth, rr_depth, ...) read as sppm's, direction
/// gather (the default; the only one that stores photons), photon_count --photons x scale unless
/// the scene gives one.
SppmSettings sceneSppmSettings(const Scene& scene, const Options& o) {
    std::vector<IntegratorParam> overrides = {
        {"direction", IntegratorParam::Kind::Text, "gather", "spatial_bench"}};
    if (!IntegratorParams(scene.integrator).has("photon_count"))
        overrides.push_back({"photon_count", IntegratorParam::Kind::Text,
                             std::to_string(scaled(o.photons, o.scale)), "--photons"});
    IntegratorParams params = integratorParams(scene.integrator, "sppm", overrides);
    return readSppmSettings(params, PhotonMapper::Sppm);
}

/// Renders --iterations SPPM iterations of the scene on the CPU and takes the point sets of the
/// last one: the photons with the largest visible-point radius as the common radius, gathered at
/// the visible points with their own radii (what gatherPass does), and the visible points' spheres
/// with the photons as queries (what the deposit direction does).
std::vector<BenchSet> sceneSets(const SceneSource& src, const Options& o) {
    const double side = std::sqrt(o.scale);  // --scale: the image area
    const int w = std::max(1, int(std::lround(src.width * side)));
    const int h = std::max(1, int(std::lround(src.height * side)));
    Scene scene = loadScene(std::string(CAUSTICA_SOURCE_DIR) + "/" + src.file,
                            {{"width", std::to_string(w)}, {"height", std::to_string(h)}});
    const SppmSettings settings = sceneSppmSettings(scene, o);
    const auto start = Clock::now();
    SppmLookupInputs in;
    Float initialRadius = 0;
    {
        const Accel accel(scene, AccelKind::Embree);
        auto driver = makeSppmDriver<CpuExec>(scene, accel, settings, scene.seed);
        for (int i = 0; i < o.iterations; ++i) driver->iterate();
        in = driver->lookupInputs();
        initialRadius = driver->settings().initialRadius;  // the automatic one, once resolved
    }  // the driver's and the accel's memory go before the measurements
    std::printf(
        "%s: %s at %dx%d, sppm %d iterations of %llu photon paths (direction gather, "
        "initial radius %.4g) in %.1f s: %zu photons stored, %zu visible points\n",
        src.name, src.file, w, h, o.iterations, (unsigned long long)settings.photonCount,
        double(initialRadius), msSince(start) * 1e-3, in.photons.size(), in.visiblePoints.size());
    if (in.photons.empty() || in.visiblePoints.empty())
        throw Error(std::string(src.name) + ": no photons or no visible points");

    BenchSet photons;
    photons.name = std::string(src.name) + "/photons";
    photons.positions = in.photons;
    photons.radius = *std::max_element(in.visibleRadii.begin(), in.visibleRadii.end());
    photons.queries = in.visiblePoints;
    photons.queryRadii = in.visibleRadii;

    BenchSet spheres;
    spheres.name = std::string(src.name) + "/spheres";
    spheres.positions = std::move(in.visiblePoints);
    spheres.radii = std::move(in.visibleRadii);
    spheres.queries = std::move(in.photons);
    addSegments(spheres);
    return {std::move(photons), std::move(spheres)};
}

// ---- structures ---------------------------------------------------------------------------------

/// One configuration of structure S: its name in the table and how it is built (on the CPU).
template <class S>
struct Variant {
    std::string name;
    std::function<S(const PointSet&)> build;
};

/// A string literal as a template argument (the names in the structure list).
template <size_t N>
struct Literal {
    char text[N];
    constexpr Literal(const char (&s)[N]) { std::copy_n(s, N, text); }
};

/// Structure S with its default build, named `name`.
template <class S, Literal name>
struct Defaults {
    static std::vector<Variant<S>> variants() {
        return {{name.text, [](const PointSet& p) { return S::build(CpuExec{}, p); }}};
    }
};

/// MultiHash with the rule's alternatives (docs/PHOTON_LOOKUP.md): the density rule with
/// leafPoints {512, 4096, 32768} x pointsPerCell {4, 16, 64} (pointsPerCell 1 was measured 10-50x
/// slower and left out), the radius rule and the coarser of both at leafPoints 4096.
struct MultiHashSweep {
    static std::vector<Variant<MultiHash>> variants() {
        std::vector<Variant<MultiHash>> sweep;
        auto add = [&](const char* name, MultiHashOptions options) {
            sweep.push_back({name, [options](const PointSet& p) { return MultiHash::build(CpuExec{}, p, options); }});
        };
        for (uint32_t leafPoints : {512u, 4096u, 32768u})
            for (Float pointsPerCell : {Float(4), Float(16), Float(64)}) {
                char name[64];
                std::snprintf(name, sizeof name, "multihash(L=%u,P=%g)", leafPoints, double(pointsPerCell));
                add(name, MultiHashOptions{leafPoints, pointsPerCell});
            }
        add("multihash(L=4096,radius)", MultiHashOptions{4096, 4, MultiHashCellRule::Radius});
        add("multihash(L=4096,P=16,coarser)", MultiHashOptions{4096, 16, MultiHashCellRule::Coarser});
        return sweep;
    }
};

template <class... Entries>
struct StructureList {};

/// Every structure measured, in table order: one line each. An entry is a type with
/// `static std::vector<Variant<S>> variants()` (Defaults, or a sweep of a structure's options).
/// BruteForce is left out: O(n) per query is hours at 1M points.
using Structures = StructureList<Defaults<UniformGrid, "grid">,  //
                                 Defaults<HashGrid, "hash">,     //
                                 Defaults<KdTree, "kdtree">,     //
                                 MultiHashSweep>;

template <class... Entries, class F>
void forEachStructure(StructureList<Entries...>, F&& f) {
    (f(Entries::variants()), ...);
}

bool selected(const std::vector<std::string>& prefixes, const std::string& name) {
    if (prefixes.empty()) return true;
    for (const std::string& p : prefixes)
        if (name.compare(0, p.size(), p) == 0) return true;
    return false;
}

// ---- queries ------------------------------------------------------------------------------------

enum class Query { Within, Knn16, Covering, Segment };

const char* queryName(Query q) {
    switch (q) {
        case Query::Within:
            return "within";
        case Query::Knn16:
            return "knn16";
        case Query::Covering:
            return "covering";
        case Query::Segment:
            return "segment";
    }
    return "?";
}

std::vector<Query> queriesOf(const BenchSet& s) {
    if (s.spheres()) return {Query::Covering, Query::Segment};
    return {Query::Within, Query::Knn16};
}

/// Per query: how many results and the sum of their indices (written by the kernels).
struct QueryOutputs {
    std::vector<uint32_t> counts;
    std::vector<uint64_t> indexSums;
    explicit QueryOutputs(size_t n) : counts(n), indexSums(n) {}
};

/// The totals over all queries: what every structure must agree on.
struct Totals {
    uint64_t results = 0, indexSum = 0;
    bool operator==(const Totals&) const = default;
};

Totals totalsOf(const QueryOutputs& out) {
    Totals t;
    for (size_t i = 0; i < out.counts.size(); ++i) {
        t.results += out.counts[i];
        t.indexSum += out.indexSums[i];
    }
    return t;
}

/// Runs query(i, add) for every query i on all threads (one launch): `add(j)` for each result j
/// counts it and adds j to the query's index sum, written to `out` when the query is done.
template <class QueryFn>
void launchQueries(const char* name, size_t n, QueryOutputs& out, const QueryFn& query) {
    uint32_t* counts = out.counts.data();
    uint64_t* sums = out.indexSums.data();
    launch(CpuExec{}, name, n, [=](size_t i) {
        uint32_t count = 0;
        uint64_t sum = 0;
        query(i, [&](uint32_t j) {
            ++count;
            sum += j;
        });
        counts[i] = count;
        sums[i] = sum;
    });
}

/// Runs every query of `s` of type q; returns the milliseconds.
template <class View>
double runQueries(const View& view, Query q, const BenchSet& s, QueryOutputs& out) {
    const Vec3f* centers = s.queries.data();
    const Float* radii = s.queryRadii.data();
    const Vec3f* dirs = s.directions.data();
    const Float length = s.segmentLength;
    const size_t n = s.queries.size();
    const auto start = Clock::now();
    switch (q) {
        case Query::Within:
            launchQueries("bench.within", n, out, [=](size_t i, auto&& add) {
                view.forEachPointWithin(centers[i], radii[i], add);
            });
            break;
        case Query::Knn16:
            launchQueries("bench.knn16", n, out, [=](size_t i, auto&& add) {
                uint32_t nearest[16], count = 0;
                view.kNearest(centers[i], 16, 2 * radii[i], nearest, count);
                for (uint32_t k = 0; k < count; ++k) add(nearest[k]);
            });
            break;
        case Query::Covering:
            launchQueries("bench.covering", n, out, [=](size_t i, auto&& add) {
                view.forEachSphereCovering(centers[i], add);
            });
            break;
        case Query::Segment:
            launchQueries("bench.segment", n, out, [=](size_t i, auto&& add) {
                view.forEachSphereOnSegment(centers[i], dirs[i], length, add);
            });
            break;
    }
    return msSince(start);
}

// ---- measurement and output ---------------------------------------------------------------------

/// One row of the CSV and the table.
struct Row {
    std::string set, structure, query;
    size_t points = 0, queries = 0;
    double buildMs = 0, bytesPerPoint = 0, queryMs = 0, resultsPerQuery = 0;
    int threads = 0;
    Vec3f extent;
    Float radius = 0, medianRadius = 0;
};

class Report {
public:
    explicit Report(const std::string& path) : path_(path) {
        std::filesystem::create_directories(std::filesystem::path(path).parent_path());
        file_ = std::fopen(path.c_str(), "w");
        if (!file_) throw Error("cannot write " + path);
        std::fprintf(
            file_,
            "set,points,structure,query,build_ms,bytes_per_point,queries,query_ms,queries_per_s,"
            "results_per_query,threads,extent_x,extent_y,extent_z,radius,median_radius\n");
    }
    ~Report() {
        if (file_) std::fclose(file_);
    }
    Report(const Report&) = delete;
    Report& operator=(const Report&) = delete;

    static void printHeader() {
        std::printf("%-22s %-24s %-9s %9s %7s %9s %10s %10s %9s\n", "set", "structure", "query",
                    "build ms", "B/pt", "queries", "query ms", "Mq/s", "res/q");
    }
    /// Prints the row (the table) and appends it to the CSV at once (a long run keeps its rows).
    void add(const Row& r) {
        const double perSecond = r.queryMs > 0 ? double(r.queries) / (r.queryMs * 1e-3) : 0;
        std::printf("%-22s %-24s %-9s %9.1f %7.2f %9zu %10.1f %10.3f %9.2f\n", r.set.c_str(),
                    r.structure.c_str(), r.query.c_str(), r.buildMs, r.bytesPerPoint, r.queries,
                    r.queryMs, perSecond * 1e-6, r.resultsPerQuery);
        std::fflush(stdout);
        std::fprintf(file_,
                     "%s,%zu,\"%s\",%s,%.3f,%.3f,%zu,%.3f,%.1f,%.4f,%d,%.6g,%.6g,%.6g,%.6g,%.6g\n",
                     r.set.c_str(), r.points, r.structure.c_str(), r.query.c_str(), r.buildMs,
                     r.bytesPerPoint, r.queries, r.queryMs, perSecond, r.resultsPerQuery, r.threads,
                     double(r.extent.x), double(r.extent.y), double(r.extent.z), double(r.radius),
                     double(r.medianRadius));
        std::fflush(file_);
    }
    const std::string& path() const { return path_; }

private:
    std::string path_;
    std::FILE* file_ = nullptr;
};

/// The totals of the first structure measured for each (set, query), and every disagreement.
class AgreementCheck {
public:
    void check(const std::string& set, Query q, const std::string& structure, const Totals& t) {
        const std::string key = set + " " + queryName(q);
        auto [it, first] = reference_.try_emplace(key, structure, t);
        if (first || it->second.second == t) return;
        const auto& [refName, ref] = it->second;
        std::printf(
            "\n!!!!! ERROR: %s: %s returned %llu results (index sum %llu), %s returned %llu (index "
            "sum %llu): the structures disagree !!!!!\n\n",
            key.c_str(), structure.c_str(), (unsigned long long)t.results,
            (unsigned long long)t.indexSum, refName.c_str(), (unsigned long long)ref.results,
            (unsigned long long)ref.indexSum);
        ++failures_;
    }
    int failures() const { return failures_; }

private:
    std::map<std::string, std::pair<std::string, Totals>> reference_;
    int failures_ = 0;
};

struct Context {
    const Options& options;
    int threads;
    Report& report;
    AgreementCheck& agreement;
};

/// A point set in device memory (the CPU's), with the statistics its rows carry.
struct PreparedSet {
    const BenchSet& set;
    Buffer<Vec3f> positions;
    Buffer<Float> radii;
    Vec3f extent;
    Float radius = 0, medianRadius = 0;

    explicit PreparedSet(const BenchSet& s)
        : set(s),
          positions(Device::cpu(), s.positions),
          radii(Device::cpu(), s.radii),
          extent(extentOf(s.positions)),
          radius(buildRadius(s)),
          medianRadius(typicalRadius(s)) {}
    PointSet points() const {
        return PointSet{positions.constSpan(), radii.constSpan(), set.radius};
    }
};

/// Builds variant v --repeat times (best time), then runs each query type --repeat times (best
/// time) and reports a row per query type. Every run's totals go to the agreement check: a
/// structure's results depend on its build only, so its repeats must agree as well.
template <class S>
void measure(const Variant<S>& v, const PreparedSet& p, Context& c) {
    const BenchSet& s = p.set;
    const int repeat = c.options.repeat;
    std::optional<S> structure;
    double buildMs = 1e300;
    for (int r = 0; r < repeat; ++r) {
        structure.reset();  // one structure in memory at a time
        const auto start = Clock::now();
        structure.emplace(v.build(p.points()));
        buildMs = std::min(buildMs, msSince(start));
    }
    const auto view = structure->view();
    for (Query q : queriesOf(s)) {
        QueryOutputs out(s.queries.size());
        double queryMs = 1e300;
        Totals totals;
        for (int r = 0; r < repeat; ++r) {
            queryMs = std::min(queryMs, runQueries(view, q, s, out));
            totals = totalsOf(out);
            c.agreement.check(s.name, q, v.name, totals);
        }
        Row row;
        row.set = s.name;
        row.structure = v.name;
        row.query = queryName(q);
        row.points = s.positions.size();
        row.queries = s.queries.size();
        row.buildMs = buildMs;
        row.bytesPerPoint =
            double(structure->memoryBytes()) / double(std::max<size_t>(1, row.points));
        row.queryMs = queryMs;
        row.resultsPerQuery = double(totals.results) / double(std::max<size_t>(1, row.queries));
        row.threads = c.threads;
        row.extent = p.extent;
        row.radius = p.radius;
        row.medianRadius = p.medianRadius;
        c.report.add(row);
    }
}

void printSetStatistics(const PreparedSet& p) {
    const BenchSet& s = p.set;
    std::printf("\n%s: %zu %s, box extent %.4g x %.4g x %.4g, ", s.name.c_str(), s.positions.size(),
                s.spheres() ? "spheres" : "points", double(p.extent.x), double(p.extent.y),
                double(p.extent.z));
    if (s.spheres())
        std::printf("radius median %.4g, largest %.4g; %zu queries, segments of length %.4g\n",
                    double(p.medianRadius), double(p.radius), s.queries.size(),
                    double(s.segmentLength));
    else
        std::printf("common radius %.4g; %zu queries, query radius median %.4g\n", double(p.radius),
                    s.queries.size(), double(p.medianRadius));
}

/// Every selected structure on one point set.
void measureSet(const BenchSet& s, Context& c) {
    const PreparedSet prepared(s);
    printSetStatistics(prepared);
    Report::printHeader();
    forEachStructure(Structures{}, [&](const auto& variants) {
        for (const auto& v : variants)
            if (selected(c.options.structures, v.name)) measure(v, prepared, c);
    });
}

bool wanted(const Options& o, const std::string& set) {
    return o.sets.empty() || std::find(o.sets.begin(), o.sets.end(), set) != o.sets.end();
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parseOptions(argc, argv);
    for (const std::string& name : o.sets) {
        bool known = name == "uniform";
        for (const SceneSource& src : kScenes) known = known || name == src.name;
        if (!known) {
            std::fprintf(stderr, "unknown set '%s'\n", name.c_str());
            usage(2);
        }
    }
    std::unique_ptr<tbb::global_control> threadLimit;
    if (o.threads > 0)
        threadLimit = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, size_t(o.threads));
    const int threads =
        int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));

    try {
        Report report(o.csv.empty() ? todaysCsv() : o.csv);
        AgreementCheck agreement;
        Context context{o, threads, report, agreement};
        std::printf("spatial_bench: %d threads, best of %d, scale %g\n", threads, o.repeat,
                    o.scale);
        const auto start = Clock::now();
        if (wanted(o, "uniform"))
            for (const BenchSet& s : uniformSets(o.scale)) measureSet(s, context);
        for (const SceneSource& src : kScenes) {
            if (!wanted(o, src.name)) continue;
            for (const BenchSet& s : sceneSets(src, o)) measureSet(s, context);
        }
        std::printf("\nwrote %s (%.0f s)\n", report.path().c_str(), msSince(start) * 1e-3);
        if (agreement.failures() > 0) {
            std::printf("!!!!! ERROR: %d disagreement(s) between structures (see above) !!!!!\n",
                        agreement.failures());
            return 1;
        }
        std::printf("all structures agree (result counts and index sums of every set and query)\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "spatial_bench: %s\n", e.what());
        return 1;
    }
    return 0;
}
