// sensor_test.cpp — perspective sensor (fov and fov_axis exactly as Mitsuba's parse_fov), film,
// reconstruction filters, sampler and integrator settings with their defaults and limits.
#include <cmath>

#include "scene_test_util.h"

namespace caustica::test {
namespace {

constexpr double kDeg = M_PI / 180.0;

Scene sensorScene(const std::string& sensorBody, const std::string& extra = "") {
    TempDir dir;
    return loadXml(
        dir, sceneXml("<sensor type=\"perspective\">" + sensorBody + "</sensor>" + extra, false));
}

std::string film(int w, int h) {
    return "<film type=\"hdrfilm\"><integer name=\"width\" value=\"" + std::to_string(w) +
           "\"/><integer name=\"height\" value=\"" + std::to_string(h) + "\"/></film>";
}

TEST(Sensor, Defaults) {
    Scene s = sensorScene("");
    EXPECT_EQ(s.film.width, 768);
    EXPECT_EQ(s.film.height, 576);
    EXPECT_EQ(s.camera.width, 768);
    EXPECT_EQ(s.camera.height, 576);
    EXPECT_EQ(s.film.filter.type, FilterType::Gaussian);
    EXPECT_FLOAT_EQ(s.film.filter.stddev, 0.5f);
    EXPECT_FLOAT_EQ(s.film.filter.radius, 2.0f);
    EXPECT_EQ(s.sampleCount, 4);
    EXPECT_EQ(s.seed, 0u);
    EXPECT_FLOAT_EQ(s.camera.nearClip, 1e-2f);
    EXPECT_FLOAT_EQ(s.camera.farClip, 1e4f);
    // No fov: Mitsuba's 50 mm focal length on 36 x 24 mm film, a diagonal field of view.
    double halfDiagonal = std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / 100.0;
    EXPECT_NEAR(std::hypot(s.camera.tanHalfX, s.camera.tanHalfY), halfDiagonal, 1e-6);
    EXPECT_NEAR(s.camera.tanHalfX / s.camera.tanHalfY, 768.0 / 576.0, 1e-6);
    EXPECT_EQ(s.integrator.type, "path");
    EXPECT_TRUE(s.integrator.params.empty());
}

struct FovCase {
    const char* axis;
    int width, height;
    double tanX, tanY;  // expected, fov = 60°
};

TEST(Sensor, FovAxisVariants) {
    const double t = std::tan(30 * kDeg);
    const FovCase cases[] = {
        {"x", 200, 100, t, t / 2},
        {"y", 200, 100, 2 * t, t},
        {"smaller", 200, 100, 2 * t, t},
        {"smaller", 100, 200, t, 2 * t},
        {"larger", 200, 100, t, t / 2},
        {"larger", 100, 200, t / 2, t},
        {"diagonal", 300, 400, t * 3 / 5, t * 4 / 5},
    };
    for (const FovCase& c : cases) {
        SCOPED_TRACE(std::string(c.axis) + " " + std::to_string(c.width) + "x" +
                     std::to_string(c.height));
        Scene s =
            sensorScene("<float name=\"fov\" value=\"60\"/><string name=\"fov_axis\" value=\"" +
                        std::string(c.axis) + "\"/>" + film(c.width, c.height));
        EXPECT_NEAR(s.camera.tanHalfX, c.tanX, 1e-6);
        EXPECT_NEAR(s.camera.tanHalfY, c.tanY, 1e-6);
    }
}

TEST(Sensor, ClipsTransformAndFocalLength) {
    Scene s = sensorScene(R"(<string name="focal_length" value="35mm"/>
        <float name="near_clip" value="0.5"/><float name="far_clip" value="20"/>
        <transform name="to_world"><rotate y="1" angle="180"/><translate x="2"/></transform>)");
    EXPECT_FLOAT_EQ(s.camera.nearClip, 0.5f);
    EXPECT_FLOAT_EQ(s.camera.farClip, 20.0f);
    EXPECT_NEAR(std::hypot(s.camera.tanHalfX, s.camera.tanHalfY),
                std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / 70.0, 1e-6);
    EXPECT_NEAR(s.camera.worldFromCamera.m.m[0][3], 2.0f, 1e-6f);
    EXPECT_NEAR(s.camera.worldFromCamera.m.m[2][2], -1.0f, 1e-6f);
}

TEST(Sensor, FiltersAndSampler) {
    Scene box = sensorScene("<film type=\"hdrfilm\"><rfilter type=\"box\"/></film>");
    EXPECT_EQ(box.film.filter.type, FilterType::Box);
    EXPECT_FLOAT_EQ(box.film.filter.radius, 0.5f);
    Scene tent = sensorScene("<film type=\"hdrfilm\"><rfilter type=\"tent\"/></film>");
    EXPECT_EQ(tent.film.filter.type, FilterType::Tent);
    EXPECT_FLOAT_EQ(tent.film.filter.radius, 1.0f);
    Scene gauss = sensorScene(
        "<film type=\"hdrfilm\"><rfilter type=\"gaussian\"><float name=\"stddev\" value=\"0.25\"/>"
        "</rfilter></film><sampler type=\"independent\"><integer name=\"sample_count\" "
        "value=\"128\"/><integer name=\"seed\" value=\"7\"/></sampler>");
    EXPECT_EQ(gauss.film.filter.type, FilterType::Gaussian);
    EXPECT_FLOAT_EQ(gauss.film.filter.stddev, 0.25f);
    EXPECT_FLOAT_EQ(gauss.film.filter.radius, 1.0f);
    EXPECT_EQ(gauss.sampleCount, 128);
    EXPECT_EQ(gauss.seed, 7u);
}

TEST(Sensor, IgnoredFilmParametersWarn) {
    TempDir dir;
    std::vector<std::string> warnings;
    loadXml(dir,
            sceneXml(R"(<sensor type="perspective"><film type="hdrfilm">
        <string name="pixel_format" value="rgba"/>
        <string name="file_format" value="openexr"/>
    </film></sensor>)",
                     false),
            &warnings);
    EXPECT_TRUE(hasWarning(warnings, {"scene.xml:4:", "'pixel_format' is ignored"}));
    EXPECT_TRUE(hasWarning(warnings, {"scene.xml:5:", "'file_format' is ignored"}));
}

TEST(Sensor, Integrator) {
    Scene s = sensorScene("", R"(<integrator type="path">
        <integer name="max_depth" value="8"/><integer name="rr_depth" value="3"/>
        <boolean name="hide_emitters" value="true"/></integrator>)");
    // Kept as written: the path tracer reads them (tests/render/integrator_settings_test.cpp).
    ASSERT_EQ(s.integrator.params.size(), 3u);
    EXPECT_EQ(s.integrator.params[0].name, "max_depth");
    EXPECT_EQ(s.integrator.params[0].text, "8");
    EXPECT_EQ(s.integrator.params[0].kind, IntegratorParam::Kind::Integer);
    EXPECT_EQ(s.integrator.params[2].name, "hide_emitters");
    EXPECT_EQ(s.integrator.params[2].text, "true");
    EXPECT_EQ(s.integrator.params[2].kind, IntegratorParam::Kind::Boolean);
    EXPECT_NE(s.integrator.params[1].where.find("scene.xml:"), std::string::npos);
}

TEST(Sensor, RefusedSettings) {
    TempDir dir;
    auto bad = [&](const std::string& body, int line, const std::string& reason) {
        std::string path =
            dir.write("s.xml", "<scene version=\"3.0.0\">\n" + body + "\n</scene>\n");
        expectError([&] { loadScene(path); }, "s.xml", line, reason);
    };
    bad("<sensor type=\"perspective\">\n" + film(0, 10) + "</sensor>", 3, "absurd resolution 0x10");
    bad("<sensor type=\"perspective\">\n" + film(40000, 10) + "</sensor>", 3, "absurd resolution");
    bad("<sensor type=\"perspective\">\n" + film(20000, 20000) + "</sensor>", 3,
        "at most 2^28 pixels");
    bad("<sensor type=\"perspective\">\n<film type=\"hdrfilm\">\n<integer name=\"crop_width\" "
        "value=\"800\"/></film></sensor>",
        3, "crop window 800x576 at (0, 0) does not fit in the 768x576 film");
    bad("<sensor type=\"perspective\">\n<film type=\"specfilm\"/></sensor>", 3,
        "unsupported film type 'specfilm'");
    bad("<sensor type=\"radiancemeter\"/>", 2,
        "unsupported sensor type 'radiancemeter' (supported: orthographic, perspective, thinlens)");
    bad("<sensor type=\"perspective\">\n<float name=\"fov\" value=\"180\"/></sensor>", 3,
        "between 0 and 180");
    bad("<sensor type=\"perspective\">\n<string name=\"fov_axis\" value=\"z\"/>\n"
        "<float name=\"fov\" value=\"40\"/></sensor>",
        3, "must be x, y, diagonal, smaller or larger");
    bad("<sensor type=\"perspective\">\n<float name=\"near_clip\" value=\"0\"/></sensor>", 3,
        "'near_clip' must be positive");
    bad("<sensor type=\"perspective\">\n<transform name=\"to_world\"><scale value=\"2\"/>"
        "</transform></sensor>",
        3, "must not scale");
    bad("<sensor type=\"perspective\">\n<sampler type=\"sobol\"/></sensor>", 3,
        "unsupported sampler type 'sobol'");
    bad("<sensor type=\"perspective\">\n<sampler type=\"independent\">\n<integer "
        "name=\"sample_count\" value=\"0\"/></sampler></sensor>",
        4, "'sample_count' must be positive");
    bad(std::string(kSensor) + "\n<integrator type=\"path\"/>\n<integrator type=\"path\"/>", 4,
        "a second integrator");
    bad("<shape type=\"cube\"/>", 0, "scene has no sensor");
}

}  // namespace
}  // namespace caustica::test
