// emitter_sensor_plugins_test.cpp — loading the spot, directional and envmap emitters, area
// emitters on every shape type, the thinlens and orthographic sensors, crop windows, the ldrfilm
// and the sampler plugins: parameters with Mitsuba's names and defaults, and their errors.
#include <cmath>

#include "caustica/io/image_io.h"
#include "caustica/scene/light_delta.h"
#include "scene_test_util.h"

namespace caustica::test {
namespace {

constexpr double kDeg = M_PI / 180.0;

Scene load(const std::string& body, std::vector<std::string>* warnings = nullptr) {
    TempDir dir;
    return loadXml(dir, sceneXml(body), warnings);
}

void expectBad(const std::string& body, int line, const std::string& reason, bool sensor = true) {
    TempDir dir;
    const std::string path = dir.write("e.xml", sceneXml(body, sensor));
    expectError([&] { loadScene(path); }, "e.xml", line, reason);
}

TEST(SpotEmitter, DefaultsAndTransform) {
    Scene s = load(R"(<emitter type="spot"/>
        <emitter type="spot"><rgb name="intensity" value="2, 3, 4"/>
            <float name="cutoff_angle" value="40"/><float name="beam_width" value="10"/>
            <transform name="to_world"><lookat origin="1, 2, 3" target="1, 0, 3" up="0, 0, 1"/></transform>
        </emitter>)");
    ASSERT_EQ(s.lights.size(), 2u);
    const Light& a = s.lights[0];
    EXPECT_EQ(a.type, LightType::Spot);
    EXPECT_EQ(a.radiance.g, 1.0f);
    EXPECT_NEAR(a.cutoff, 20 * kDeg, 1e-6);
    EXPECT_NEAR(a.cosBeam, std::cos(15 * kDeg), 1e-6);  // 3/4 of the cutoff
    EXPECT_NEAR(a.invTransition, 1 / (5 * kDeg), 1e-3);
    const Light& b = s.lights[1];
    EXPECT_EQ(b.radiance.b, 4.0f);
    EXPECT_NEAR(length(b.position - Vec3f(1, 2, 3)), 0, 1e-6);
    EXPECT_NEAR(b.cosCutoff, std::cos(40 * kDeg), 1e-6);
    // The axis (+z local) points down: world -y maps to local +z.
    EXPECT_NEAR(length(applyRows(b.localFromWorld, Vec3f(0, -1, 0)) - Vec3f(0, 0, 1)), 0, 1e-6);
}

TEST(DirectionalEmitter, DirectionOrTransform) {
    Scene s = load(R"(<shape type="cube"/>
        <emitter type="directional"><vector name="direction" value="0, -2, 0"/>
            <rgb name="irradiance" value="5"/></emitter>
        <emitter type="directional"><transform name="to_world"><rotate x="1" angle="90"/></transform>
        </emitter>
        <emitter type="directional"/>)");
    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_EQ(s.lights[0].type, LightType::Directional);
    EXPECT_EQ(s.lights[0].radiance.r, 5.0f);
    EXPECT_NEAR(length(s.lights[0].direction - Vec3f(0, -1, 0)), 0, 1e-6);
    EXPECT_NEAR(length(s.lights[1].direction - Vec3f(0, -1, 0)), 0, 1e-6);  // +z rotated
    EXPECT_NEAR(length(s.lights[2].direction - Vec3f(0, 0, 1)), 0, 1e-6);
    EXPECT_NEAR(s.lights[0].sceneRadius, std::sqrt(3.0f), 1e-3);  // the cube's bounding sphere
    EXPECT_EQ(s.environmentLight, -1);
}

/// A 6x4 EXR in `dir`, texel (x, y) = (x, y, 1).
std::string writeEnv(const TempDir& dir, const std::string& name = "env.exr") {
    Image img(6, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 6; ++x) img.set(x, y, Spectrum(Float(x), Float(y), 1));
    const std::string path = dir.path(name);
    writeImage(path, img);
    return path;
}

TEST(EnvMapEmitter, LoadsTexelsScaleAndDistribution) {
    TempDir dir;
    writeEnv(dir);
    Scene s = loadXml(dir, sceneXml(R"(<shape type="sphere"/>
        <emitter type="envmap"><string name="filename" value="env.exr"/>
            <float name="scale" value="2"/>
            <transform name="to_world"><rotate y="1" angle="90"/></transform></emitter>
        <emitter type="point"/>)"));
    ASSERT_EQ(s.lights.size(), 2u);
    const Light& l = s.lights[0];
    EXPECT_EQ(l.type, LightType::EnvMap);
    EXPECT_EQ(s.environmentLight, 0);
    EXPECT_EQ(l.texWidth, 6u);
    EXPECT_EQ(l.texHeight, 4u);
    ASSERT_EQ(s.lightTexels.size(), 24u);
    EXPECT_EQ(s.lightTexels[2 * 6 + 5].r, 10.0f);  // texel (5, 2) times the scale
    EXPECT_EQ(s.lightTexels[2 * 6 + 5].g, 4.0f);
    EXPECT_EQ(l.cdfCount, 3u + 3u * 6u);  // marginal over 3 patch rows, 6 patches per row
    EXPECT_EQ(s.lightCdf[l.cdfOffset + 2], 1.0f);
    EXPECT_GT(l.sceneRadius, 1.0f);
}

TEST(EnvMapEmitter, Refusals) {
    TempDir dir;
    writeEnv(dir);
    Image tiny(2, 2);
    writeImage(dir.path("tiny.exr"), tiny);
    auto bad = [&](const std::string& body, int line, const std::string& reason) {
        const std::string path = dir.write("e.xml", sceneXml(body));
        expectError([&] { loadScene(path); }, "e.xml", line, reason);
    };
    bad("<emitter type=\"envmap\">\n<string name=\"filename\" value=\"nope.exr\"/></emitter>", 4,
        "nope.exr");
    bad("<emitter type=\"envmap\">\n<string name=\"filename\" value=\"tiny.exr\"/></emitter>", 4,
        "at least 2x3 pixels");
    bad("<emitter type=\"constant\"/>\n<emitter type=\"envmap\"><string name=\"filename\" "
        "value=\"env.exr\"/></emitter>",
        4, "only one environment emitter (constant or envmap)");
    bad("<emitter type=\"envmap\"><string name=\"filename\" value=\"env.exr\"/>\n"
        "<float name=\"scale\" value=\"-1\"/></emitter>",
        4, "'scale' must not be negative");
}

TEST(EmitterRefusals, SpotAndDirectional) {
    expectBad("<emitter type=\"spot\">\n<float name=\"beam_width\" value=\"30\"/></emitter>", 4,
              "must be between 0 and cutoff_angle");
    expectBad("<emitter type=\"spot\">\n<float name=\"cutoff_angle\" value=\"0\"/></emitter>", 4,
              "must be in (0, 180] degrees");
    expectBad("<emitter type=\"directional\"><vector name=\"direction\" value=\"0, 0, 1\"/>"
              "<transform name=\"to_world\"/></emitter>",
              3, "either 'direction' or 'to_world'");
    expectBad("<emitter type=\"directional\"><vector name=\"direction\" value=\"0\"/></emitter>",
              3, "must be a nonzero vector");
}

/// Mitsuba 3 attaches an area emitter to any shape: every shape type's light gets its area.
TEST(AreaEmitter, OnEveryShapeType) {
    Scene s = load(R"(
        <shape type="rectangle"><emitter type="area"/></shape>
        <shape type="cube"><transform name="to_world"><scale value="0.5"/></transform><emitter type="area"/></shape>
        <shape type="disk"><emitter type="area"/></shape>
        <shape type="sphere"><float name="radius" value="2"/><emitter type="area"/></shape>)");
    ASSERT_EQ(s.lights.size(), 4u);
    const double areas[] = {4, 6, M_PI * (1 - 2.5e-5), 16 * M_PI};
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(s.lights[size_t(i)].type, LightType::Area);
        EXPECT_NEAR(s.lights[size_t(i)].area, areas[i], 1e-4 * areas[i]) << i;
        EXPECT_EQ(s.shapes[size_t(i)].light, i);
    }
}

Scene sensor(const std::string& type, const std::string& body,
             std::vector<std::string>* warnings = nullptr) {
    TempDir dir;
    return loadXml(dir, sceneXml("<sensor type=\"" + type + "\">" + body + "</sensor>", false),
                   warnings);
}

TEST(ThinLensSensor, ApertureAndFocus) {
    Scene s = sensor("thinlens", R"(<float name="aperture_radius" value="0.25"/>
        <float name="fov" value="60"/><float name="far_clip" value="50"/>)");
    EXPECT_EQ(s.camera.type, CameraType::ThinLens);
    EXPECT_EQ(s.camera.apertureRadius, 0.25f);
    EXPECT_EQ(s.camera.focusDistance, 50.0f);  // Mitsuba's default: far_clip
    EXPECT_NEAR(s.camera.tanHalfX, std::tan(30 * kDeg), 1e-6);
    Scene f = sensor("thinlens", R"(<float name="aperture_radius" value="0.1"/>
        <float name="focus_distance" value="3"/>)");
    EXPECT_EQ(f.camera.focusDistance, 3.0f);
    expectBad("<sensor type=\"thinlens\"/>", 3, "missing required parameter 'aperture_radius'", false);
    expectBad("<sensor type=\"thinlens\"><float name=\"aperture_radius\" value=\"0.1\"/>\n"
              "<transform name=\"to_world\"><scale value=\"2\"/></transform></sensor>",
              4, "must not scale", false);
}

TEST(OrthographicSensor, ExtentFromToWorld) {
    Scene s = sensor("orthographic", R"(<transform name="to_world"><scale value="3"/></transform>
        <film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="20"/></film>)");
    EXPECT_EQ(s.camera.type, CameraType::Orthographic);
    EXPECT_EQ(s.camera.tanHalfX, 1.0f);
    EXPECT_EQ(s.camera.tanHalfY, 0.5f);
    const Ray r = generateCameraRay(s.camera, Vec2f(0, 0));
    EXPECT_NEAR(r.o.x, 3, 1e-5);  // Mitsuba's extent [-1, 1] scaled by to_world
    EXPECT_NEAR(r.o.y, 1.5f, 1e-5);
}

TEST(CropWindow, RendersTheWindowWithTheFullCamera) {
    Scene s = sensor("perspective", R"(<float name="fov" value="50"/>
        <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="48"/>
            <integer name="crop_offset_x" value="10"/><integer name="crop_offset_y" value="6"/>
            <integer name="crop_width" value="20"/><integer name="crop_height" value="30"/></film>)");
    EXPECT_EQ(s.film.width, 20);
    EXPECT_EQ(s.film.height, 30);
    EXPECT_EQ(s.camera.width, 64);
    EXPECT_EQ(s.camera.height, 48);
    EXPECT_EQ(s.camera.cropX, 10);
    EXPECT_EQ(s.camera.cropY, 6);
    EXPECT_NEAR(s.camera.tanHalfY, std::tan(25 * kDeg) * 48 / 64, 1e-6);  // the full aspect
    expectBad("<sensor type=\"perspective\">\n<film type=\"ldrfilm\">\n"
              "<integer name=\"width\" value=\"10\"/><integer name=\"crop_offset_x\" value=\"2\"/>"
              "<integer name=\"crop_width\" value=\"9\"/></film></sensor>",
              4, "crop window 9x576 at (2, 0) does not fit in the 10x576 film", false);
    expectBad("<sensor type=\"perspective\">\n<film type=\"hdrfilm\">\n"
              "<integer name=\"crop_offset_y\" value=\"-1\"/></film></sensor>",
              5, "'crop_offset_y' must not be negative", false);
}

TEST(LdrFilm, ToneMapParameters) {
    Scene d = sensor("perspective", R"(<film type="ldrfilm"/>)");
    EXPECT_TRUE(d.film.tonemap.ldr);
    EXPECT_EQ(d.film.tonemap.method, ToneMapMethod::Gamma);
    EXPECT_EQ(d.film.tonemap.gamma, -1.0f);
    EXPECT_EQ(d.film.tonemap.exposure, 0.0f);
    Scene r = sensor("perspective", R"(<film type="ldrfilm">
        <string name="tonemap_method" value="reinhard"/><float name="gamma" value="2.2"/>
        <float name="key" value="0.3"/><float name="burn" value="0.5"/>
        <float name="exposure" value="1"/></film>)");
    EXPECT_EQ(r.film.tonemap.method, ToneMapMethod::Reinhard);
    EXPECT_FLOAT_EQ(r.film.tonemap.gamma, 2.2f);
    EXPECT_FLOAT_EQ(r.film.tonemap.key, 0.3f);
    EXPECT_FLOAT_EQ(r.film.tonemap.burn, 0.5f);
    Scene h = sensor("perspective", R"(<film type="hdrfilm"/>)");
    EXPECT_FALSE(h.film.tonemap.ldr);
    expectBad("<sensor type=\"perspective\"><film type=\"ldrfilm\">\n"
              "<string name=\"tonemap_method\" value=\"filmic\"/></film></sensor>",
              4, "must be gamma or reinhard, not 'filmic'", false);
    expectBad("<sensor type=\"perspective\"><film type=\"ldrfilm\">\n"
              "<string name=\"file_format\" value=\"jpeg\"/></film></sensor>",
              4, "only 'png' is supported", false);
}

/// Mitsuba 3.9.1's sample counts (printed by its samplers for the same requests).
TEST(Samplers, CountsRoundedAsMitsuba) {
    struct Case { const char* type; int requested, expected; };
    const Case cases[] = {
        {"independent", 5, 5},  {"stratified", 5, 9},   {"stratified", 26, 36},
        {"multijitter", 5, 6},  {"multijitter", 32, 35}, {"multijitter", 3, 3},
        {"orthogonal", 16, 25}, {"orthogonal", 50, 121}, {"ldsampler", 1, 4},
        {"ldsampler", 8, 16},   {"ldsampler", 65, 256},  {"stratified", 64, 64}};
    for (const Case& c : cases) {
        std::vector<std::string> warnings;
        Scene s = sensor("perspective", std::string("<sampler type=\"") + c.type +
                                            "\"><integer name=\"sample_count\" value=\"" +
                                            std::to_string(c.requested) +
                                            "\"/><integer name=\"seed\" value=\"7\"/></sampler>",
                         &warnings);
        EXPECT_EQ(s.sampleCount, c.expected) << c.type << " " << c.requested;
        EXPECT_EQ(s.seed, 7u);
        EXPECT_EQ(warnings.size(), c.requested == c.expected ? 0u : 1u) << c.type;
    }
    expectBad("<sensor type=\"perspective\"><sampler type=\"stratified\">\n"
              "<boolean name=\"jitter\" value=\"false\"/></sampler></sensor>",
              4, "'jitter' must be true", false);
}

}  // namespace
}  // namespace caustica::test
