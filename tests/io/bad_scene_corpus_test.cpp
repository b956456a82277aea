// bad_scene_corpus_test.cpp — every malformed file in tests/io/data/bad is refused with one line
// naming the file, the line and the reason (mesh errors name the mesh file and its line too).
#include <filesystem>
#include <ostream>
#include <set>

#include "scene_test_util.h"

namespace caustica::test {
namespace {

const std::string kBad = CAUSTICA_SOURCE_DIR "/tests/io/data/bad/";

struct BadCase {
    const char* scene;      // file loaded, in tests/io/data/bad
    const char* errorFile;  // file the message must name (an included file for include errors)
    int line;               // line the message must name (0: the message names no line)
    const char* reason;
};

const BadCase kCases[] = {
    {"xml_syntax.xml", "xml_syntax.xml", 4, R"(XML syntax error)"},
    {"no_version.xml", "no_version.xml", 1, R"(<scene> needs a 'version' attribute)"},
    {"root_not_scene.xml", "root_not_scene.xml", 1, R"(the root element must be <scene>)"},
    {"unknown_tag.xml", "unknown_tag.xml", 5, R"(unknown element <colour>)"},
    {"unknown_plugin.xml", "unknown_plugin.xml", 5, R"(unsupported bsdf type 'hair')"},
    {"polarized_bsdf.xml", "polarized_bsdf.xml", 5, R"(polarised rendering is not supported)"},
    {"spectral_film.xml", "spectral_film.xml", 4, R"(spectral rendering is not supported)"},
    {"bad_float.xml", "bad_float.xml", 4, R"(cannot read '4o' as a finite number)"},
    {"nan_float.xml", "nan_float.xml", 5, R"(cannot read 'NaN' as a finite number)"},
    {"bad_integer.xml", "bad_integer.xml", 5, R"(cannot read '4.5' as an integer)"},
    {"bad_boolean.xml", "bad_boolean.xml", 5, R"(must be 'true' or 'false')"},
    {"missing_value.xml", "missing_value.xml", 5, R"(<float> needs a 'value' attribute)"},
    {"missing_type.xml", "missing_type.xml", 4, R"(<shape> needs a 'type' attribute)"},
    {"unexpected_attribute.xml", "unexpected_attribute.xml", 5,
     R"(unexpected attribute 'unit' in <float>)"},
    {"wrong_property_type.xml", "wrong_property_type.xml", 5,
     R"(parameter 'radius' must be a <float>, not <string>)"},
    {"duplicate_parameter.xml", "duplicate_parameter.xml", 6,
     R"(parameter 'radius' is given twice (first at line)"},
    {"unknown_ref.xml", "unknown_ref.xml", 5, R"(<ref id="marble">: no object has this id)"},
    {"duplicate_id.xml", "duplicate_id.xml", 5, R"(duplicate id 'white')"},
    {"ref_wrong_category.xml", "ref_wrong_category.xml", 5, R"(cannot contain a <sensor>)"},
    {"undefined_parameter.xml", "undefined_parameter.xml", 5, R"(undefined parameter '$spp')"},
    {"include_missing.xml", "include_missing.xml", 4, R"(does_not_exist.xml' not found)"},
    {"include_cycle.xml", "parts/cycle_b.xml", 3, R"(include cycle)"},
    {"include_error.xml", "parts/bad_property.xml", 3, R"(cannot read 'one' as a finite number)"},
    {"nan_transform.xml", "nan_transform.xml", 6, R"(cannot read 'inf' as a finite number)"},
    {"singular_matrix.xml", "singular_matrix.xml", 6, R"(<matrix> is singular)"},
    {"wavelength_spectrum.xml", "wavelength_spectrum.xml", 6,
     R"(wavelengths must increase ('400' nm follows '700' nm))"},
    {"bad_distribution.xml", "bad_distribution.xml", 6,
     R"(must be 'beckmann' or 'ggx', not 'phong')"},
    {"conductor_unknown_material.xml", "conductor_unknown_material.xml", 6,
     R"(names an unknown conductor 'Unobtainium')"},
    {"medium.xml", "medium.xml", 4, R"(<medium>: participating media are not supported)"},
    {"texture.xml", "texture.xml", 6, R"(missing required parameter 'filename')"},
    {"texture_bad_wrap.xml", "texture_bad_wrap.xml", 6,
     R"(must be 'repeat', 'mirror' or 'clamp', not 'border')"},
    {"texture_corrupt.xml", "texture_corrupt.xml", 7, R"(corrupt_texture.png: corrupt)"},
    {"bumpmap_checkerboard.xml", "bumpmap_checkerboard.xml", 6,
     R"(the height field must be a bitmap)"},
    {"absurd_resolution.xml", "absurd_resolution.xml", 4, R"(absurd resolution 100000x576)"},
    {"crop.xml", "crop.xml", 4, R"(crop window 768x576 at (8, 0) does not fit in the 768x576 film)"},
    {"envmap_missing.xml", "envmap_missing.xml", 5, R"(no_such_sky.exr)"},
    {"spot_beam_wider.xml", "spot_beam_wider.xml", 6, R"(must be between 0 and cutoff_angle)"},
    {"spot_constant_texture.xml", "spot_constant_texture.xml", 5,
     R"('texture' must be spatially varying, e.g. a bitmap (as Mitsuba 3))"},
    {"checkerboard_cycle.xml", "checkerboard_cycle.xml", 4,
     R"(refers to itself (reference cycle))"},
    {"two_environments.xml", "two_environments.xml", 5,
     R"(a scene can have only one environment emitter (constant or envmap))"},
    {"thinlens_no_aperture.xml", "thinlens_no_aperture.xml", 3,
     R"(missing required parameter 'aperture_radius')"},
    {"ldrfilm_bad_tonemap.xml", "ldrfilm_bad_tonemap.xml", 5,
     R"('tonemap_method' must be gamma or reinhard, not 'aces')"},
    {"no_sensor.xml", "no_sensor.xml", 0, R"(scene has no sensor)"},
    {"area_at_top_level.xml", "area_at_top_level.xml", 4, R"(an area emitter must be nested in)"},
    {"point_in_shape.xml", "point_in_shape.xml", 5,
     R"(only area emitters can be attached to a shape)"},
    {"twosided_dielectric.xml", "twosided_dielectric.xml", 6, R"(cannot wrap a transmissive bsdf)"},
    {"twosided_mask.xml", "twosided_mask.xml", 6, R"(cannot wrap a bsdf that transmits light (mask))"},
    {"blendbsdf_no_weight.xml", "blendbsdf_no_weight.xml", 5, R"(needs a 'weight')"},
    {"roughplastic_anisotropic.xml", "roughplastic_anisotropic.xml", 5,
     R"(anisotropic roughness (alpha_u != alpha_v) is not supported by roughplastic)"},
    {"bad_fov_axis.xml", "bad_fov_axis.xml", 5, R"(must be x, y, diagonal, smaller or larger)"},
    {"sphere_ellipsoid.xml", "sphere_ellipsoid.xml", 4, R"(to_world must scale uniformly)"},
    {"negative_radiance.xml", "negative_radiance.xml", 6, R"(must be finite and non-negative)"},
    {"rgb_reflectance_above_one.xml", "rgb_reflectance_above_one.xml", 6,
     R"(parameter 'reflectance' must lie in [0, 1]: it is an <rgb> reflectance (Mitsuba refuses it too))"},
    {"checkerboard_rgb_above_one.xml", "checkerboard_rgb_above_one.xml", 7,
     R"(parameter 'color0' must lie in [0, 1]: it is an <rgb> reflectance)"},
    {"blendbsdf_rgb_weight_above_one.xml", "blendbsdf_rgb_weight_above_one.xml", 6,
     R"(parameter 'weight' must lie in [0, 1]: it is an <rgb> reflectance)"},
    {"rawconstant_rgb.xml", "rawconstant_rgb.xml", 7,
     R"(must be a <float> or a <vector>, as Mitsuba's rawconstant requires)"},
    {"rawconstant_vector_for_float.xml", "rawconstant_vector_for_float.xml", 6,
     R"(has three channels and cannot give the float parameter 'alpha')"},
    {"stray_text.xml", "stray_text.xml", 4, R"(unexpected text)"},
    {"property_in_scene.xml", "property_in_scene.xml", 4, R"(<float> must be inside an object)"},
    {"missing_mesh.xml", "missing_mesh.xml", 5, R"(no_such_mesh.obj: cannot open mesh file)"},
    {"obj_bad_number.xml", "obj_bad_number.xml", 5, R"(bad_number.obj:4: bad number '0.5.5')"},
    {"obj_index_out_of_range.xml", "obj_index_out_of_range.xml", 5,
     R"(index_out_of_range.obj:6: vertex index 9 is out of range (the file has 4))"},
    {"obj_nan.xml", "obj_nan.xml", 5, R"(nan.obj:2: bad number 'nan')"},
    {"obj_empty.xml", "obj_empty.xml", 5, R"(empty.obj: OBJ file has no faces)"},
    {"obj_fuzz_texcoord_index.xml", "obj_fuzz_texcoord_index.xml", 5,
     R"(texcoord_index_behind_comment.obj: face 1, corner 4: texture coordinate index 1 is out)"},
    {"ply_truncated.xml", "ply_truncated.xml", 5,
     R"(truncated.ply:13: file ends before element 'face' 1)"},
    {"ply_bad_index.xml", "ply_bad_index.xml", 5,
     R"(bad_index.ply:13: face 0 references vertex 7 but the file has 3 vertices)"},
    {"ply_binary_truncated.xml", "ply_binary_truncated.xml", 5,
     R"(binary_truncated.ply: file ends inside element 'vertex' 2)"},
    {"ply_nan.xml", "ply_nan.xml", 5, R"(nan.ply: vertex 1 has a NaN or infinite position)"},
    {"serialized_bad_magic.xml", "serialized_bad_magic.xml", 5,
     R"(bad_magic.serialized: not a .serialized file (the header is not 0x041C))"},
    {"serialized_bad_version.xml", "serialized_bad_version.xml", 5,
     R"(bad_version.serialized: unsupported .serialized version 5 (3 and 4 are read))"},
    {"serialized_truncated.xml", "serialized_truncated.xml", 5,
     R"(truncated.serialized: file ends inside the compressed data of the vertex normals)"},
    {"serialized_corrupt.xml", "serialized_corrupt.xml", 5,
     R"(corrupt.serialized: corrupt compressed data (zlib:)"},
    {"serialized_index_out_of_range.xml", "serialized_index_out_of_range.xml", 5,
     R"(index_out_of_range.serialized: triangle 1 references vertex 7 but the mesh has 4)"},
    {"serialized_nan.xml", "serialized_nan.xml", 5,
     R"(nan.serialized: vertex 1 has a NaN or infinite position)"},
    {"serialized_bad_offset.xml", "serialized_bad_offset.xml", 5,
     R"(bad_offset.serialized: mesh 1 starts at byte 1099511627776, beyond the end of the file)"},
    {"alias_unknown.xml", "alias_unknown.xml", 4,
     R"(<alias>: no object with id 'white' is declared before it)"},
};

void PrintTo(const BadCase& c, std::ostream* os) {
    *os << c.scene;
}

class BadSceneCorpus : public testing::TestWithParam<BadCase> {};

TEST_P(BadSceneCorpus, IsRefusedWithFileLineAndReason) {
    const BadCase& c = GetParam();
    expectError([&] { loadScene(kBad + c.scene); }, c.errorFile, c.line, c.reason);
    if (c.line == 0) {
        try {
            loadScene(kBad + c.scene);
        } catch (const Error& e) {
            EXPECT_EQ(e.line(), 0) << e.what();
        }
    }
}

INSTANTIATE_TEST_SUITE_P(All, BadSceneCorpus, testing::ValuesIn(kCases),
                         [](const testing::TestParamInfo<BadCase>& info) {
                             std::string name = info.param.scene;
                             name = name.substr(0, name.find('.'));
                             for (char& ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });

TEST(BadSceneCorpus, EveryFileHasACase) {
    std::set<std::string> covered;
    for (const BadCase& c : kCases) covered.insert(c.scene);
    for (const auto& entry : std::filesystem::directory_iterator(kBad)) {
        if (entry.path().extension() == ".xml") {
            EXPECT_TRUE(covered.count(entry.path().filename().string()))
                << entry.path() << " has no entry in kCases";
        }
    }
}

}  // namespace
}  // namespace caustica::test
