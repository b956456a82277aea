// build_shapes.cpp — Mitsuba 3 shape plugins -> meshes and spheres in the flat Scene arrays.
//
// | plugin    | parameters (default)                                                          |
// |-----------|-------------------------------------------------------------------------------|
// | obj       | filename, face_normals (false), flip_tex_coords (true), to_world              |
// | ply       | filename, face_normals (false), to_world                                      |
// | rectangle | to_world ([-1,1]² in z = 0, normal +z)                                        |
// | cube      | to_world ([-1,1]³, outward normals), face_normals (false)                     |
// | disk      | to_world (unit disk in z = 0, normal +z; 512-segment fan, area error 2.5e-5)  |
// | sphere    | center (0), radius (1), to_world (uniform scale only)                         |
// Every shape: flip_normals (false), one nested or referenced bsdf (default diffuse 0.5), one
// nested or referenced area emitter.
#include <cmath>

#include "caustica/io/mesh/obj_loader.h"
#include "caustica/io/mesh/ply_loader.h"
#include "caustica/io/mesh/shape_meshes.h"
#include "caustica/io/mitsuba/build_context.h"
#include "caustica/io/mitsuba/plugin_table.h"
#include "caustica/util/error.h"

namespace caustica::mitsuba {

namespace {

using meshio::TriangleMesh;

/// What a shape plugin produces: a world-space mesh or an analytic sphere.
struct ShapeGeometry {
    bool isSphere = false;
    Sphere sphere;
    bool mirrored = false;  // sphere: to_world mirrors, which turns Mitsuba's normals inwards
    TriangleMesh mesh;
};

/// Loads a mesh file; loader errors are reported at the XML line of `filename`, naming the mesh
/// file and its own line as well.
template <class LoadFn>
TriangleMesh loadMeshFile(BuildContext& ctx, const Params& p, LoadFn load) {
    const Property* prop = p.find("filename");
    if (!prop) p.fail("missing required parameter 'filename'");
    const std::string path = ctx.resolvePath(p.object(), p.getString("filename"));
    try {
        return load(path);
    } catch (const Error& e) {
        throw Error(prop->where.file, prop->where.line, p.object().describe() + ": " + e.what());
    }
}

/// The steps Mitsuba's mesh plugins share: to_world, then face normals or vertex normals.
ShapeGeometry finishMesh(const Params& p, TriangleMesh mesh, bool readFaceNormals,
                         bool computeMissingNormals) {
    const Transform toWorld = p.getTransform("to_world");
    const bool faceNormals = readFaceNormals && p.getBool("face_normals", false);
    meshio::transformMesh(mesh, toWorld);
    if (faceNormals)
        mesh.normals.clear();
    else if (!mesh.hasNormals() && computeMissingNormals)
        meshio::computeVertexNormals(mesh);
    try {
        meshio::validateMesh(mesh, p.object().where.file);
    } catch (const Error& e) {
        p.fail(e.reason() + " after to_world");
    }
    ShapeGeometry g;
    g.mesh = std::move(mesh);
    return g;
}

ShapeGeometry objShape(BuildContext& ctx, Params& p) {
    const bool flip = p.getBool("flip_tex_coords", true);
    TriangleMesh m =
        loadMeshFile(ctx, p, [&](const std::string& f) { return meshio::loadObj(f, flip); });
    return finishMesh(p, std::move(m), true, true);
}

ShapeGeometry plyShape(BuildContext& ctx, Params& p) {
    TriangleMesh m = loadMeshFile(ctx, p, [](const std::string& f) { return meshio::loadPly(f); });
    return finishMesh(p, std::move(m), true, true);
}

ShapeGeometry rectangleShape(BuildContext&, Params& p) {
    return finishMesh(p, meshio::makeRectangle(), false, false);
}

ShapeGeometry cubeShape(BuildContext&, Params& p) {
    return finishMesh(p, meshio::makeCube(), true, false);
}

ShapeGeometry diskShape(BuildContext&, Params& p) {
    return finishMesh(p, meshio::makeDisk(), false, false);
}

/// Mitsuba 3's sphere: to_world * translate(center) * scale(radius); the result must be a
/// similarity (rotation, uniform scale, translation). A mirroring transform flips the normals.
ShapeGeometry sphereShape(BuildContext&, Params& p) {
    const Vec3f center = p.getPoint("center", Vec3f(0));
    const Float radius = p.getFloat("radius", 1.0f);
    if (radius == 0) p.fail(*p.find("radius"), "must not be zero");
    const Transform toWorld = p.getTransform("to_world");
    const Transform t = toWorld * translate(center) * scale(Vec3f(radius));
    Vec3f col[3];
    for (int c = 0; c < 3; ++c) col[c] = Vec3f(t.m.m[0][c], t.m.m[1][c], t.m.m[2][c]);
    const Float s = length(col[0]);
    const Float tol = 1e-4f * s * s;
    for (int c = 1; c < 3; ++c)
        if (std::fabs(lengthSquared(col[c]) - s * s) > tol)
            p.fail("to_world must scale uniformly (a sphere cannot become an ellipsoid)");
    if (std::fabs(dot(col[0], col[1])) > tol || std::fabs(dot(col[0], col[2])) > tol ||
        std::fabs(dot(col[1], col[2])) > tol)
        p.fail("to_world must not shear a sphere");
    if (t.m.m[3][0] != 0 || t.m.m[3][1] != 0 || t.m.m[3][2] != 0 || t.m.m[3][3] != 1)
        p.fail("to_world must be affine for a sphere");
    ShapeGeometry g;
    g.isSphere = true;
    g.sphere.center = t.applyPoint(Vec3f(0));
    g.sphere.radius = s;
    g.mirrored = dot(cross(col[0], col[1]), col[2]) < 0;
    if (!isFinite(g.sphere.center) || !std::isfinite(s)) p.fail("sphere is not finite");
    return g;
}

using ShapeFn = ShapeGeometry (*)(BuildContext&, Params&);
const PluginTable<ShapeFn> kShapePlugins{{{"cube", cubeShape},
                                          {"disk", diskShape},
                                          {"obj", objShape},
                                          {"ply", plyShape},
                                          {"rectangle", rectangleShape},
                                          {"sphere", sphereShape}}};

/// Appends the geometry to the scene's flat arrays and returns the new shape's record.
Shape appendGeometry(const Params& p, Scene& scene, ShapeGeometry& g, uint32_t shapeIndex) {
    Shape s;
    if (g.isSphere) {
        s.type = ShapeType::Sphere;
        s.primOffset = uint32_t(scene.spheres.size());
        s.primCount = 1;
        g.sphere.shape = shapeIndex;
        scene.spheres.push_back(g.sphere);
        return s;
    }
    const TriangleMesh& m = g.mesh;
    if (scene.positions.size() + m.positions.size() >= 0xffffffffull ||
        scene.triangles.size() + m.triangles.size() >= 0xffffffffull)
        p.fail("the scene has more than 2^32 - 1 vertices or triangles");
    const uint32_t base = uint32_t(scene.positions.size());
    s.type = ShapeType::Mesh;
    s.primOffset = uint32_t(scene.triangles.size());
    s.primCount = uint32_t(m.triangles.size());
    s.hasNormals = m.hasNormals();
    s.hasUVs = m.hasUVs();
    scene.positions.insert(scene.positions.end(), m.positions.begin(), m.positions.end());
    if (m.hasNormals())
        scene.normals.insert(scene.normals.end(), m.normals.begin(), m.normals.end());
    else
        scene.normals.resize(scene.positions.size(), Vec3f(0));
    if (m.hasUVs())
        scene.uvs.insert(scene.uvs.end(), m.uvs.begin(), m.uvs.end());
    else
        scene.uvs.resize(scene.positions.size(), Vec2f(0, 0));
    for (const Vec3u& t : m.triangles) {
        scene.triangles.push_back({base + t.x, base + t.y, base + t.z});
        scene.triangleShape.push_back(shapeIndex);
    }
    return s;
}

}  // namespace

void buildShape(BuildContext& ctx, int object) {
    ctx.used.insert(object);
    Params p(ctx.desc, object);
    ShapeGeometry g = kShapePlugins.find(p)(ctx, p);
    const bool flip = p.getBool("flip_normals", false);

    std::vector<int> bsdfs = p.takeChildren("bsdf");
    if (bsdfs.size() > 1) p.failAtChild(bsdfs[1], "a shape takes at most one bsdf");
    std::vector<int> emitters = p.takeChildren("emitter");
    if (emitters.size() > 1) p.failAtChild(emitters[1], "a shape takes at most one emitter");
    for (int e : emitters) {
        const ObjectEntity& em = ctx.desc.objects[size_t(e)];
        if (em.type != "area")
            p.failAtChild(e,
                          "only area emitters can be attached to a shape, not '" + em.type + "'");
        if (ctx.used.count(e)) p.failAtChild(e, em.describe() + " is already attached to a shape");
    }
    p.finish(ctx.warnings);

    const uint32_t shapeIndex = uint32_t(ctx.scene.shapes.size());
    Shape s = appendGeometry(p, ctx.scene, g, shapeIndex);
    s.flipNormals = flip != g.mirrored;
    // Mitsuba 3 gives an emitting shape without a BSDF a black diffuse one.
    s.bsdf = bsdfs.empty() ? ctx.defaultBsdf(!emitters.empty()) : ctx.bsdf(bsdfs[0]);
    ctx.scene.shapes.push_back(s);
    if (!emitters.empty()) buildEmitter(ctx, emitters[0], int32_t(shapeIndex));
}

}  // namespace caustica::mitsuba
