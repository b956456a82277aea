// build_textures.cpp — Mitsuba 3 texture plugins -> caustica::Texture records; texture-valued BSDF
// parameters; the bumpmap and normalmap BSDF adapters.
//
// | plugin       | parameters (default)                                                        |
// |--------------|-----------------------------------------------------------------------------|
// | bitmap       | filename (.png, .jpg/.jpeg, .exr, .hdr, .pfm), filter_type (bilinear or     |
// |              | nearest), wrap_mode (repeat, mirror or clamp), raw (false: 8/16-bit images  |
// |              | are sRGB-decoded; float images are linear), to_uv (identity), format (auto: |
// |              | 8/16-bit texels rounded to half floats as Mitsuba stores them; variant;     |
// |              | fp16), accel (true; ignored)                                                |
// | checkerboard | color0 (0.4), color1 (0.2) (values or textures, evaluated at the unchanged  |
// |              | uv as Mitsuba), to_uv (identity)                                            |
// | rawconstant  | value (1): a <float>, or a <vector> (three channels; not for float params)  |
// | bumpmap      | one nested texture (the height field; a bitmap), one nested bsdf, scale (1),|
// |              | flip_invalid_normals (true), use_shadowing_function (true)                  |
// | normalmap    | a nested texture named "normalmap" (tangent-space normals, 2 rgb - 1; use  |
// |              | raw="true"), one nested bsdf, flip_invalid_normals, use_shadowing_function  |
#include "caustica/io/mitsuba/build_textures.h"

#include <Imath/half.h>

#include "caustica/io/image_io.h"
#include "caustica/io/mitsuba/plugin_table.h"
#include "caustica/util/error.h"

namespace caustica::mitsuba {

namespace {

/// Mitsuba's to_uv: a 3x3 transform of (u, v, 1); from an XML 4x4 <transform>, the third row and
/// column are dropped (translate/scale/rotate about z act on uv).
void readToUv(const Params& p, Texture& t) {
    if (!p.has("to_uv")) return;
    const Matrix4& m = p.getTransform("to_uv").m;
    if (m.m[3][0] != 0 || m.m[3][1] != 0 || m.m[3][3] != 1)
        p.fail(*p.find("to_uv"), "must be an affine transform of uv");
    const Float e[6] = {m.m[0][0], m.m[0][1], m.m[0][3], m.m[1][0], m.m[1][1], m.m[1][3]};
    for (int i = 0; i < 6; ++i) t.toUv[i] = e[i];
}

/// Rounds to the nearest half float, as Mitsuba stores 8- and 16-bit bitmaps (format "auto").
float roundToHalf(float v) { return float(Imath::half(v)); }

Texture bitmap(BuildContext& ctx, Params& p) {
    Texture t;
    t.type = TextureType::Bitmap;
    const std::string file = p.getString("filename");
    const std::string path = ctx.resolvePath(p.object(), file);
    const std::string filter = p.getString("filter_type", "bilinear");
    if (filter == "bilinear")
        t.filter = TextureFilter::Bilinear;
    else if (filter == "nearest")
        t.filter = TextureFilter::Nearest;
    else
        p.fail(*p.find("filter_type"), "must be 'bilinear' or 'nearest', not '" + filter + "'");
    const std::string wrap = p.getString("wrap_mode", "repeat");
    if (wrap == "repeat")
        t.wrap = TextureWrap::Repeat;
    else if (wrap == "mirror")
        t.wrap = TextureWrap::Mirror;
    else if (wrap == "clamp")
        t.wrap = TextureWrap::Clamp;
    else
        p.fail(*p.find("wrap_mode"), "must be 'repeat', 'mirror' or 'clamp', not '" + wrap + "'");
    const std::string format = p.getString("format", "auto");
    if (format != "auto" && format != "variant" && format != "fp16")
        p.fail(*p.find("format"), "must be 'auto', 'variant' or 'fp16', not '" + format + "'");
    p.getBool("accel", true);  // CUDA hardware interpolation in Mitsuba; no effect here
    readToUv(p, t);
    ImageReadOptions options;
    options.raw = p.getBool("raw", false);
    ImageFileInfo info;
    Image image;
    try {
        image = readImage(path, options, &info);
    } catch (const Error& e) {
        p.fail(*p.find("filename"), e.what());
    }
    if (image.empty()) p.fail(*p.find("filename"), "the image has no pixels");
    if (image.width < 2 || image.height < 2) {
        // Mitsuba resamples to at least 2 x 2 with a tent filter, which repeats a lone row or
        // column (textures/bitmap.cpp, expand_bitmap).
        Image grown(image.width < 2 ? 2 : image.width, image.height < 2 ? 2 : image.height);
        for (int y = 0; y < grown.height; ++y)
            for (int x = 0; x < grown.width; ++x)
                grown.set(x, y, image.at(x < image.width ? x : 0, y < image.height ? y : 0));
        image = std::move(grown);
    }
    if (!image.allFinite()) p.fail(*p.find("filename"), "the image has non-finite pixels");
    const bool half = format == "fp16" || (format == "auto" && info.bitsPerChannel <= 16);
    t.width = image.width;
    t.height = image.height;
    t.texelOffset = uint32_t(ctx.scene.texels.size());
    double sum = 0;
    ctx.scene.texels.reserve(ctx.scene.texels.size() + image.pixelCount());
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            Spectrum c = image.at(x, y);
            if (half) c = {roundToHalf(c.r), roundToHalf(c.g), roundToHalf(c.b)};
            ctx.scene.texels.push_back(c);
            sum += c.luminance();
        }
    t.mean = Float(sum / double(image.pixelCount()));
    return t;
}

/// A checkerboard colour: a value, or a nested/referenced texture (`child`; a constant one is
/// kept as its value). Returns Mitsuba's mean() of the colour.
Float checkerColour(BuildContext& ctx, Params& p, const std::string& name, Spectrum def,
                    Spectrum& value, uint32_t& child) {
    const int object = findTextureChild(p, name);
    if (object < 0) {
        value = p.getSpectrum(name, def);
        return value.average();
    }
    if (const Property* prop = p.find(name))
        p.fail(*prop, "'" + name + "' is given both as a value and as a texture");
    const uint32_t index = buildTexture(ctx, object);
    const Texture& t = ctx.scene.textures[index];
    if (t.type == TextureType::Constant)
        value = t.value;
    else
        child = index;
    return t.mean;
}

Texture checkerboard(BuildContext& ctx, Params& p) {
    for (const ChildRef& c : p.object().children)
        if (ctx.desc.objects[size_t(c.object)].category == "texture" && c.name != "color0" &&
            c.name != "color1")
            p.failAtChild(c.object, "texture '" + c.name +
                                        "' is not a parameter of checkerboard (color0, color1)");
    p.takeChildren("texture");
    Texture t;
    t.type = TextureType::Checkerboard;
    const Float mean0 = checkerColour(ctx, p, "color0", Spectrum(0.4f), t.value, t.child0);
    const Float mean1 = checkerColour(ctx, p, "color1", Spectrum(0.2f), t.value1, t.child1);
    readToUv(p, t);
    t.mean = (mean0 + mean1) / 2;
    return t;
}

/// Mitsuba's rawconstant: a <float> (one channel) or a <vector> (three); it refuses an <rgb>.
Texture rawConstant(BuildContext&, Params& p) {
    Texture t;
    t.type = TextureType::Constant;
    const Property* value = p.find("value");
    if (!value || value->type == PropertyType::Float || value->type == PropertyType::Integer) {
        t.value = p.getSpectrum("value", Spectrum(1.0f));
    } else if (value->type == PropertyType::Vector || value->type == PropertyType::Point) {
        t.value = Spectrum(value->vector.x, value->vector.y, value->vector.z);
        if (!t.value.isValid()) p.fail(*value, "must be finite and non-negative");
    } else {
        p.fail(*value, "must be a <float> or a <vector>, as Mitsuba's rawconstant requires");
    }
    t.mean = t.value.average();
    return t;
}

/// A rawconstant given a <vector>: three channels, which a float parameter cannot take.
bool isThreeChannelConstant(const SceneDescription& desc, int object) {
    const ObjectEntity& o = desc.objects[size_t(object)];
    if (o.type != "rawconstant") return false;
    for (const Property& q : o.properties)
        if (q.name == "value") return q.type == PropertyType::Vector || q.type == PropertyType::Point;
    return false;
}

using TextureFn = Texture (*)(BuildContext&, Params&);
const PluginTable<TextureFn> kTexturePlugins{
    {{"bitmap", bitmap}, {"checkerboard", checkerboard}, {"rawconstant", rawConstant}},
    {{"mesh_attribute", "mesh attributes are not supported"},
     {"volume", "volume textures are not supported"}}};

void addTexture(const Params& p, Bsdf& b, BsdfParam param, uint32_t texture) {
    if (b.numTextures >= uint32_t(kMaxBsdfTextures))
        p.fail("too many textured parameters (at most " + std::to_string(kMaxBsdfTextures) + ")");
    b.textures[b.numTextures++] = {param, texture};
}

/// The texture `child` of `p` for parameter `name` (not also given as a value).
const Texture& textureFor(BuildContext& ctx, Params& p, const std::string& name, int child,
                          uint32_t& index) {
    if (const Property* prop = p.find(name))
        p.fail(*prop, "'" + name + "' is given both as a value and as a texture");
    p.takeChildren("texture");  // checkTextureChildren reports the ones nobody read
    index = buildTexture(ctx, child);
    return ctx.scene.textures[index];
}

/// The nested bsdf of an adapter; a second bumpmap/normalmap in the chain is refused (kernels
/// resolve one perturbed frame).
uint32_t adapterChild(BuildContext& ctx, Params& p) {
    const std::vector<int> children = p.takeChildren("bsdf");
    if (children.size() != 1)
        p.fail("needs exactly one nested bsdf, got " + std::to_string(children.size()));
    const uint32_t id = ctx.bsdf(children[0]);
    auto isAdapter = [&](uint32_t i) {
        const BsdfType t = ctx.scene.bsdfs[i].type;
        return t == BsdfType::BumpMap || t == BsdfType::NormalMap;
    };
    const Bsdf& child = ctx.scene.bsdfs[id];
    if (isAdapter(id) ||
        (child.type == BsdfType::TwoSided && (isAdapter(child.front) || isAdapter(child.back))))
        p.failAtChild(children[0], "cannot nest a bumpmap or normalmap in another one");
    return id;
}

/// Mitsuba's PerturbedBSDF flags (bumpmap and normalmap).
void readPerturbedFlags(const Params& p, Bsdf& b) {
    b.flipInvalidNormals = p.getBool("flip_invalid_normals", true);
    b.shadowTerminator = p.getBool("use_shadowing_function", true);
}

}  // namespace

uint32_t buildTexture(BuildContext& ctx, int object) {
    ctx.used.insert(object);
    const ObjectEntity& e = ctx.desc.objects[size_t(object)];
    if (auto it = ctx.textureIndex.find(object); it != ctx.textureIndex.end()) {
        if (it->second == kNoTexture)  // still being built: a checkerboard that nests itself
            throw Error(e.where.file, e.where.line,
                        e.describe() + " refers to itself (reference cycle)");
        return it->second;
    }
    if (e.category != "texture")
        throw Error(e.where.file, e.where.line, e.describe() + " is used where a texture is expected");
    ctx.textureIndex[object] = kNoTexture;
    Params params(ctx.desc, object);
    const Texture t = kTexturePlugins.find(params)(ctx, params);
    params.finish(ctx.warnings);
    const uint32_t index = uint32_t(ctx.scene.textures.size());
    ctx.scene.textures.push_back(t);
    ctx.textureIndex[object] = index;
    return index;
}

int findTextureChild(const Params& p, const std::string& name) {
    for (const ChildRef& c : p.object().children)
        if (c.name == name && p.description().objects[size_t(c.object)].category == "texture")
            return c.object;
    return -1;
}

bool hasParam(const Params& p, const std::string& name) {
    return p.has(name) || findTextureChild(p, name) >= 0;
}

Spectrum readSpectrumParam(BuildContext& ctx, Params& p, const std::string& name, Spectrum def,
                           Bsdf& b, BsdfParam param) {
    const int child = findTextureChild(p, name);
    if (child < 0) return p.getSpectrum(name, def);
    uint32_t index = 0;
    const Texture& t = textureFor(ctx, p, name, child, index);
    if (t.type == TextureType::Constant) return t.value;
    addTexture(p, b, param, index);
    return Spectrum(t.mean);
}

Float readFloatParam(BuildContext& ctx, Params& p, const std::string& name, Float def, Bsdf& b,
                     BsdfParam param) {
    const int child = findTextureChild(p, name);
    if (child < 0) return p.getFloat(name, def);
    uint32_t index = 0;
    const Texture& t = textureFor(ctx, p, name, child, index);
    if (t.type == TextureType::Constant) {
        if (isThreeChannelConstant(ctx.desc, child))
            p.failAtChild(child, "a rawconstant with a <vector> value has three channels and cannot give the "
                                 "float parameter '" + name + "' (Mitsuba refuses it too)");
        return t.value.r;
    }
    addTexture(p, b, param, index);
    return t.mean;
}

void checkTextureChildren(BuildContext& ctx, const Params& p) {
    for (const ChildRef& c : p.object().children) {
        const ObjectEntity& child = ctx.desc.objects[size_t(c.object)];
        if (child.category == "texture" && !ctx.textureIndex.count(c.object))
            throw Error(c.where.file, c.where.line,
                        p.object().describe() + ": texture '" + c.name +
                            "' is not a textured parameter of this plugin");
    }
}

Bsdf buildBumpMap(BuildContext& ctx, Params& p) {
    Bsdf b;
    b.type = BsdfType::BumpMap;
    const std::vector<int> textures = p.takeChildren("texture");
    if (textures.size() != 1)
        p.fail("needs exactly one nested texture (the height field), got " +
               std::to_string(textures.size()));
    b.frameTexture = buildTexture(ctx, textures[0]);
    if (ctx.scene.textures[b.frameTexture].type != TextureType::Bitmap)
        p.failAtChild(textures[0], "the height field must be a bitmap (its gradient is needed)");
    b.bumpScale = p.getFloat("scale", 1.0f);
    readPerturbedFlags(p, b);
    b.front = adapterChild(ctx, p);
    return b;
}

Bsdf buildNormalMap(BuildContext& ctx, Params& p) {
    Bsdf b;
    b.type = BsdfType::NormalMap;
    const int texture = findTextureChild(p, "normalmap");
    if (texture < 0) p.fail("needs a nested texture named 'normalmap'");
    p.takeChildren("texture");
    b.frameTexture = buildTexture(ctx, texture);
    readPerturbedFlags(p, b);
    b.front = adapterChild(ctx, p);
    checkTextureChildren(ctx, p);
    return b;
}

}  // namespace caustica::mitsuba
