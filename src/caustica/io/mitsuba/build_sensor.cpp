// build_sensor.cpp — Mitsuba 3's perspective sensor with its film, reconstruction filter and
// sampler -> Camera, FilmDesc and the sample count.
//
// | plugin      | parameters (default)                                                      |
// |-------------|---------------------------------------------------------------------------|
// | perspective | fov or focal_length ("50mm"), fov_axis (x | y | diagonal | smaller |      |
// |             | larger), near_clip (0.01), far_clip (10000), to_world (no scaling)        |
// | hdrfilm     | width (768), height (576), rfilter (gaussian); pixel_format,             |
// |             | component_format, file_format ignored; crop_* refused                    |
// | box/tent/gaussian rfilter | tent: radius (1); gaussian: stddev (0.5), radius 4 stddev  |
// | independent | sample_count (4), seed (0)                                                |
#include <cmath>

#include "caustica/io/mitsuba/build_context.h"
#include "caustica/io/mitsuba/plugin_table.h"
#include "caustica/util/error.h"

namespace caustica::mitsuba {

namespace {

/// At most one child of `category`; -1 when there is none.
int singleChild(Params& p, const std::string& category) {
    std::vector<int> c = p.takeChildren(category);
    if (c.size() > 1) p.failAtChild(c[1], "takes at most one <" + category + ">");
    return c.empty() ? -1 : c[0];
}

FilterDesc boxFilter(Params&) {
    return {FilterType::Box, 0.5f, 0.5f};
}

FilterDesc tentFilter(Params& p) {
    Float r = p.getFloat("radius", 1.0f);
    if (!(r > 0)) p.fail(*p.find("radius"), "must be positive");
    return {FilterType::Tent, r, 0.5f};
}

FilterDesc gaussianFilter(Params& p) {
    Float s = p.getFloat("stddev", 0.5f);
    if (!(s > 0)) p.fail(*p.find("stddev"), "must be positive");
    return {FilterType::Gaussian, 4 * s, s};
}

using FilterFn = FilterDesc (*)(Params&);
const PluginTable<FilterFn> kFilterPlugins{
    {{"box", boxFilter}, {"gaussian", gaussianFilter}, {"tent", tentFilter}}};

FilmDesc hdrFilm(BuildContext& ctx, Params& p) {
    FilmDesc film;
    film.width = p.getInt("width", 768);
    film.height = p.getInt("height", 576);
    if (film.width <= 0 || film.height <= 0 || film.width > 32768 || film.height > 32768 ||
        int64_t(film.width) * film.height > (int64_t(1) << 28))
        p.fail("absurd resolution " + std::to_string(film.width) + "x" +
               std::to_string(film.height) + " (each side 1..32768, at most 2^28 pixels)");
    for (const char* crop : {"crop_offset_x", "crop_offset_y", "crop_width", "crop_height"})
        p.refuse(crop, "(film cropping) is not supported yet");
    for (const char* ignored : {"pixel_format", "component_format", "file_format"})
        p.ignore(ignored, ctx.warnings);
    int rfilter = singleChild(p, "rfilter");
    if (rfilter >= 0) {
        ctx.used.insert(rfilter);
        Params fp(ctx.desc, rfilter);
        film.filter = kFilterPlugins.find(fp)(fp);
        fp.finish(ctx.warnings);
    }
    return film;
}

void independentSampler(BuildContext& ctx, Params& p) {
    int count = p.getInt("sample_count", 4);
    if (count <= 0) p.fail(*p.find("sample_count"), "must be positive");
    int seed = p.getInt("seed", 0);
    if (seed < 0) p.fail(*p.find("seed"), "must not be negative");
    ctx.scene.sampleCount = count;
    ctx.scene.seed = uint64_t(seed);
}

/// Mitsuba 3's parse_fov: the horizontal field of view in degrees for the given aspect ratio.
double horizontalFov(const Params& p, double aspect) {
    if (p.has("fov") && p.has("focal_length"))
        p.fail("give either 'fov' or 'focal_length', not both");
    double fov;
    std::string axis;
    if (p.has("fov")) {
        fov = p.getFloat("fov");
        if (!(fov > 0 && fov < 180)) p.fail(*p.find("fov"), "must be between 0 and 180 degrees");
        axis = p.getString("fov_axis", "x");
        if (axis == "smaller" || axis == "larger")
            axis = std::string(1, (axis == "smaller") == (aspect > 1) ? 'y' : 'x');
    } else {
        std::string f = p.getString("focal_length", "50mm");
        if (f.size() > 2 && f.compare(f.size() - 2, 2, "mm") == 0) f.resize(f.size() - 2);
        char* end = nullptr;
        double mm = std::strtod(f.c_str(), &end);
        if (f.empty() || *end != '\0' || !(mm > 0)) p.fail("'focal_length' must look like '50mm'");
        // 35 mm film: the diagonal of a 36 x 24 mm frame.
        fov = 2.0 * std::atan(std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2.0 * mm)) * 180.0 / M_PI;
        axis = "diagonal";
    }
    const double deg = M_PI / 180.0;
    if (axis == "x") return fov;
    if (axis == "y") return 2.0 * std::atan(std::tan(0.5 * fov * deg) * aspect) / deg;
    if (axis == "diagonal") {
        double diagonal = 2.0 * std::tan(0.5 * fov * deg);
        double width = diagonal / std::sqrt(1.0 + 1.0 / (aspect * aspect));
        return 2.0 * std::atan(0.5 * width) / deg;
    }
    p.fail(*p.find("fov_axis"), "must be x, y, diagonal, smaller or larger, not '" + axis + "'");
}

void perspectiveSensor(BuildContext& ctx, Params& p) {
    Scene& scene = ctx.scene;
    int film = singleChild(p, "film");
    if (film >= 0) {
        ctx.used.insert(film);
        Params fp(ctx.desc, film);
        if (fp.object().type != "hdrfilm") {
            const ObjectEntity& f = fp.object();
            throw Error(f.where.file, f.where.line,
                        "unsupported film type '" + f.type + "'" +
                            (f.type == "specfilm" ? ": spectral rendering is not supported" : "") +
                            " (supported: hdrfilm)");
        }
        scene.film = hdrFilm(ctx, fp);
        fp.finish(ctx.warnings);
    }
    int sampler = singleChild(p, "sampler");
    if (sampler >= 0) {
        ctx.used.insert(sampler);
        Params sp(ctx.desc, sampler);
        if (sp.object().type != "independent") {
            const ObjectEntity& s = sp.object();
            throw Error(s.where.file, s.where.line,
                        "unsupported sampler type '" + s.type + "' (supported: independent)");
        }
        independentSampler(ctx, sp);
        sp.finish(ctx.warnings);
    }
    Camera& cam = scene.camera;
    cam.width = scene.film.width;
    cam.height = scene.film.height;
    const double aspect = double(cam.width) / double(cam.height);
    const double fovX = horizontalFov(p, aspect);
    cam.tanHalfX = Float(std::tan(0.5 * fovX * M_PI / 180.0));
    cam.tanHalfY = Float(std::tan(0.5 * fovX * M_PI / 180.0) / aspect);
    cam.nearClip = p.getFloat("near_clip", 1e-2f);
    cam.farClip = p.getFloat("far_clip", 1e4f);
    if (!(cam.nearClip > 0)) p.fail(*p.find("near_clip"), "must be positive");
    if (!(cam.nearClip < cam.farClip)) p.fail("'near_clip' must be smaller than 'far_clip'");
    for (const char* pp : {"principal_point_offset_x", "principal_point_offset_y"})
        p.refuse(pp, "(off-axis projection) is not supported yet");
    cam.worldFromCamera = p.getTransform("to_world");
    for (int c = 0; c < 3; ++c) {
        Vec3f col(cam.worldFromCamera.m.m[0][c], cam.worldFromCamera.m.m[1][c],
                  cam.worldFromCamera.m.m[2][c]);
        if (std::fabs(lengthSquared(col) - 1) > 1e-3f)
            p.fail(*p.find("to_world"), "must not scale (Mitsuba refuses scaled sensors too)");
    }
}

using SensorFn = void (*)(BuildContext&, Params&);
const PluginTable<SensorFn> kSensorPlugins{{{"perspective", perspectiveSensor}}};

}  // namespace

void buildSensor(BuildContext& ctx, int object) {
    ctx.used.insert(object);
    Params p(ctx.desc, object);
    kSensorPlugins.find(p)(ctx, p);
    p.finish(ctx.warnings);
}

}  // namespace caustica::mitsuba
