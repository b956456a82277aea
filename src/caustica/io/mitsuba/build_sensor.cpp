// build_sensor.cpp — Mitsuba 3's projective sensors -> Camera (scene/camera.h); their film and
// sampler are built by build_film.cpp.
//
// | plugin       | parameters (default)                                                    |
// |--------------|-------------------------------------------------------------------------|
// | perspective  | fov or focal_length ("50mm"), fov_axis (x | y | diagonal | smaller |    |
// |              | larger), near_clip (0.01), far_clip (10000), to_world (no scaling)      |
// | thinlens     | as perspective, plus aperture_radius (required), focus_distance         |
// |              | (far_clip)                                                              |
// | orthographic | near_clip, far_clip, to_world (its scale sets the extent: camera space  |
// |              | spans [-1, 1] horizontally)                                             |
#include <cmath>

#include "caustica/io/mitsuba/build_context.h"
#include "caustica/io/mitsuba/build_film.h"
#include "caustica/io/mitsuba/plugin_table.h"
#include "caustica/util/error.h"

namespace caustica::mitsuba {

namespace {

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

/// What every sensor shares: film (size, crop window), sampler, clip planes and to_world.
void commonSensor(BuildContext& ctx, Params& p) {
    Scene& scene = ctx.scene;
    Camera& cam = scene.camera;
    cam.width = scene.film.width;
    cam.height = scene.film.height;
    std::vector<int> films = p.takeChildren("film");
    if (films.size() > 1) p.failAtChild(films[1], "takes at most one <film>");
    if (!films.empty()) scene.film = buildFilm(ctx, films[0], cam);
    std::vector<int> samplers = p.takeChildren("sampler");
    if (samplers.size() > 1) p.failAtChild(samplers[1], "takes at most one <sampler>");
    if (!samplers.empty()) buildSampler(ctx, samplers[0]);
    cam.nearClip = p.getFloat("near_clip", 1e-2f);
    cam.farClip = p.getFloat("far_clip", 1e4f);
    if (!(cam.nearClip > 0)) p.fail(*p.find("near_clip"), "must be positive");
    if (!(cam.nearClip < cam.farClip)) p.fail("'near_clip' must be smaller than 'far_clip'");
    cam.worldFromCamera = p.getTransform("to_world");
}

/// Perspective and thin lens: field of view, no scaling in to_world (Mitsuba refuses it too).
void projectiveSensor(BuildContext& ctx, Params& p) {
    commonSensor(ctx, p);
    Camera& cam = ctx.scene.camera;
    const double aspect = double(cam.width) / double(cam.height);
    const double fovX = horizontalFov(p, aspect);
    cam.tanHalfX = Float(std::tan(0.5 * fovX * M_PI / 180.0));
    cam.tanHalfY = Float(std::tan(0.5 * fovX * M_PI / 180.0) / aspect);
    for (const char* pp : {"principal_point_offset_x", "principal_point_offset_y"})
        p.refuse(pp, "(off-axis projection) is not supported yet");
    for (int c = 0; c < 3; ++c) {
        Vec3f col(cam.worldFromCamera.m.m[0][c], cam.worldFromCamera.m.m[1][c],
                  cam.worldFromCamera.m.m[2][c]);
        if (std::fabs(lengthSquared(col) - 1) > 1e-3f)
            p.fail(*p.find("to_world"), "must not scale (Mitsuba refuses scaled sensors too)");
    }
}

void perspectiveSensor(BuildContext& ctx, Params& p) {
    ctx.scene.camera.type = CameraType::Perspective;
    projectiveSensor(ctx, p);
}

/// Mitsuba 3's thinlens: aperture_radius is required (0 is a pinhole: Mitsuba warns and uses
/// a radius of one float epsilon), focus_distance defaults to far_clip.
void thinLensSensor(BuildContext& ctx, Params& p) {
    Camera& cam = ctx.scene.camera;
    cam.type = CameraType::ThinLens;
    projectiveSensor(ctx, p);
    cam.apertureRadius = p.getFloat("aperture_radius");
    if (!(cam.apertureRadius >= 0)) p.fail(*p.find("aperture_radius"), "must not be negative");
    cam.focusDistance = p.getFloat("focus_distance", cam.farClip);
    if (!(cam.focusDistance > 0)) p.fail(*p.find("focus_distance"), "must be positive");
}

/// Mitsuba 3's orthographic: camera space spans x in [-1, 1] and y in [-1/aspect, 1/aspect];
/// to_world (scale allowed) maps it into the scene.
void orthographicSensor(BuildContext& ctx, Params& p) {
    Camera& cam = ctx.scene.camera;
    cam.type = CameraType::Orthographic;
    commonSensor(ctx, p);
    cam.tanHalfX = 1;
    cam.tanHalfY = Float(double(cam.height) / double(cam.width));
    const Vec3f axis = cam.worldFromCamera.applyVector(Vec3f(0, 0, 1));
    if (!(length(axis) > 0)) p.fail(*p.find("to_world"), "must not collapse the view direction");
}

using SensorFn = void (*)(BuildContext&, Params&);
const PluginTable<SensorFn> kSensorPlugins{{{"orthographic", orthographicSensor},
                                            {"perspective", perspectiveSensor},
                                            {"thinlens", thinLensSensor}}};

}  // namespace

void buildSensor(BuildContext& ctx, int object) {
    ctx.used.insert(object);
    Params p(ctx.desc, object);
    kSensorPlugins.find(p)(ctx, p);
    p.finish(ctx.warnings);
}

}  // namespace caustica::mitsuba
