// scene_features_test.cpp — <spectrum> wavelength:value lists (values from Mitsuba 3.9.1's
// scalar_rgb), <path>, <alias>, shapegroup/instance, the cylinder's parameters and the
// refusals of features caustica does not render (media, curves, spectrum files).
#include "scene_test_util.h"

namespace caustica::test {
namespace {

void expectRgb(Spectrum s, double r, double g, double b, double tol = 2e-5) {
    EXPECT_NEAR(s.r, r, tol);
    EXPECT_NEAR(s.g, g, tol);
    EXPECT_NEAR(s.b, b, tol);
}

std::string diffuseWith(const std::string& spectrum) {
    return "<shape type=\"sphere\"><bsdf type=\"diffuse\">" + spectrum + "</bsdf></shape>";
}

std::string areaWith(const std::string& spectrum) {
    return "<shape type=\"sphere\"><emitter type=\"area\">" + spectrum + "</emitter></shape>";
}

TEST(Spectrum, WavelengthListsConvertLikeMitsuba) {
    TempDir dir;
    // Reflectance: weighted by D65 and clamped to [0, 1]; emission: neither.
    const std::string list = R"(<spectrum name="NAME" value="400:0.1, 500:0.5, 600:0.8"/>)";
    auto with = [&](const std::string& name) {
        return std::string(list).replace(list.find("NAME"), 4, name);
    };
    Scene r = loadXml(dir, sceneXml(diffuseWith(with("reflectance"))));
    expectRgb(r.bsdfs[r.shapes[0].bsdf].reflectance, 0.184134, 0.667361, 0.280429);
    Scene e = loadXml(dir, sceneXml(areaWith(with("radiance"))));
    expectRgb(e.lights[0].radiance, 0.233418, 0.64466, 0.246182);
    // Blanks or commas between pairs; values above 1 clamp for reflectances only.
    Scene c = loadXml(dir, sceneXml(diffuseWith(
                               R"(<spectrum name="reflectance" value="400:1.5 700:1.5"/>)")));
    expectRgb(c.bsdfs[c.shapes[0].bsdf].reflectance, 1, 1, 1);
    Scene u = loadXml(dir, sceneXml(areaWith(
                               R"(<spectrum name="radiance" value="400:1.5,700:1.5"/>)")));
    expectRgb(u.lights[0].radiance, 1.79954, 1.42428, 1.35517, 1e-4);
    // Outside 360..830 nm nothing is seen.
    Scene z = loadXml(dir, sceneXml(diffuseWith(
                               R"(<spectrum name="reflectance" value="100:0.5, 300:1"/>)")));
    expectRgb(z.bsdfs[z.shapes[0].bsdf].reflectance, 0, 0, 0);
}

TEST(Spectrum, SingleValueInAnEmitterIsEqualEnergyWhite) {
    // Mitsuba's RGB mode turns <spectrum value="2"/> in an emitter into 2 * xyz_to_srgb(1, 1, 1).
    TempDir dir;
    Scene e = loadXml(dir, sceneXml(areaWith(R"(<spectrum name="radiance" value="2"/>)")));
    expectRgb(e.lights[0].radiance, 2.40959, 1.89658, 1.81783);
    Scene r = loadXml(dir, sceneXml(diffuseWith(R"(<spectrum name="reflectance" value="0.3"/>)")));
    expectRgb(r.bsdfs[r.shapes[0].bsdf].reflectance, 0.3, 0.3, 0.3, 1e-7);
}

TEST(Spectrum, MalformedListsAreRefused) {
    TempDir dir;
    auto bad = [&](const std::string& value, const std::string& reason) {
        const std::string path = dir.write(
            "s.xml", sceneXml("<shape type=\"sphere\">\n<bsdf type=\"diffuse\">\n"
                              "<spectrum name=\"reflectance\" value=\"" + value + "\"/>\n"
                              "</bsdf></shape>"));
        expectError([&] { loadScene(path); }, "s.xml", 5, reason);
    };
    bad("500:0.5, 400:0.1", "wavelengths must increase ('400' nm follows '500' nm)");
    bad("400:0.5", "needs at least two wavelength:value pairs");
    bad("400:0.5:3, 500:1", "cannot read '400:0.5:3' as a wavelength:value pair");
    bad("400 : 0.5, 700:0.1", "cannot read '400' as a wavelength:value pair");
    bad("400:-0.5, 700:0.1", "value '-0.5' at '400' nm must be non-negative");
    bad("400:x, 700:0.1", "cannot read 'x' as a finite number");
    bad("-1", "must be non-negative");
}

TEST(SearchPath, RelativeFilesAreFoundInPathFolders) {
    TempDir dir;
    dir.write("meshes/deep/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string shape =
        R"(<shape type="obj"><string name="filename" value="tri.obj"/></shape>)";
    // The <path> may come after the shape (Mitsuba resolves when it builds).
    Scene s = loadXml(dir, sceneXml(shape + "<path value=\"meshes/deep\"/>"));
    EXPECT_EQ(s.triangles.size(), 1u);
    // Without it the file is not found, next to the scene.
    const std::string path = dir.write("n.xml", sceneXml("\n" + shape));
    expectError([&] { loadScene(path); }, "n.xml", 4, "tri.obj: cannot open mesh file");
    const std::string missing = dir.write("m.xml", sceneXml("\n<path value=\"nowhere\"/>"));
    expectError([&] { loadScene(missing); }, "m.xml", 4, "<path>: folder");
}

TEST(Alias, NamesTheSameObject) {
    TempDir dir;
    Scene s = loadXml(dir, sceneXml(R"(
        <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.8, 0.1, 0.1"/></bsdf>
        <alias id="red" as="paint"/>
        <shape type="sphere"><ref id="paint"/></shape>
        <shape type="sphere"><ref id="red"/></shape>)"));
    ASSERT_EQ(s.shapes.size(), 2u);
    EXPECT_EQ(s.shapes[0].bsdf, s.shapes[1].bsdf);  // one record
    EXPECT_FLOAT_EQ(s.bsdfs[s.shapes[0].bsdf].reflectance.r, 0.8f);

    auto bad = [&](const std::string& body, int line, const std::string& reason) {
        const std::string path = dir.write("a.xml", sceneXml(body));
        expectError([&] { loadScene(path); }, "a.xml", line, reason);
    };
    bad("\n<alias id=\"nope\" as=\"x\"/>", 4, "no object with id 'nope' is declared before it");
    bad("<bsdf type=\"diffuse\" id=\"w\"/>\n<bsdf type=\"diffuse\" id=\"v\"/>\n"
        "<alias id=\"w\" as=\"v\"/>",
        5, "<alias>: id 'v' is already used");
}

const char* kGroup = R"(
    <shape type="shapegroup" id="group">
        <shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance" value="0.2"/></bsdf></shape>
        <shape type="sphere"><float name="radius" value="0.5"/></shape>
    </shape>)";

TEST(Instance, FlattensTheGroupUnderEachTransform) {
    TempDir dir;
    Scene s = loadXml(dir, sceneXml(std::string(kGroup) + R"(
        <shape type="instance"><ref id="group"/>
            <transform name="to_world"><translate x="3"/></transform></shape>
        <shape type="instance"><ref id="group"/>
            <transform name="to_world"><scale value="2"/><translate y="-4"/></transform></shape>)"));
    ASSERT_EQ(s.shapes.size(), 4u);  // the group itself draws nothing
    EXPECT_EQ(s.triangles.size(), 4u);
    ASSERT_EQ(s.spheres.size(), 2u);
    EXPECT_EQ(s.spheres[0].center, Vec3f(3, 0, 0));
    EXPECT_FLOAT_EQ(s.spheres[0].radius, 0.5f);
    EXPECT_EQ(s.spheres[1].center, Vec3f(0, -4, 0));
    EXPECT_FLOAT_EQ(s.spheres[1].radius, 1.0f);
    EXPECT_EQ(s.positions[4], Vec3f(-2, -6, 0));  // second rectangle, scaled then moved
    EXPECT_EQ(s.shapes[0].bsdf, s.shapes[2].bsdf);  // one BSDF record for all copies
}

TEST(Instance, RefusesWhatMitsubaRefuses) {
    TempDir dir;
    auto bad = [&](const std::string& body, int line, const std::string& reason) {
        const std::string path = dir.write("i.xml", sceneXml(body));
        expectError([&] { loadScene(path); }, "i.xml", line, reason);
    };
    bad("<shape type=\"shapegroup\" id=\"g\">\n<shape type=\"sphere\">\n"
        "<emitter type=\"area\"/></shape></shape>\n"
        "<shape type=\"instance\"><ref id=\"g\"/></shape>",
        5, "emitters cannot be instanced");
    bad("\n<shape type=\"instance\"><shape type=\"sphere\"/></shape>", 4,
        "an instance needs exactly one shapegroup");
    bad("<shape type=\"shapegroup\" id=\"g\"><shape type=\"sphere\"/></shape>\n"
        "<shape type=\"shapegroup\" id=\"h\">\n<shape type=\"instance\"><ref id=\"g\"/></shape>"
        "</shape>",
        5, "a shapegroup cannot contain a instance");
}

TEST(Cylinder, ParametersBecomeTheWorldRecord) {
    TempDir dir;
    Scene s = loadXml(dir, sceneXml(R"(<shape type="cylinder">
        <point name="p0" value="0, 0, 1"/><point name="p1" value="0, 3, 1"/>
        <float name="radius" value="0.5"/><boolean name="flip_normals" value="true"/>
        <transform name="to_world"><scale value="2"/><translate x="1"/></transform></shape>)"));
    ASSERT_EQ(s.cylinders.size(), 1u);
    ASSERT_EQ(s.shapes[0].type, ShapeType::Cylinder);
    EXPECT_TRUE(s.shapes[0].flipNormals);
    const Cylinder& c = s.cylinders[0];
    EXPECT_EQ(c.base, Vec3f(1, 0, 2));
    EXPECT_NEAR(c.radius, 1.0f, 1e-6f);
    EXPECT_NEAR(c.length, 6.0f, 1e-5f);
    EXPECT_NEAR(c.axis.y, 1.0f, 1e-6f);
    EXPECT_NEAR(dot(c.axis, c.xAxis), 0.0f, 1e-6f);

    auto bad = [&](const std::string& params, const std::string& reason) {
        const std::string path =
            dir.write("c.xml", sceneXml("\n<shape type=\"cylinder\">" + params + "</shape>"));
        expectError([&] { loadScene(path); }, "c.xml", 0, reason);
    };
    bad("<float name=\"radius\" value=\"0\"/>", "'radius' must be positive");
    bad("<point name=\"p1\" value=\"0, 0, 0\"/>", "p0 and p1 must differ");
    bad("<transform name=\"to_world\"><scale x=\"2\"/></transform>",
        "must scale the cylinder's cross-section uniformly");
    bad("<transform name=\"to_world\"><scale z=\"-1\"/></transform>", "must not mirror");
}

TEST(Refusals, UnsupportedFeaturesNameFileLineAndElement) {
    TempDir dir;
    auto bad = [&](const std::string& body, int line, const std::string& reason) {
        const std::string path = dir.write("r.xml", sceneXml("\n" + body));
        expectError([&] { loadScene(path); }, "r.xml", line, reason);
    };
    bad("<phase type=\"hg\"/>", 4, "<phase>: participating media are not supported");
    bad("<medium type=\"homogeneous\"/>", 4, "<medium>: participating media are not supported");
    bad("<shape type=\"bsplinecurve\"/>", 4, "unsupported shape type 'bsplinecurve': curves");
    bad("<shape type=\"teapot\"/>", 4, "unsupported shape type 'teapot' (supported: cube,");
    bad("<shape type=\"sphere\">\n<spectrum name=\"x\" filename=\"a.spd\"/></shape>", 5,
        "<spectrum filename=...> (measured spectra from files) is not supported");
}

}  // namespace
}  // namespace caustica::test
