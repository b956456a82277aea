#include "caustica/io/mesh/ply_loader.h"

#include <bit>
#include <cstring>

#include "caustica/io/mesh/ply_reader.h"
#include "caustica/io/mesh/read_file.h"
#include "caustica/io/mesh/text_parse.h"
#include "caustica/util/error.h"

namespace caustica::meshio {

namespace {

/// Slot of a vertex property in the mesh: 0-2 position, 3-5 normal, 6-7 uv, -1 skipped.
std::vector<int> vertexSlots(const PlyElement& el, bool& hasNormals, bool& hasUVs) {
    auto find = [&](const char* name) -> int {
        for (size_t i = 0; i < el.properties.size(); ++i)
            if (el.properties[i].name == name && !el.properties[i].isList) return int(i);
        return -1;
    };
    std::vector<int> slots(el.properties.size(), -1);
    const char* xyz[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
        int i = find(xyz[k]);
        if (i < 0)
            throw Error("", el.line,
                        "element 'vertex' has no property '" + std::string(xyz[k]) + "'");
        slots[size_t(i)] = k;
    }
    int nx = find("nx"), ny = find("ny"), nz = find("nz");
    hasNormals = nx >= 0 && ny >= 0 && nz >= 0;
    if (hasNormals) slots[size_t(nx)] = 3, slots[size_t(ny)] = 4, slots[size_t(nz)] = 5;
    static const char* kUVNames[4][2] = {
        {"u", "v"}, {"texture_u", "texture_v"}, {"s", "t"}, {"texture_s", "texture_t"}};
    hasUVs = false;
    for (const auto& names : kUVNames) {
        int u = find(names[0]), v = find(names[1]);
        if (u >= 0 && v >= 0) {
            slots[size_t(u)] = 6, slots[size_t(v)] = 7;
            hasUVs = true;
            break;
        }
    }
    return slots;
}

int faceIndexProperty(const PlyElement& el) {
    for (size_t i = 0; i < el.properties.size(); ++i) {
        const PlyProperty& p = el.properties[i];
        if (p.isList && (p.name == "vertex_indices" || p.name == "vertex_index")) {
            if (!isIntegerType(p.type))
                throw Error("", el.line, "face property '" + p.name + "' must hold integers");
            return int(i);
        }
    }
    throw Error("", el.line, "element 'face' has no list property 'vertex_indices'");
}

template <class Reader>
void readBody(Reader& in, const PlyHeader& header, TriangleMesh& mesh) {
    const PlyElement* vertexEl = header.find("vertex");
    const uint64_t vertexCount = vertexEl ? vertexEl->count : 0;
    std::vector<uint32_t> poly;
    for (const PlyElement& el : header.elements) {
        const bool isVertex = &el == vertexEl;
        const bool isFace = el.name == "face" && &el == header.find("face");
        bool hasNormals = false, hasUVs = false;
        std::vector<int> slots;
        int indexProp = -1;
        if (isVertex) {
            slots = vertexSlots(el, hasNormals, hasUVs);
            size_t n = size_t(std::min<uint64_t>(el.count, in.remaining()));
            mesh.positions.reserve(n);
            if (hasNormals) mesh.normals.reserve(n);
            if (hasUVs) mesh.uvs.reserve(n);
        } else if (isFace) {
            indexProp = faceIndexProperty(el);
        }
        // Records without properties hold nothing (empty lines, or 0 bytes in a binary file, so
        // a header could promise 2^63 of them: found by fuzzing, a timeout at 2e9).
        if (el.properties.empty()) continue;
        for (uint64_t r = 0; r < el.count; ++r) {
            in.beginRecord(el.name, r);
            double v[8] = {0, 0, 0, 0, 0, 0, 0, 0};
            for (size_t pi = 0; pi < el.properties.size(); ++pi) {
                const PlyProperty& p = el.properties[pi];
                if (!p.isList) {
                    double x = in.scalar(p.type, p.name);
                    if (isVertex && slots[pi] >= 0) v[slots[pi]] = x;
                    continue;
                }
                uint64_t n = in.count(p.countType, p.name);
                if (int(pi) != indexProp) {
                    for (uint64_t k = 0; k < n; ++k) in.scalar(p.type, p.name);
                    continue;
                }
                if (n < 3)
                    in.fail("face " + std::to_string(r) + " has " + std::to_string(n) +
                            " vertices (at least 3 needed)");
                poly.clear();
                for (uint64_t k = 0; k < n; ++k) {
                    double idx = in.scalar(p.type, p.name);
                    if (idx < 0 || idx >= double(vertexCount))
                        in.fail("face " + std::to_string(r) + " references vertex " +
                                std::to_string(int64_t(idx)) + " but the file has " +
                                std::to_string(vertexCount) + " vertices");
                    poly.push_back(uint32_t(idx));
                }
                for (size_t k = 2; k < poly.size(); ++k)
                    mesh.triangles.push_back({poly[0], poly[k - 1], poly[k]});
            }
            in.endRecord();
            if (isVertex) {
                Vec3f p{Float(v[0]), Float(v[1]), Float(v[2])};
                if (!isFinite(p))
                    in.fail("vertex " + std::to_string(r) + " has a NaN or infinite position");
                mesh.positions.push_back(p);
                if (hasNormals) mesh.normals.emplace_back(Float(v[3]), Float(v[4]), Float(v[5]));
                if (hasUVs) mesh.uvs.emplace_back(Float(v[6]), Float(v[7]));
            }
        }
    }
    in.finish();
}

}  // namespace

TriangleMesh loadPly(const std::string& path) {
    const std::string data = readWholeFile(path, "mesh file");
    TriangleMesh mesh;
    try {
        PlyHeader header = parsePlyHeader(data);
        if (!header.find("vertex")) throw Error("", 0, "PLY file has no 'vertex' element");
        if (!header.find("face")) throw Error("", 0, "PLY file has no 'face' element");
        if (header.find("vertex")->count >= 0xffffffffull)
            throw Error("", header.find("vertex")->line, "too many vertices (limit 2^32 - 1)");
        if (header.format == PlyFormat::Ascii) {
            AsciiPlyReader in(data, header.dataOffset, header.dataLine);
            readBody(in, header, mesh);
        } else {
            bool swap = (header.format == PlyFormat::BinaryBigEndian) !=
                        (std::endian::native == std::endian::big);
            BinaryPlyReader in(data, header.dataOffset, swap);
            readBody(in, header, mesh);
        }
    } catch (const Error& e) {
        if (!e.file().empty()) throw;
        throw Error(path, e.line(), e.reason());  // reader errors carry no file name
    }
    validateMesh(mesh, path);
    return mesh;
}

}  // namespace caustica::meshio
