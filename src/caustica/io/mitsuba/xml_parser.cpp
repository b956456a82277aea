#include "caustica/io/mitsuba/xml_parser.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>

#include "caustica/io/mesh/read_file.h"
#include "caustica/io/mesh/text_parse.h"
#include "caustica/io/mitsuba/xml_file.h"
#include "caustica/io/mitsuba/xml_properties.h"
#include "caustica/util/error.h"

namespace caustica::mitsuba {

namespace {

namespace fs = std::filesystem;

bool isObjectTag(std::string_view t) {
    return t == "shape" || t == "bsdf" || t == "emitter" || t == "sensor" || t == "film" ||
           t == "rfilter" || t == "sampler" || t == "integrator" || t == "texture";
}

/// Mitsuba elements caustica recognises but cannot honour yet: a clear refusal, not "unknown".
const char* unsupportedTagReason(std::string_view t) {
    if (t == "medium" || t == "phase" || t == "volume")
        return "participating media are not supported";
    return nullptr;
}

/// Deeper nesting is refused (it would only come from a broken or hostile file).
constexpr int kMaxDepth = 64;

/// Mitsuba 3's upgrade of pre-2.0 scenes: name="fooBar" -> name="foo_bar", <lookAt> -> <lookat>.
void upgradeLegacyNames(pugi::xml_node node, int depth = 0) {
    if (depth > kMaxDepth) return;  // parseObject reports the excessive nesting
    for (pugi::xml_node n : node.children()) {
        if (n.type() != pugi::node_element) continue;
        if (std::string_view(n.name()) == "lookAt") n.set_name("lookat");
        pugi::xml_attribute a = n.attribute("name");
        if (!a.empty() && std::string_view(n.name()) != "default") {
            std::string out = a.value();
            for (size_t i = 0; i + 1 < out.size(); ++i) {
                if (std::islower(static_cast<unsigned char>(out[i])) &&
                    std::isupper(static_cast<unsigned char>(out[i + 1]))) {
                    out.insert(out.begin() + std::ptrdiff_t(i) + 1, '_');
                    for (i += 2; i < out.size() && std::isupper(static_cast<unsigned char>(out[i]));
                         ++i)
                        out[i] = char(std::tolower(static_cast<unsigned char>(out[i])));
                }
            }
            if (out == "diffuse_reflectance") out = "reflectance";
            a.set_value(out.c_str());
        }
        upgradeLegacyNames(n, depth + 1);
    }
}

/// A path's identity for cycle detection (falls back to the path itself if it cannot be resolved).
std::string canonicalKey(const fs::path& path) {
    std::error_code ec;
    fs::path p = fs::weakly_canonical(path, ec);
    return ec ? path.lexically_normal().string() : p.string();
}

class Parser {
public:
    explicit Parser(Defines& defines) : defines_(defines) {}

    SceneDescription run(const std::string& path) {
        desc_.file = path;
        includeStack_.push_back({canonicalKey(path), fs::path(path).lexically_normal().string()});
        parseFile(path, nullptr, {});
        resolveReferences();
        return std::move(desc_);
    }

private:
    void parseFile(const std::string& path, const XmlFile* includer, pugi::xml_node includeNode) {
        std::string text;
        try {
            text = meshio::readWholeFile(path, "scene file");
        } catch (const Error& e) {
            if (includer) includer->fail(includeNode, e.what());
            throw;
        }
        desc_.files.push_back(path);
        auto file = std::make_unique<XmlFile>(path, std::move(text), defines_);
        pugi::xml_document doc;
        pugi::xml_parse_result r = doc.load_buffer(file->text().data(), file->text().size(),
                                                   pugi::parse_default, pugi::encoding_utf8);
        if (!r)
            throw Error(path, file->lineOf(r.offset),
                        std::string("XML syntax error: ") + r.description());
        pugi::xml_node root = doc.document_element();
        if (!root) throw Error(path, 0, "the file has no XML element");
        const bool isScene = std::string_view(root.name()) == "scene";
        if (isScene) {
            file->checkAttributes(root, {"version"});
            if (!includer && !file->has(root, "version"))
                file->fail(root, "<scene> needs a 'version' attribute (e.g. version=\"3.0.0\")");
            if (file->has(root, "version")) checkVersion(*file, root);
            for (pugi::xml_node child : root.children()) parseSceneChild(*file, child);
        } else if (includer) {
            parseSceneChild(*file, root);  // an included file holding a single object
        } else {
            file->fail(root,
                       "the root element must be <scene>, not <" + std::string(root.name()) + ">");
        }
    }

    void checkVersion(const XmlFile& f, pugi::xml_node root) {
        std::string v = f.attribute(root, "version");
        std::vector<std::string_view> parts = meshio::tokenize(v, ".");
        int64_t n[3];
        if (parts.size() != 3 || !meshio::parseInt64(parts[0], n[0]) ||
            !meshio::parseInt64(parts[1], n[1]) || !meshio::parseInt64(parts[2], n[2]))
            f.fail(root, "cannot read version " + meshio::quoteText(v) + " (expected e.g. 3.0.0)");
        if (n[0] < 2) upgradeLegacyNames(root);
    }

    void parseSceneChild(const XmlFile& f, pugi::xml_node node) {
        if (node.type() == pugi::node_pcdata || node.type() == pugi::node_cdata)
            f.fail(node.parent(), "unexpected text " + meshio::quoteText(node.value()));
        if (node.type() != pugi::node_element) return;
        const std::string tag = node.name();
        if (tag == "include") return parseInclude(f, node);
        if (tag == "path") return parsePath(f, node);
        if (tag == "alias") return parseAlias(f, node);
        if (tag == "default") {
            f.checkAttributes(node, {"name", "value"});
            std::string name = f.required(node, "name");
            if (!node.attribute("value")) f.fail(node, "<default> needs a 'value' attribute");
            defines_.values.try_emplace(name, f.attribute(node, "value"));
            return;
        }
        if (isPropertyTag(tag) || tag == "ref")
            f.fail(node, "<" + tag + "> must be inside an object, not directly in <scene>");
        int obj = parseObject(f, node);
        desc_.objects[size_t(obj)].topLevel = true;
        desc_.topLevel.push_back(obj);
    }

    void parseInclude(const XmlFile& f, pugi::xml_node node) {
        f.checkAttributes(node, {"filename"});
        fs::path target = f.required(node, "filename");
        if (target.is_relative())
            target = (fs::path(f.path()).parent_path() / target).lexically_normal();
        std::error_code ec;
        if (!fs::exists(target, ec))
            f.fail(node, "included file '" + target.string() + "' not found");
        std::string key = canonicalKey(target);
        auto again = std::find_if(includeStack_.begin(), includeStack_.end(),
                                  [&](const IncludedFile& i) { return i.key == key; });
        if (again != includeStack_.end()) f.fail(node, "include cycle: " + cycleText(again));
        includeStack_.push_back({key, target.string()});
        parseFile(target.string(), &f, node);
        includeStack_.pop_back();
    }

    /// A file being read (the scene, or an include inside it): its identity and its path.
    struct IncludedFile {
        std::string key, path;
    };

    /// "a.xml -> b.xml -> a.xml": the files from `first` on (the cycle), named relative to
    /// first's folder when they are inside it.
    std::string cycleText(std::vector<IncludedFile>::const_iterator first) const {
        const fs::path folder = fs::path(first->path).parent_path();
        auto name = [&](const std::string& path) {
            const fs::path relative = fs::path(path).lexically_relative(folder);
            return relative.empty() || *relative.begin() == ".." ? path : relative.string();
        };
        std::string text;
        for (auto it = first; it != includeStack_.end(); ++it) text += name(it->path) + " -> ";
        return text + name(first->path);
    }

    /// <path value="dir"/>: a folder searched for relative file names, relative to this file.
    void parsePath(const XmlFile& f, pugi::xml_node node) {
        f.checkAttributes(node, {"value"});
        fs::path dir = f.required(node, "value");
        if (dir.is_relative()) dir = fs::path(f.path()).parent_path() / dir;
        std::error_code ec;
        if (!fs::is_directory(dir, ec))
            f.fail(node, "<path>: folder '" + dir.lexically_normal().string() + "' not found");
        desc_.searchPaths.insert(desc_.searchPaths.begin(), dir.lexically_normal().string());
    }

    /// <alias id="existing" as="other"/>: `other` names the same object. As in Mitsuba, the
    /// object must be declared before the alias and `other` must be a new id.
    void parseAlias(const XmlFile& f, pugi::xml_node node) {
        f.checkAttributes(node, {"id", "as"});
        const std::string id = f.required(node, "id"), as = f.required(node, "as");
        auto it = desc_.ids.find(id);
        if (it == desc_.ids.end())
            f.fail(node, "<alias>: no object with id '" + id + "' is declared before it");
        if (desc_.ids.count(as)) f.fail(node, "<alias>: id '" + as + "' is already used");
        desc_.ids.emplace(as, it->second);
    }

    int parseObject(const XmlFile& f, pugi::xml_node node) {
        const std::string tag = node.name();
        if (depth_ >= kMaxDepth)
            f.fail(node, "objects nested more than " + std::to_string(kMaxDepth) + " levels deep");
        if (const char* reason = unsupportedTagReason(tag))
            f.fail(node, "<" + tag + ">: " + reason);
        if (tag == "spectrum" && node.attribute("type"))
            f.fail(node, "spectrum plugins (<spectrum type=...>) are not supported yet");
        if (!isObjectTag(tag)) f.fail(node, "unknown element <" + tag + ">");
        f.checkAttributes(node, {"type", "id", "name"});
        ObjectEntity e;
        e.category = tag;
        e.type = f.required(node, "type");
        e.id = f.attribute(node, "id");
        e.where = f.where(node);
        if (f.has(node, "id") && e.id.empty()) f.fail(node, "empty 'id'");
        const int index = int(desc_.objects.size());
        desc_.objects.push_back(std::move(e));
        ++depth_;
        for (pugi::xml_node child : node.children()) parseObjectChild(f, child, index);
        --depth_;
        registerId(f, node, index);
        return index;
    }

    void parseObjectChild(const XmlFile& f, pugi::xml_node node, int parent) {
        if (node.type() == pugi::node_pcdata || node.type() == pugi::node_cdata)
            f.fail(node.parent(), "unexpected text " + meshio::quoteText(node.value()));
        if (node.type() != pugi::node_element) return;
        const std::string tag = node.name();
        if (tag == "ref") {
            f.checkAttributes(node, {"id", "name"});
            ChildRef c{f.attribute(node, "name"), f.required(node, "id"), -1, f.where(node)};
            desc_.objects[size_t(parent)].children.push_back(c);
        } else if (isPropertyTag(tag) && !(tag == "spectrum" && node.attribute("type"))) {
            Property p = parseProperty(f, node, desc_.objects[size_t(parent)].category);
            for (const Property& q : desc_.objects[size_t(parent)].properties)
                if (q.name == p.name)
                    f.fail(node, "parameter '" + p.name + "' is given twice (first at line " +
                                     std::to_string(q.where.line) + ")");
            desc_.objects[size_t(parent)].properties.push_back(std::move(p));
        } else if (tag == "alias") {
            parseAlias(f, node);
        } else if (tag == "include" || tag == "default" || tag == "path") {
            f.fail(node, "<" + tag + "> is supported only directly inside <scene>");
        } else {
            std::string name = f.attribute(node, "name");
            int child = parseObject(f, node);
            desc_.objects[size_t(parent)].children.push_back(
                {name, "", child, desc_.objects[size_t(child)].where});
        }
    }

    void registerId(const XmlFile& f, pugi::xml_node node, int index) {
        const std::string& id = desc_.objects[size_t(index)].id;
        if (id.empty()) return;
        auto [it, inserted] = desc_.ids.try_emplace(id, index);
        if (!inserted) {
            const SourceLocation& first = desc_.objects[size_t(it->second)].where;
            f.fail(node, "duplicate id '" + id + "' (first used at " + first.file + ":" +
                             std::to_string(first.line) + ")");
        }
    }

    void resolveReferences() {
        for (ObjectEntity& e : desc_.objects)
            for (ChildRef& c : e.children) {
                if (c.refId.empty()) continue;
                auto it = desc_.ids.find(c.refId);
                if (it == desc_.ids.end())
                    throw Error(c.where.file, c.where.line,
                                "<ref id=\"" + c.refId + "\">: no object has this id");
                c.object = it->second;
            }
    }

    Defines& defines_;
    SceneDescription desc_;
    std::vector<IncludedFile> includeStack_;  // the scene, then the includes being read
    int depth_ = 0;
};

}  // namespace

SceneDescription parseSceneXml(const std::string& path,
                               const std::map<std::string, std::string>& defines,
                               std::vector<std::string>& warnings) {
    Defines d;
    d.values = defines;
    for (const auto& kv : defines) d.fromCaller.insert(kv.first);
    SceneDescription desc = Parser(d).run(path);
    for (const std::string& name : d.fromCaller)
        if (!d.used.count(name))
            warnings.push_back(path + ": define '" + name + "' is never used by the scene");
    return desc;
}

}  // namespace caustica::mitsuba
