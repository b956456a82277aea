// transform_test.cpp — <transform> operations against hand-computed matrices, their order of
// composition (each new operation applied after the previous ones), and refused transforms.
#include "scene_test_util.h"

namespace caustica::test {
namespace {

/// Loads a rectangle with the given <transform> body and returns its world-space transform,
/// recovered from where the corners (-1,-1,0), (1,-1,0), (-1,1,0) and the normal went.
struct Placed {
    Vec3f p00, p10, p01, normal;
};
Placed placeRectangle(const std::string& ops) {
    TempDir dir;
    Scene s = loadXml(dir, sceneXml("<shape type=\"rectangle\"><transform name=\"to_world\">" +
                                    ops + "</transform></shape>"));
    return {s.positions[0], s.positions[1], s.positions[3], s.normals[0]};
}

void expectNear(Vec3f a, Vec3f b, Float eps = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

TEST(Transform, TranslateForms) {
    expectNear(placeRectangle("<translate x=\"1\" y=\"2\" z=\"3\"/>").p00, Vec3f(0, 1, 3));
    expectNear(placeRectangle("<translate value=\"1, 2, 3\"/>").p00, Vec3f(0, 1, 3));
    expectNear(placeRectangle("<translate value=\"1 2 3\"/>").p00, Vec3f(0, 1, 3));
    expectNear(placeRectangle("<translate y=\"2\"/>").p00, Vec3f(-1, 1, 0));  // x, z default 0
}

TEST(Transform, ScaleForms) {
    expectNear(placeRectangle("<scale value=\"2\"/>").p10, Vec3f(2, -2, 0));
    expectNear(placeRectangle("<scale x=\"3\"/>").p10, Vec3f(3, -1, 0));  // y, z default 1
    expectNear(placeRectangle("<scale value=\"2 4 1\"/>").p01, Vec3f(-2, 4, 0));
}

TEST(Transform, RotateIsRightHandedInDegrees) {
    // 90° about +y: x -> -z, z -> x. Corner (1,-1,0) -> (0,-1,-1); normal +z -> +x.
    Placed r = placeRectangle("<rotate y=\"1\" angle=\"90\"/>");
    expectNear(r.p10, Vec3f(0, -1, -1));
    expectNear(r.normal, Vec3f(1, 0, 0));
    Placed v = placeRectangle("<rotate value=\"0, 0, 2\" angle=\"90\"/>");  // axis normalised
    expectNear(v.p10, Vec3f(1, 1, 0));
}

TEST(Transform, MatrixIsRowMajor) {
    // x' = 2x + 1, y' = z + 2, z' = -y + 3.
    Placed m = placeRectangle("<matrix value=\"2 0 0 1  0 0 1 2  0 -1 0 3  0 0 0 1\"/>");
    expectNear(m.p10, Vec3f(3, 2, 4));
    expectNear(m.p01, Vec3f(-1, 2, 2));
    expectNear(m.normal, Vec3f(0, 1, 0));  // inverse transpose of the linear part maps +z to +y
}

TEST(Transform, OperationsComposeInDocumentOrder) {
    // scale then translate: (1,-1,0) -> (2,-2,0) -> (3,-2,0); the other order -> (4,-2,0).
    expectNear(placeRectangle("<scale value=\"2\"/><translate x=\"1\"/>").p10, Vec3f(3, -2, 0));
    expectNear(placeRectangle("<translate x=\"1\"/><scale value=\"2\"/>").p10, Vec3f(4, -2, 0));
    // rotate 90° about z, then translate: (1,-1,0) -> (1,1,0) -> (1,1,5).
    expectNear(placeRectangle("<rotate z=\"1\" angle=\"90\"/><translate z=\"5\"/>").p10,
               Vec3f(1, 1, 5));
}

TEST(Transform, LookAtBuildsMitsubasCameraFrame) {
    TempDir dir;
    Scene s = loadXml(dir, sceneXml(R"(<sensor type="perspective">
        <transform name="to_world">
            <lookat origin="1, 2, 3" target="1, 2, 0" up="0, 1, 0"/></transform>
    </sensor>)",
                                    false));
    const Matrix4& m = s.camera.worldFromCamera.m;
    // Columns: left = cross(up, dir) = (-1,0,0) for dir (0,0,-1); up (0,1,0); dir; origin.
    expectNear({m.m[0][0], m.m[1][0], m.m[2][0]}, Vec3f(-1, 0, 0));
    expectNear({m.m[0][1], m.m[1][1], m.m[2][1]}, Vec3f(0, 1, 0));
    expectNear({m.m[0][2], m.m[1][2], m.m[2][2]}, Vec3f(0, 0, -1));
    expectNear({m.m[0][3], m.m[1][3], m.m[2][3]}, Vec3f(1, 2, 3));
}

TEST(Transform, LookAtWithoutUpPicksAPerpendicular) {
    TempDir dir;
    Scene s = loadXml(dir, sceneXml(R"(<sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, 0" target="0, 0, 1"/></transform>
    </sensor>)",
                                    false));
    const Matrix4& m = s.camera.worldFromCamera.m;
    Vec3f up(m.m[0][1], m.m[1][1], m.m[2][1]);
    EXPECT_NEAR(up.z, 0.0f, 1e-6f);
    EXPECT_NEAR(length(up), 1.0f, 1e-6f);
}

TEST(Transform, MirrorKeepsWindingAndTransformsNormalsByInverseTranspose) {
    TempDir dir;
    Scene s = loadXml(
        dir,
        sceneXml(
            "<shape type=\"rectangle\"><transform name=\"to_world\"><scale x=\"-1\"/></transform>"
            "</shape>"));
    // The rectangle's normal is Mitsuba's analytic one: diag(-1,1,1)^-T (0,0,1) = (0,0,1) ...
    expectNear(s.normals[0], Vec3f(0, 0, 1));
    EXPECT_TRUE(s.shapes[0].hasNormals);
    // ... while the winding is kept, so the triangle's face normal now points to -z.
    const Vec3u t = s.triangles[0];
    Vec3f face = cross(s.positions[t.y] - s.positions[t.x], s.positions[t.z] - s.positions[t.x]);
    EXPECT_LT(face.z, 0);
}

TEST(Transform, RefusedTransforms) {
    TempDir dir;
    auto bad = [&](const std::string& ops, const std::string& reason, int line = 5) {
        std::string path =
            dir.write("t.xml", sceneXml("<shape type=\"cube\">\n<transform name=\"to_world\">\n" +
                                        ops + "\n</transform>\n</shape>"));
        expectError([&] { loadScene(path); }, "t.xml", line, reason);
    };
    bad("<translate x=\"nan\"/>", "cannot read 'nan' as a finite number");
    bad("<translate x=\"1e39\"/>", "transform overflows");
    bad("<scale value=\"0\"/>", "<scale> by zero");
    bad("<scale value=\"1 2\"/>", "needs 1 or 3 numbers, got 2");
    bad("<matrix value=\"1 0 0 0  0 1 0 0  0 0 0 0  0 0 0 1\"/>", "<matrix> is singular");
    bad("<matrix value=\"1 2 3\"/>", "needs 16 or 9 numbers");
    bad("<rotate angle=\"30\"/>", "non-zero axis");
    bad("<rotate x=\"1\"/>", "<rotate> needs a 'angle' attribute");
    bad("<lookat origin=\"0 0 0\" target=\"0 0 0\"/>", "origin and target coincide");
    bad("<lookat origin=\"0 0 0\" target=\"0 1 0\" up=\"0 2 0\"/>", "parallel to the view");
    bad("<translate value=\"1\" x=\"2\"/>", "either 'value' or 'x'/'y'/'z'");
    bad("<shear x=\"1\"/>", "not <shear>");
    bad("<scale value=\"1e30\"/>\n<scale value=\"1e30\"/>", "overflows", 6);
}

}  // namespace
}  // namespace caustica::test
