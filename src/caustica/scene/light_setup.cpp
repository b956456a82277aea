// light_setup.cpp — derived light data computed once on the host after the scene is built:
// triangle-area CDFs and areas of area emitters, and the environment's scene bounding sphere.
#include "caustica/scene/light_setup.h"

#include <cmath>
#include <string>

#include "caustica/scene/interaction.h"
#include "caustica/scene/light_envmap_setup.h"
#include "caustica/scene/parallelogram.h"
#include "caustica/util/error.h"

namespace caustica {

namespace {

/// Area of triangle `t` of the scene, in double precision.
double triangleArea(const Scene& scene, uint32_t t) {
    const Vec3u& tri = scene.triangles[t];
    const Vec3f& p0 = scene.positions[tri.x];
    const Vec3f& p1 = scene.positions[tri.y];
    const Vec3f& p2 = scene.positions[tri.z];
    const double e1[3] = {double(p1.x) - p0.x, double(p1.y) - p0.y, double(p1.z) - p0.z};
    const double e2[3] = {double(p2.x) - p0.x, double(p2.y) - p0.y, double(p2.z) - p0.z};
    const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    return 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

[[noreturn]] void fail(size_t light, const std::string& reason) {
    throw Error("light " + std::to_string(light) + ": " + reason);
}

/// Light::isQuad and its parallelogram for a mesh that is one parallelogram (meshParallelogram)
/// with the same front side on both halves (flip_normals included) and, if it has shading
/// normals, the same normal at every vertex (the front side follows the interpolated normal, which
/// must then be constant). Such a mesh — every rectangle shape — is then sampled without the
/// triangle CDF: the same uniform density by area, fewer operations per light sample.
void setupQuad(const Scene& scene, Light& light, const Shape& shape) {
    light.isQuad = false;
    MeshParallelogram quad;
    if (!meshParallelogram(scene, shape, quad)) return;
    if (shape.hasNormals) {
        const Vec3u ta = scene.triangles[quad.first], tb = scene.triangles[quad.second];
        const Vec3f n = scene.normals[ta.x];
        for (uint32_t v : {ta.y, ta.z, tb.x, tb.y, tb.z})
            if (!(scene.normals[v] == n)) return;
    }
    const SceneView view = scene.view();
    const Vec3f na = trianglePoint(view, shape, quad.first, Float(1) / 3, Float(1) / 3).ng;
    const Vec3f nb = trianglePoint(view, shape, quad.second, Float(1) / 3, Float(1) / 3).ng;
    if (!(dot(na, nb) > 0)) return;  // the two halves emit to different sides
    light.isQuad = true;
    light.quadCorner = quad.corner;
    light.quadEdgeU = quad.edgeU;
    light.quadEdgeV = quad.edgeV;
    light.quadNormal = na;
}

/// Area light on a mesh: appends the normalised cumulative triangle areas to scene.lightCdf.
void setupMeshLight(Scene& scene, Light& light, const Shape& shape, size_t index) {
    if (size_t(shape.primOffset) + shape.primCount > scene.triangles.size())
        fail(index, "emitting mesh references triangles out of range");
    double total = 0;
    for (uint32_t i = 0; i < shape.primCount; ++i)
        total += triangleArea(scene, shape.primOffset + i);
    if (!(total > 0) || !std::isfinite(total))
        throw Error("area emitter on a shape with zero area");

    light.cdfOffset = uint32_t(scene.lightCdf.size());
    light.cdfCount = shape.primCount;
    double sum = 0;
    for (uint32_t i = 0; i < shape.primCount; ++i) {
        sum += triangleArea(scene, shape.primOffset + i);
        scene.lightCdf.push_back(float(sum / total));
    }
    scene.lightCdf.back() = 1.0f;  // exactly 1, whatever the rounding
    light.area = Float(total);
    setupQuad(scene, light, shape);
}

void setupSphereLight(const Scene& scene, Light& light, const Shape& shape, size_t index) {
    if (shape.primOffset >= scene.spheres.size())
        fail(index, "emitting sphere references a sphere out of range");
    const double r = scene.spheres[shape.primOffset].radius;
    const double area = 4.0 * double(kPi) * r * r;
    if (!(area > 0) || !std::isfinite(area))
        throw Error("area emitter on a shape with zero area");
    light.area = Float(area);
    light.cdfOffset = 0;
    light.cdfCount = 0;
}

/// Mitsuba's cylinder emitter samples its lateral surface uniformly: area 2π r length.
void setupCylinderLight(const Scene& scene, Light& light, const Shape& shape, size_t index) {
    if (shape.primOffset >= scene.cylinders.size())
        fail(index, "emitting cylinder references a cylinder out of range");
    const Cylinder& c = scene.cylinders[shape.primOffset];
    const double area = 2.0 * double(kPi) * double(c.radius) * double(c.length);
    if (!(area > 0) || !std::isfinite(area)) throw Error("area emitter on a shape with zero area");
    light.area = Float(area);
    light.cdfOffset = 0;
    light.cdfCount = 0;
}

/// Mitsuba's constant emitter: the bounding sphere of the scene's bounding box, slightly enlarged
/// and never of zero radius (math::RayEpsilon = 1500 float epsilons).
void setupEnvironment(const Scene& scene, Light& light) {
    constexpr Float kRayEpsilon = 1500 * 5.96046448e-8f;
    const Bounds3f b = scene.bounds();
    if (b.empty()) {
        light.sceneCenter = Vec3f(0);
        light.sceneRadius = 1;  // nothing to enclose: any positive radius serves
        return;
    }
    light.sceneCenter = b.center();
    const Float r = 0.5f * length(b.diagonal());
    light.sceneRadius = max(kRayEpsilon, r * (1 + kRayEpsilon));
}

}  // namespace

void finalizeLights(Scene& scene) {
    scene.lightCdf.clear();
    scene.environmentLight = -1;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        Light& light = scene.lights[i];
        switch (light.type) {
            case LightType::Area: {
                if (light.shape >= scene.shapes.size())
                    fail(i, "area emitter references a shape out of range");
                const Shape& shape = scene.shapes[light.shape];
                if (shape.type == ShapeType::Mesh)
                    setupMeshLight(scene, light, shape, i);
                else if (shape.type == ShapeType::Cylinder)
                    setupCylinderLight(scene, light, shape, i);
                else
                    setupSphereLight(scene, light, shape, i);
                break;
            }
            case LightType::Constant:
            case LightType::EnvMap:  // Mitsuba 3 too allows one environment emitter per scene
                if (scene.environmentLight >= 0)
                    fail(i, "more than one environment (constant, envmap) emitter in the scene");
                scene.environmentLight = int32_t(i);
                setupEnvironment(scene, light);
                if (light.type == LightType::EnvMap) setupEnvMapDistribution(scene, light);
                break;
            case LightType::Directional:
                setupEnvironment(scene, light);  // shadow rays start outside the scene's sphere
                break;
            case LightType::Point:
            case LightType::Spot:
                break;
        }
    }
}

}  // namespace caustica
