// scene.h — the flattened, device-ready scene. `Scene` owns host arrays; `SceneView` is the plain
// struct of spans that kernels take (on the GPU its spans point to device copies).
// scene/ knows nothing of files: io/ builds a Scene, integrators read a SceneView.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "caustica/scene/bsdf_data.h"
#include "caustica/scene/camera.h"
#include "caustica/scene/light_data.h"
#include "caustica/scene/shape.h"
#include "caustica/util/span.h"

namespace caustica {

enum class FilterType : uint32_t { Box, Tent, Gaussian };

/// Image reconstruction filter, as Mitsuba's rfilter plugins define it.
struct FilterDesc {
    FilterType type = FilterType::Gaussian;
    Float radius = 2.0f;   // support half-width in pixels (box 0.5, tent 1, gaussian 4 * stddev)
    Float stddev = 0.5f;   // gaussian only
};

struct FilmDesc {
    int width = 768, height = 576;
    FilterDesc filter;
};

enum class IntegratorType : uint32_t { Path, Direct, Mlt };

/// The integrator's name as the CLI and the scene format spell it ("path", "direct", "mlt").
inline const char* integratorTypeName(IntegratorType type) {
    switch (type) {
        case IntegratorType::Path: return "path";
        case IntegratorType::Direct: return "direct";
        case IntegratorType::Mlt: return "mlt";
    }
    return "?";
}

/// Parses an integrator name as integratorTypeName spells it; false when unknown.
inline bool parseIntegratorType(const std::string& name, IntegratorType& type) {
    for (IntegratorType t : {IntegratorType::Path, IntegratorType::Direct, IntegratorType::Mlt})
        if (name == integratorTypeName(t)) {
            type = t;
            return true;
        }
    return false;
}

struct IntegratorDesc {
    IntegratorType type = IntegratorType::Path;
    int maxDepth = -1;          // Mitsuba's meaning: longest path in segments; -1 = unbounded
    int rrDepth = 5;            // Russian roulette from this depth on
    bool hideEmitters = false;  // directly visible emitters render black
};

struct SceneView {
    Span<const Vec3f> positions;      // all mesh vertices, world space
    Span<const Vec3f> normals;        // per vertex; meaningful where the owning shape hasNormals
    Span<const Vec2f> uvs;            // per vertex; meaningful where the owning shape hasUVs
    Span<const Vec3u> triangles;      // global vertex indices
    Span<const uint32_t> triangleShape;  // shape of each triangle
    Span<const Sphere> spheres;
    Span<const Shape> shapes;
    Span<const Bsdf> bsdfs;
    Span<const Light> lights;
    Span<const float> lightCdf;       // per-area-light triangle CDFs (see Light::cdfOffset)
    int32_t environmentLight = -1;    // index of the constant emitter, -1 if none
    Camera camera;

    CA_HD uint32_t numTriangles() const { return uint32_t(triangles.size()); }
    CA_HD uint32_t numPrimitives() const { return uint32_t(triangles.size() + spheres.size()); }
    /// The shape a primitive id (triangles first, then spheres) belongs to.
    CA_HD uint32_t shapeOf(uint32_t primId) const {
        return primId < numTriangles() ? triangleShape[primId] : spheres[primId - numTriangles()].shape;
    }
};

struct Scene {
    std::vector<Vec3f> positions, normals;
    std::vector<Vec2f> uvs;
    std::vector<Vec3u> triangles;
    std::vector<uint32_t> triangleShape;
    std::vector<Sphere> spheres;
    std::vector<Shape> shapes;
    std::vector<Bsdf> bsdfs;
    std::vector<Light> lights;
    std::vector<float> lightCdf;
    int32_t environmentLight = -1;

    Camera camera;
    FilmDesc film;
    IntegratorDesc integrator;
    int sampleCount = 4;   // sampler sample_count (samples per pixel)
    uint64_t seed = 0;     // sampler seed (Mitsuba's <integer name="seed">)
    std::string sourceFile;

    SceneView view() const {
        SceneView v;
        v.positions = positions; v.normals = normals; v.uvs = uvs; v.triangles = triangles;
        v.triangleShape = triangleShape; v.spheres = spheres; v.shapes = shapes; v.bsdfs = bsdfs;
        v.lights = lights; v.lightCdf = lightCdf; v.environmentLight = environmentLight;
        v.camera = camera;
        return v;
    }
    uint32_t numPrimitives() const { return uint32_t(triangles.size() + spheres.size()); }
    /// World-space bounds of all geometry.
    Bounds3f bounds() const;
    /// Bounds of one primitive (triangles first, then spheres).
    Bounds3f primitiveBounds(uint32_t primId) const;
};

}  // namespace caustica
