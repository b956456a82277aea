// build_shapes.cpp — Mitsuba 3 shape plugins -> meshes, spheres and cylinders in the flat Scene
// arrays; shapegroup + instance are flattened into world-space copies.
//
// | plugin     | parameters (default)                                                         |
// |------------|------------------------------------------------------------------------------|
// | obj        | filename, face_normals (false), flip_tex_coords (true), to_world             |
// | ply        | filename, face_normals (false), to_world                                     |
// | serialized | filename, shape_index (0), face_normals (false), to_world                    |
// | rectangle  | to_world ([-1,1]² in z = 0, normal +z)                                       |
// | cube       | to_world ([-1,1]³, outward normals), face_normals (false)                    |
// | disk       | to_world (unit disk in z = 0, normal +z; 512-segment fan, area error 2.5e-5) |
// | sphere     | center (0), radius (1), to_world (uniform scale only)                        |
// | cylinder   | p0 (0,0,0), p1 (0,0,1), radius (1), to_world (no shear, no mirroring)        |
// | shapegroup | nested or referenced shapes, drawn only through instances                    |
// | instance   | one shapegroup (nested or referenced), to_world                              |
// Every shape: flip_normals (false), one nested or referenced bsdf (default diffuse 0.5), one
// nested or referenced area emitter (not inside a shapegroup, as in Mitsuba).
#include <cmath>

#include "caustica/io/mesh/obj_loader.h"
#include "caustica/io/mesh/ply_loader.h"
#include "caustica/io/mesh/serialized_loader.h"
#include "caustica/io/mesh/shape_meshes.h"
#include "caustica/io/mitsuba/build_context.h"
#include "caustica/io/mitsuba/plugin_table.h"
#include "caustica/io/mitsuba/shape_geometry.h"
#include "caustica/util/error.h"

namespace caustica::mitsuba {

namespace {

using meshio::TriangleMesh;

/// What a shape plugin reads: its parameters and the transform of the instance drawing it
/// (identity outside instances), applied after the shape's own to_world.
struct ShapeArgs {
    BuildContext& ctx;
    Params& p;
    Transform outer;

    Transform toWorld() const { return outer * p.getTransform("to_world"); }
};

/// Loads a mesh file; loader errors are reported at the XML line of `filename`, naming the mesh
/// file and its own line as well.
template <class LoadFn>
TriangleMesh loadMeshFile(const ShapeArgs& a, LoadFn load) {
    const Property* prop = a.p.find("filename");
    if (!prop) a.p.fail("missing required parameter 'filename'");
    const std::string path = a.ctx.resolvePath(a.p.object(), a.p.getString("filename"));
    try {
        return load(path);
    } catch (const Error& e) {
        throw Error(prop->where.file, prop->where.line, a.p.object().describe() + ": " + e.what());
    }
}

/// The steps Mitsuba's mesh plugins share: to_world, then face normals or vertex normals.
ShapeGeometry finishMesh(const ShapeArgs& a, TriangleMesh mesh, bool readFaceNormals,
                         bool computeMissingNormals) {
    const Transform toWorld = a.toWorld();
    const bool faceNormals = readFaceNormals && a.p.getBool("face_normals", false);
    meshio::transformMesh(mesh, toWorld);
    if (faceNormals)
        mesh.normals.clear();
    else if (!mesh.hasNormals() && computeMissingNormals)
        meshio::computeVertexNormals(mesh);
    try {
        meshio::validateMesh(mesh, a.p.object().where.file);
    } catch (const Error& e) {
        a.p.fail(e.reason() + " after to_world");
    }
    ShapeGeometry g;
    g.mesh = std::move(mesh);
    return g;
}

ShapeGeometry objShape(ShapeArgs& a) {
    const bool flip = a.p.getBool("flip_tex_coords", true);
    TriangleMesh m = loadMeshFile(a, [&](const std::string& f) { return meshio::loadObj(f, flip); });
    return finishMesh(a, std::move(m), true, true);
}

ShapeGeometry plyShape(ShapeArgs& a) {
    TriangleMesh m = loadMeshFile(a, [](const std::string& f) { return meshio::loadPly(f); });
    return finishMesh(a, std::move(m), true, true);
}

/// Mitsuba 3's serialized plugin. The file's FaceNormals flag is ignored, as Mitsuba 3.9.1 does
/// (only the face_normals parameter discards the normals).
ShapeGeometry serializedShape(ShapeArgs& a) {
    const int index = a.p.getInt("shape_index", 0);
    if (index < 0) a.p.fail(*a.p.find("shape_index"), "must not be negative");
    TriangleMesh m = loadMeshFile(
        a, [&](const std::string& f) { return meshio::loadSerialized(f, index).mesh; });
    return finishMesh(a, std::move(m), true, true);
}

ShapeGeometry rectangleShape(ShapeArgs& a) {
    return finishMesh(a, meshio::makeRectangle(), false, false);
}

ShapeGeometry cubeShape(ShapeArgs& a) {
    return finishMesh(a, meshio::makeCube(), true, false);
}

ShapeGeometry diskShape(ShapeArgs& a) {
    return finishMesh(a, meshio::makeDisk(), false, false);
}

ShapeGeometry sphereShape(ShapeArgs& a) {
    const Vec3f center = a.p.getPoint("center", Vec3f(0));
    const Float radius = a.p.getFloat("radius", 1.0f);
    if (radius == 0) a.p.fail(*a.p.find("radius"), "must not be zero");
    return makeSphereGeometry(a.p, a.toWorld() * translate(center) * scale(Vec3f(radius)));
}

ShapeGeometry cylinderShape(ShapeArgs& a) {
    const Vec3f p0 = a.p.getPoint("p0", Vec3f(0, 0, 0));
    const Vec3f p1 = a.p.getPoint("p1", Vec3f(0, 0, 1));
    const Float radius = a.p.getFloat("radius", 1.0f);
    if (!(radius > 0)) a.p.fail(*a.p.find("radius"), "must be positive");
    return makeCylinderGeometry(a.p, a.toWorld(), p0, p1, radius);
}

using ShapeFn = ShapeGeometry (*)(ShapeArgs&);
const PluginTable<ShapeFn> kShapePlugins{
    {{"cube", cubeShape},
     {"cylinder", cylinderShape},
     {"disk", diskShape},
     {"obj", objShape},
     {"ply", plyShape},
     {"rectangle", rectangleShape},
     {"serialized", serializedShape},
     {"sphere", sphereShape}},
    {{"bsplinecurve", "curves are not supported"},
     {"linearcurve", "curves are not supported"},
     {"sdfgrid", "SDF grids are not supported"},
     {"ellipsoids", "ellipsoids are not supported"},
     {"ellipsoidsmesh", "ellipsoids are not supported"}}};

/// Appends the geometry to the scene's flat arrays and returns the new shape's record.
Shape appendGeometry(const Params& p, Scene& scene, const ShapeGeometry& g, uint32_t shapeIndex) {
    if (g.kind == ShapeGeometry::Kind::Sphere)
        return appendPrimitiveShape(ShapeType::Sphere, scene.spheres, g.sphere, shapeIndex);
    if (g.kind == ShapeGeometry::Kind::Cylinder)
        return appendPrimitiveShape(ShapeType::Cylinder, scene.cylinders, g.cylinder, shapeIndex);
    Shape s;
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

/// Builds one geometric shape (not a group or instance) drawn with `outer`. Inside a
/// shapegroup (`inGroup`) the shape may not emit; its parameters are checked once (`report`).
void buildGeometricShape(BuildContext& ctx, int object, const Transform& outer, bool inGroup,
                         bool report) {
    ctx.used.insert(object);
    Params p(ctx.desc, object);
    ShapeArgs args{ctx, p, outer};
    ShapeGeometry g = kShapePlugins.find(p)(args);
    const bool flip = p.getBool("flip_normals", false);

    std::vector<int> bsdfs = p.takeChildren("bsdf");
    if (bsdfs.size() > 1) p.failAtChild(bsdfs[1], "a shape takes at most one bsdf");
    std::vector<int> emitters = p.takeChildren("emitter");
    if (emitters.size() > 1) p.failAtChild(emitters[1], "a shape takes at most one emitter");
    if (inGroup && !emitters.empty())
        p.failAtChild(emitters[0], "emitters cannot be instanced (a shape inside a shapegroup "
                                   "cannot carry an emitter, as in Mitsuba)");
    for (int e : emitters) {
        const ObjectEntity& em = ctx.desc.objects[size_t(e)];
        if (em.type != "area")
            p.failAtChild(e,
                          "only area emitters can be attached to a shape, not '" + em.type + "'");
        if (ctx.used.count(e)) p.failAtChild(e, em.describe() + " is already attached to a shape");
    }
    std::vector<std::string> ignored;
    p.finish(report ? ctx.warnings : ignored);

    const uint32_t shapeIndex = uint32_t(ctx.scene.shapes.size());
    Shape s = appendGeometry(p, ctx.scene, g, shapeIndex);
    s.flipNormals = flip != g.mirrored;
    // Mitsuba 3 gives an emitting shape without a BSDF a black diffuse one.
    s.bsdf = bsdfs.empty() ? ctx.defaultBsdf(!emitters.empty()) : ctx.bsdf(bsdfs[0]);
    ctx.scene.shapes.push_back(s);
    if (!emitters.empty()) buildEmitter(ctx, emitters[0], int32_t(shapeIndex));
}

/// The shapes of a shapegroup, checked: geometric shapes only (no nested groups or instances).
std::vector<int> groupMembers(BuildContext& ctx, int group) {
    ctx.used.insert(group);
    Params p(ctx.desc, group);
    std::vector<int> shapes = p.takeChildren("shape");
    for (int s : shapes) {
        const std::string& type = ctx.desc.objects[size_t(s)].type;
        if (type == "shapegroup" || type == "instance")
            p.failAtChild(s, "a shapegroup cannot contain a " + type + " (nested instancing is "
                             "not supported, as in Mitsuba)");
    }
    p.finish(ctx.warnings);
    return shapes;
}

/// Mitsuba's instance: draws the shapes of one shapegroup under to_world. caustica flattens each
/// instance into world-space copies of the group's shapes (memory grows with the instances).
void buildInstance(BuildContext& ctx, int object) {
    ctx.used.insert(object);
    Params p(ctx.desc, object);
    std::vector<int> groups = p.takeChildren("shape");
    if (groups.size() != 1 || ctx.desc.objects[size_t(groups[0])].type != "shapegroup")
        p.fail("an instance needs exactly one shapegroup (nested or referenced)");
    const Transform toWorld = p.getTransform("to_world");
    p.finish(ctx.warnings);
    for (int member : groupMembers(ctx, groups[0])) {
        const bool firstUse = !ctx.used.count(member);  // report its warnings once
        buildGeometricShape(ctx, member, toWorld, true, firstUse);
    }
}

}  // namespace

void buildShape(BuildContext& ctx, int object) {
    const std::string& type = ctx.desc.objects[size_t(object)].type;
    if (type == "shapegroup")
        groupMembers(ctx, object);  // checked now; drawn only through instances
    else if (type == "instance")
        buildInstance(ctx, object);
    else
        buildGeometricShape(ctx, object, Transform(), false, true);
}

}  // namespace caustica::mitsuba
