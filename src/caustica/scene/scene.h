// scene.h — the flattened, device-ready scene. `Scene` owns host arrays; `SceneView` is the plain
// struct of spans that kernels take (on the GPU its spans point to device copies).
// scene/ knows nothing of files: io/ builds a Scene, integrators read a SceneView.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "caustica/scene/bsdf_data.h"
#include "caustica/scene/camera.h"
#include "caustica/scene/integrator_spec.h"
#include "caustica/scene/light_data.h"
#include "caustica/scene/shape.h"
#include "caustica/scene/texture.h"
#include "caustica/util/span.h"

namespace caustica {

enum class FilterType : uint32_t { Box, Tent, Gaussian };

/// Image reconstruction filter, as Mitsuba's rfilter plugins define it.
struct FilterDesc {
    FilterType type = FilterType::Gaussian;
    Float radius = 2.0f;   // support half-width in pixels (box 0.5, tent 1, gaussian 4 * stddev)
    Float stddev = 0.5f;   // gaussian only
};

enum class ToneMapMethod : uint32_t { Gamma, Reinhard };

/// Mitsuba's ldrfilm (0.6; Mitsuba 3 has none): how PNG output maps radiance to 8 bits
/// (film/tonemap.h). Without an ldrfilm PNGs are plain sRGB and the default output is EXR.
struct ToneMapDesc {
    bool ldr = false;                    // the film is an ldrfilm: default output .png
    ToneMapMethod method = ToneMapMethod::Gamma;
    Float gamma = -1;                    // -1: the sRGB curve; else v^(1/gamma)
    Float exposure = 0;                  // gamma method: radiance x 2^exposure
    Float key = 0.18f, burn = 0;         // reinhard: key value and burn-out (0..1)
};

/// The rendered image: width x height pixels (a crop window's size when cropped; the camera
/// holds the full size and the window's offset).
struct FilmDesc {
    int width = 768, height = 576;
    int eyeWidth = 0;  // stereo (scene/stereo_rig.h): one eye's width, the seam a border; 0 mono
    FilterDesc filter;
    ToneMapDesc tonemap;
};

/// World-space bounds of an analytic cylinder (scene.cpp).
Bounds3f cylinderBounds(const Cylinder& c);

struct SceneView {
    Span<const Vec3f> positions;      // all mesh vertices, world space
    Span<const Vec3f> normals;        // per vertex; meaningful where the owning shape hasNormals
    Span<const Vec2f> uvs;            // per vertex; meaningful where the owning shape hasUVs
    Span<const Vec3u> triangles;      // global vertex indices
    Span<const uint32_t> triangleShape;  // shape of each triangle
    Span<const Sphere> spheres;
    Span<const Cylinder> cylinders;
    Span<const Shape> shapes;
    Span<const Bsdf> bsdfs;
    Span<const Light> lights;
    Span<const float> lightCdf;       // per-area-light triangle CDFs (see Light::cdfOffset)
    Span<const Spectrum> lightTexels; // envmap texels (see Light::texOffset)
    int32_t environmentLight = -1;    // index of the constant emitter, -1 if none
    Camera camera;
    Span<const Texture> textures;     // BSDF textures (texture.h)
    Span<const Spectrum> texels;      // bitmap texels of `textures` (Texture::texelOffset)

    CA_HD TextureView textureView() const { return {textures, texels}; }

    CA_HD uint32_t numTriangles() const { return uint32_t(triangles.size()); }
    /// Primitive ids: triangles first, then spheres, then cylinders.
    CA_HD uint32_t numPrimitives() const {
        return uint32_t(triangles.size() + spheres.size() + cylinders.size());
    }
    CA_HD uint32_t firstCylinder() const { return uint32_t(triangles.size() + spheres.size()); }
    /// The shape a primitive id belongs to.
    CA_HD uint32_t shapeOf(uint32_t primId) const {
        if (primId < numTriangles()) return triangleShape[primId];
        if (primId < firstCylinder()) return spheres[primId - numTriangles()].shape;
        return cylinders[primId - firstCylinder()].shape;
    }
};

struct Scene {
    std::vector<Vec3f> positions, normals;
    std::vector<Vec2f> uvs;
    std::vector<Vec3u> triangles;
    std::vector<uint32_t> triangleShape;
    std::vector<Sphere> spheres;
    std::vector<Cylinder> cylinders;
    std::vector<Shape> shapes;
    std::vector<Bsdf> bsdfs;
    std::vector<Light> lights;
    std::vector<float> lightCdf;
    std::vector<Spectrum> lightTexels;
    std::vector<Texture> textures;
    std::vector<Spectrum> texels;
    int32_t environmentLight = -1;

    Camera camera;
    FilmDesc film;
    IntegratorSpec integrator;  // the <integrator> as written; each integrator reads its own settings
    int sampleCount = 4;   // sampler sample_count (samples per pixel)
    uint64_t seed = 0;     // sampler seed (Mitsuba's <integer name="seed">)
    std::string sourceFile;
    /// Every file the scene was read from (scene XML, includes, meshes, images) in reading order,
    /// possibly repeated: a checkpoint identifies the render by their contents (render/).
    std::vector<std::string> inputFiles;

    SceneView view() const {
        SceneView v;
        v.positions = positions; v.normals = normals; v.uvs = uvs; v.triangles = triangles;
        v.triangleShape = triangleShape; v.spheres = spheres; v.cylinders = cylinders; v.shapes = shapes; v.bsdfs = bsdfs;
        v.lights = lights; v.lightCdf = lightCdf; v.lightTexels = lightTexels;
        v.environmentLight = environmentLight;
        v.camera = camera;
        v.textures = textures; v.texels = texels;
        return v;
    }
    uint32_t numPrimitives() const {
        return uint32_t(triangles.size() + spheres.size() + cylinders.size());
    }
    /// World-space bounds of all geometry.
    Bounds3f bounds() const;
    /// Bounds of one primitive (triangles first, then spheres, then cylinders).
    Bounds3f primitiveBounds(uint32_t primId) const;
};

/// Gives `scene.positions` spare capacity for one more vertex, so that Embree can read the array
/// in place (its 16-byte loads read 4 bytes past the last vertex; accel/embree_accel.h,
/// sharesVertexArray). Call once the positions are complete; the contents do not change.
void reserveVertexPadding(Scene& scene);

/// Appends `prim` (a Sphere or a Cylinder) to `prims` as the one primitive of shape `shapeIndex`
/// and returns that shape's record (type, primOffset, primCount = 1; the caller sets the rest).
template <class Prim>
Shape appendPrimitiveShape(ShapeType type, std::vector<Prim>& prims, Prim prim,
                           uint32_t shapeIndex) {
    Shape s;
    s.type = type;
    s.primOffset = uint32_t(prims.size());
    s.primCount = 1;
    prim.shape = shapeIndex;
    prims.push_back(prim);
    return s;
}

}  // namespace caustica
