#include "caustica/io/mesh/obj_loader.h"

#include <tiny_obj_loader.h>

#include <sstream>
#include <unordered_map>

#include "caustica/io/mesh/read_file.h"
#include "caustica/io/mesh/text_parse.h"
#include "caustica/util/error.h"

namespace caustica::meshio {

namespace {

/// Checks one face corner "v", "v/vt", "v//vn" or "v/vt/vn" against the element counts seen so
/// far (negative indices are relative, as in tinyobjloader) and the final counts.
void checkCorner(const std::string& path, int line, std::string_view corner, const size_t seen[3],
                 const size_t total[3]) {
    static const char* kWhat[3] = {"vertex", "texture coordinate", "normal"};
    std::vector<std::string_view> parts;
    size_t start = 0;
    for (size_t i = 0; i <= corner.size(); ++i)
        if (i == corner.size() || corner[i] == '/') {
            parts.push_back(corner.substr(start, i - start));
            start = i + 1;
        }
    if (parts.size() > 3 || parts[0].empty())
        throw Error(path, line, "malformed face corner " + quoteText(corner));
    for (size_t k = 0; k < parts.size(); ++k) {
        if (parts[k].empty()) {
            if (k == 1 && parts.size() == 3) continue;  // v//vn
            throw Error(path, line, "malformed face corner " + quoteText(corner));
        }
        int64_t idx = 0;
        if (!parseInt64(parts[k], idx))
            throw Error(
                path, line,
                "bad index " + quoteText(parts[k]) + " in face corner " + quoteText(corner));
        int64_t resolved = idx > 0 ? idx - 1 : int64_t(seen[k]) + idx;
        if (idx == 0 || resolved < 0 || resolved >= int64_t(total[k]))
            throw Error(path, line,
                        std::string(kWhat[k]) + " index " + std::to_string(idx) +
                            " is out of range (the file has " + std::to_string(total[k]) + ")");
    }
}

/// tinyobjloader reads malformed numbers as 0 without a word and cannot say where a bad face is,
/// so every v/vt/vn/f line is checked here first, with its line number.
void validateObjText(const std::string& path, const std::string& text) {
    size_t total[3] = {0, 0, 0};  // v, vt, vn
    for (int pass = 0; pass < 2; ++pass) {
        size_t seen[3] = {0, 0, 0};
        int line = 0;
        size_t pos = 0;
        while (pos < text.size()) {
            size_t end = text.find('\n', pos);
            if (end == std::string::npos) end = text.size();
            std::string_view l(text.data() + pos, end - pos);
            pos = end + 1;
            ++line;
            if (size_t hash = l.find('#'); hash != std::string_view::npos) l = l.substr(0, hash);
            std::vector<std::string_view> tok = tokenize(l, " \t\r");
            if (tok.empty()) continue;
            int kind = tok[0] == "v" ? 0 : tok[0] == "vt" ? 1 : tok[0] == "vn" ? 2 : -1;
            if (kind >= 0) {
                ++seen[kind];
                if (pass == 1) continue;
                size_t n = tok.size() - 1;
                bool countOk = kind == 0   ? (n == 3 || n == 4 || n == 6 || n == 7)
                               : kind == 1 ? (n >= 1 && n <= 3)
                                           : n == 3;
                if (!countOk)
                    throw Error(
                        path, line,
                        "'" + std::string(tok[0]) + "' line has " + std::to_string(n) + " numbers");
                for (size_t i = 1; i < tok.size(); ++i) {
                    double v;
                    if (!parseDouble(tok[i], v))
                        throw Error(
                            path, line,
                            "bad number " + quoteText(tok[i]) + " (NaN, infinity or not a number)");
                }
            } else if (tok[0] == "f" && pass == 1) {
                if (tok.size() < 4)
                    throw Error(path, line,
                                "face has " + std::to_string(tok.size() - 1) +
                                    " corners (at least 3 needed)");
                if (tok.size() > 256)
                    throw Error(path, line,
                                "face has " + std::to_string(tok.size() - 1) +
                                    " corners (at most 255 supported)");
                for (size_t i = 1; i < tok.size(); ++i)
                    checkCorner(path, line, tok[i], seen, total);
            }
        }
        for (int k = 0; k < 3; ++k) total[k] = seen[k];
    }
}

/// tinyobjloader reads a tag line ("t name ints/reals/strings ...") into up to 3 x 8192 values
/// whatever the line holds, and copies all the tags read so far into every shape: a 60 KB file of
/// "t a 8192/8192/8192" lines takes over 2 GB. caustica uses no tags, so every line tinyobj would
/// read as one (its lines end at '\n' or '\r'; leading blanks skipped; 't' then a blank) becomes a
/// comment. Line numbers do not change.
void commentOutTags(std::string& text) {
    bool lineStart = true;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\n' || c == '\r') {
            lineStart = true;
        } else if (lineStart && c != ' ' && c != '\t') {
            if (c == 't' && i + 1 < text.size() && (text[i + 1] == ' ' || text[i + 1] == '\t'))
                text[i] = '#';
            lineStart = false;
        }
    }
}

/// Checks every index tinyobjloader returned against the arrays it returned, before any is used.
/// validateObjText() reads the text its own way (it drops a '#' comment inside a line, tinyobj
/// does not, for one), so its checks cannot make the accesses safe; this one does. tinyobj keeps
/// no line numbers: the message names the face (counted from 1 in tinyobj's order) and corner.
/// Material and smoothing-group ids are not used (no MaterialReader), so they are not checked.
void checkParsedIndices(const std::string& path, const tinyobj::attrib_t& attrib,
                        const std::vector<tinyobj::shape_t>& shapes) {
    const size_t counts[3] = {attrib.vertices.size() / 3, attrib.texcoords.size() / 2,
                              attrib.normals.size() / 3};
    static const char* kWhat[3] = {"vertex", "texture coordinate", "normal"};
    size_t face = 0;
    for (const tinyobj::shape_t& s : shapes) {
        const std::string where = s.name.empty() ? "" : " (group " + quoteText(s.name) + ")";
        size_t offset = 0;
        for (unsigned char n : s.mesh.num_face_vertices) {
            ++face;
            // tinyobj stores a face's corner count in an unsigned char, so a longer face wraps.
            if (n < 3 || s.mesh.indices.size() - offset < n)
                throw Error(path, 0,
                            "face " + std::to_string(face) + where +
                                ": the parser returned an inconsistent corner count " +
                                std::to_string(n));
            for (size_t c = 0; c < n; ++c) {
                const tinyobj::index_t& idx = s.mesh.indices[offset + c];
                const int i[3] = {idx.vertex_index, idx.texcoord_index, idx.normal_index};
                for (int k = 0; k < 3; ++k) {
                    if (k > 0 && i[k] == -1) continue;  // no vt or vn in this corner
                    // tinyobj made the index 0-based (relative ones resolved); say it 1-based.
                    if (i[k] < 0 || size_t(i[k]) >= counts[k])
                        throw Error(path, 0,
                                    "face " + std::to_string(face) + where + ", corner " +
                                        std::to_string(c + 1) + ": " + kWhat[k] + " index " +
                                        std::to_string(int64_t(i[k]) + 1) +
                                        " is out of range (the file has " +
                                        std::to_string(counts[k]) + ")");
                }
            }
            offset += n;
        }
        if (offset != s.mesh.indices.size())
            throw Error(path, 0,
                        "the parser returned " + std::to_string(s.mesh.indices.size()) +
                            " face corners" + where + " but its faces use " +
                            std::to_string(offset));
    }
}

struct CornerKey {
    int v, vt, vn;
    bool operator==(const CornerKey& o) const { return v == o.v && vt == o.vt && vn == o.vn; }
};
struct CornerHash {
    size_t operator()(const CornerKey& k) const {
        return (size_t(uint32_t(k.v)) * 73856093u) ^ (size_t(uint32_t(k.vt)) * 19349663u) ^
               (size_t(uint32_t(k.vn)) * 83492791u);
    }
};

}  // namespace

TriangleMesh loadObj(const std::string& path, bool flipTexCoords) {
    std::string text = readWholeFile(path, "mesh file");
    commentOutTags(text);
    validateObjText(path, text);

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    std::istringstream stream(text);
    // No MaterialReader: mtllib lines are skipped. No triangulation: we fan like Mitsuba.
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &stream, nullptr, false,
                          false))
        throw Error(path, 0, "cannot parse OBJ: " + meshio::quoteText(err.empty() ? warn : err));
    checkParsedIndices(path, attrib, shapes);

    bool allNormals = true, anyUV = false;
    size_t faces = 0;
    for (const tinyobj::shape_t& s : shapes)
        for (const tinyobj::index_t& idx : s.mesh.indices) {
            allNormals &= idx.normal_index >= 0;
            anyUV |= idx.texcoord_index >= 0;
        }
    for (const tinyobj::shape_t& s : shapes) faces += s.mesh.num_face_vertices.size();
    if (faces == 0) throw Error(path, 0, "OBJ file has no faces");

    TriangleMesh mesh;
    std::unordered_map<CornerKey, uint32_t, CornerHash> corners;
    auto vertexOf = [&](const tinyobj::index_t& idx) -> uint32_t {
        CornerKey key{idx.vertex_index, anyUV ? idx.texcoord_index : -1,
                      allNormals ? idx.normal_index : -1};
        auto [it, inserted] = corners.try_emplace(key, uint32_t(mesh.positions.size()));
        if (!inserted) return it->second;
        const float* p = &attrib.vertices[3 * size_t(key.v)];
        mesh.positions.emplace_back(p[0], p[1], p[2]);
        if (allNormals) {
            const float* n = &attrib.normals[3 * size_t(key.vn)];
            mesh.normals.emplace_back(n[0], n[1], n[2]);
        }
        if (anyUV) {
            Vec2f uv(0, 0);
            if (key.vt >= 0) {
                const float* t = &attrib.texcoords[2 * size_t(key.vt)];
                uv = Vec2f(t[0], flipTexCoords ? 1 - t[1] : t[1]);
            }
            mesh.uvs.push_back(uv);
        }
        return it->second;
    };
    for (const tinyobj::shape_t& s : shapes) {
        size_t offset = 0;
        for (unsigned char count : s.mesh.num_face_vertices) {
            uint32_t first = vertexOf(s.mesh.indices[offset]);
            uint32_t prev = vertexOf(s.mesh.indices[offset + 1]);
            for (size_t k = 2; k < count; ++k) {
                uint32_t cur = vertexOf(s.mesh.indices[offset + k]);
                mesh.triangles.push_back({first, prev, cur});
                prev = cur;
            }
            offset += count;
        }
    }
    validateMesh(mesh, path);
    return mesh;
}

}  // namespace caustica::meshio
