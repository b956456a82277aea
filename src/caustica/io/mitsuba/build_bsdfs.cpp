// build_bsdfs.cpp — Mitsuba 3 BSDF plugins -> caustica::Bsdf records.
//
// | plugin         | parameters (default)                                                      |
// |----------------|---------------------------------------------------------------------------|
// | diffuse        | reflectance (0.5)                                                         |
// | dielectric     | int_ior (bk7 = 1.5046), ext_ior (air = 1.000277): float or material name; |
// |                | specular_reflectance (1), specular_transmittance (1)                      |
// | conductor      | material ("none" = eta 0, k 1: a perfect mirror), eta, k,                  |
// |                | specular_reflectance (1)                                                  |
// | roughconductor | distribution (must be "ggx"; Mitsuba's default "beckmann" is refused),    |
// |                | alpha or alpha_u + alpha_v (0.1), sample_visible (true), material, eta, k, |
// |                | specular_reflectance (1)                                                  |
// | twosided       | one nested/referenced bsdf (both sides) or two (front, back)              |
#include <algorithm>
#include <cctype>

#include "caustica/io/mitsuba/build_context.h"
#include "caustica/io/mitsuba/plugin_table.h"

namespace caustica::mitsuba {

namespace {

/// Mitsuba 3's table of named indices of refraction (include/mitsuba/render/ior.h).
struct NamedIor {
    const char* name;
    Float value;
};
constexpr NamedIor kIorTable[] = {
    {"vacuum", 1.0f},      {"helium", 1.000036f},        {"hydrogen", 1.000132f},
    {"air", 1.000277f},    {"carbon dioxide", 1.00045f}, {"water", 1.3330f},
    {"acetone", 1.36f},    {"ethanol", 1.361f},          {"carbon tetrachloride", 1.461f},
    {"glycerol", 1.4729f}, {"benzene", 1.501f},          {"silicone oil", 1.52045f},
    {"bromine", 1.661f},   {"water ice", 1.31f},         {"fused quartz", 1.458f},
    {"pyrex", 1.470f},     {"acrylic glass", 1.49f},     {"polypropylene", 1.49f},
    {"bk7", 1.5046f},      {"sodium chloride", 1.544f},  {"amber", 1.55f},
    {"pet", 1.5750f},      {"diamond", 2.419f}};

/// An index of refraction given as a float or as one of Mitsuba's material names.
Float readIor(const Params& p, const std::string& name, Float def) {
    const Property* prop = p.find(name);
    if (!prop) return def;
    Float ior = 0;
    if (prop->type == PropertyType::String) {
        std::string key = prop->text;
        std::transform(key.begin(), key.end(), key.begin(),
                       [](unsigned char c) { return char(std::tolower(c)); });
        std::string known;
        for (const NamedIor& n : kIorTable) {
            if (key == n.name) return n.value;
            known += (known.empty() ? "" : ", ") + std::string(n.name);
        }
        p.fail(*prop, "names an unknown material '" + prop->text + "' (known: " + known + ")");
    }
    ior = p.getFloat(name);
    if (!(ior > 0)) p.fail(*prop, "must be positive");
    return ior;
}

/// Complex index of refraction of the conductors: eta/k, or material="none" (Mitsuba's default).
void readConductorIor(const Params& p, Bsdf& b) {
    std::string material = p.getString("material", "none");
    if (material != "none") {
        if (p.has("eta") || p.has("k"))
            p.fail(*p.find("material"),
                   "cannot be combined with 'eta'/'k' (give one or the other)");
        p.fail(*p.find("material"), "names measured conductor data ('" + material +
                                        "'), which is not supported yet; give 'eta' and 'k'");
    }
    b.eta = p.getSpectrum("eta", Spectrum(0.0f));
    b.k = p.getSpectrum("k", Spectrum(1.0f));
}

Bsdf diffuse(BuildContext&, Params& p) {
    Bsdf b;
    b.type = BsdfType::Diffuse;
    b.reflectance = p.getSpectrum("reflectance", Spectrum(0.5f));
    return b;
}

Bsdf dielectric(BuildContext&, Params& p) {
    Bsdf b;
    b.type = BsdfType::Dielectric;
    Float intIor = readIor(p, "int_ior", 1.5046f), extIor = readIor(p, "ext_ior", 1.000277f);
    b.etaRatio = intIor / extIor;
    b.reflectance = p.getSpectrum("specular_reflectance", Spectrum(1.0f));
    b.transmittance = p.getSpectrum("specular_transmittance", Spectrum(1.0f));
    return b;
}

Bsdf conductor(BuildContext&, Params& p) {
    Bsdf b;
    b.type = BsdfType::Conductor;
    readConductorIor(p, b);
    b.reflectance = p.getSpectrum("specular_reflectance", Spectrum(1.0f));
    return b;
}

Bsdf roughConductor(BuildContext& ctx, Params& p) {
    Bsdf b;
    b.type = BsdfType::RoughConductor;
    if (!p.has("distribution"))
        p.fail(
            "no 'distribution' means Beckmann in Mitsuba 3, which is not supported yet; add "
            "<string name=\"distribution\" value=\"ggx\"/>");
    std::string dist = p.getString("distribution");
    std::transform(dist.begin(), dist.end(), dist.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (dist == "beckmann")
        p.fail(*p.find("distribution"), "'beckmann' is not supported yet; use value=\"ggx\"");
    if (dist != "ggx")
        p.fail(*p.find("distribution"), "must be 'ggx' or 'beckmann', not '" + dist + "'");
    if (p.has("alpha")) {
        if (p.has("alpha_u") || p.has("alpha_v"))
            p.fail("give either 'alpha' or 'alpha_u' and 'alpha_v', not both");
        b.alphaU = b.alphaV = p.getFloat("alpha");
    } else if (p.has("alpha_u") || p.has("alpha_v")) {
        if (!p.has("alpha_u") || !p.has("alpha_v"))
            p.fail("'alpha_u' and 'alpha_v' must be given together");
        b.alphaU = p.getFloat("alpha_u");
        b.alphaV = p.getFloat("alpha_v");
    }
    if (b.alphaU < 0 || b.alphaV < 0) p.fail("roughness (alpha) must not be negative");
    if (b.alphaU < 1e-4f || b.alphaV < 1e-4f) {
        const SourceLocation& w = p.object().where;
        ctx.warnings.push_back(w.file + ":" + std::to_string(w.line) + ": " +
                               p.object().describe() +
                               ": alpha below 1e-4 is clamped to 1e-4 (use conductor for a "
                               "smooth metal)");
        b.alphaU = std::max(b.alphaU, 1e-4f);
        b.alphaV = std::max(b.alphaV, 1e-4f);
    }
    p.getBool("sample_visible", true);  // only changes the variance, never the expected image
    readConductorIor(p, b);
    b.reflectance = p.getSpectrum("specular_reflectance", Spectrum(1.0f));
    return b;
}

Bsdf twoSided(BuildContext& ctx, Params& p) {
    std::vector<int> children = p.takeChildren("bsdf");
    if (children.empty() || children.size() > 2)
        p.fail("needs one or two nested bsdfs, got " + std::to_string(children.size()));
    Bsdf b;
    b.type = BsdfType::TwoSided;
    uint32_t sides[2] = {0, 0};
    for (size_t i = 0; i < children.size(); ++i) {
        const ObjectEntity& child = ctx.desc.objects[size_t(children[i])];
        if (child.type == "twosided") p.failAtChild(children[i], "cannot wrap another twosided");
        if (child.type == "dielectric")
            p.failAtChild(children[i], "cannot wrap a transmissive bsdf (dielectric)");
        sides[i] = ctx.bsdf(children[i]);
    }
    b.front = sides[0];
    b.back = children.size() == 2 ? sides[1] : sides[0];
    return b;
}

using BsdfFn = Bsdf (*)(BuildContext&, Params&);
const PluginTable<BsdfFn> kBsdfPlugins{{{"conductor", conductor},
                                        {"dielectric", dielectric},
                                        {"diffuse", diffuse},
                                        {"roughconductor", roughConductor},
                                        {"twosided", twoSided}},
                                       {{"polarizer", "polarised rendering is not supported"},
                                        {"retarder", "polarised rendering is not supported"},
                                        {"pplastic", "polarised rendering is not supported"}}};

}  // namespace

Bsdf buildBsdfRecord(BuildContext& ctx, Params& params) {
    return kBsdfPlugins.find(params)(ctx, params);
}

}  // namespace caustica::mitsuba
