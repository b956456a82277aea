#include "caustica/io/mitsuba/xml_file.h"

#include <algorithm>
#include <cctype>

#include "caustica/io/mesh/text_parse.h"
#include "caustica/util/error.h"

namespace caustica::mitsuba {

using meshio::quoteText;

XmlFile::XmlFile(std::string path, std::string text, Defines& defines)
    : path_(std::move(path)), text_(std::move(text)), defines_(defines) {
    lineStarts_.push_back(0);
    for (size_t i = 0; i < text_.size(); ++i)
        if (text_[i] == '\n') lineStarts_.push_back(i + 1);
}

int XmlFile::lineOf(ptrdiff_t offset) const {
    if (offset < 0) return 0;
    auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), size_t(offset));
    return int(it - lineStarts_.begin());
}

void XmlFile::fail(const pugi::xml_node& node, const std::string& reason) const {
    throw Error(path_, line(node), reason);
}

void XmlFile::checkAttributes(const pugi::xml_node& node,
                              std::initializer_list<std::string_view> allowed) const {
    for (const pugi::xml_attribute& a : node.attributes()) {
        if (std::find(allowed.begin(), allowed.end(), std::string_view(a.name())) == allowed.end())
            fail(node,
                 "unexpected attribute '" + std::string(a.name()) + "' in <" + node.name() + ">");
    }
}

std::string XmlFile::attribute(const pugi::xml_node& node, const char* name) const {
    pugi::xml_attribute a = node.attribute(name);
    return a.empty() ? std::string() : substitute(node, a.value());
}

std::string XmlFile::required(const pugi::xml_node& node, const char* name) const {
    if (node.attribute(name).empty())
        fail(node, std::string("<") + node.name() + "> needs a '" + name + "' attribute");
    std::string v = attribute(node, name);
    if (v.empty()) fail(node, std::string("<") + node.name() + ">: '" + name + "' is empty");
    return v;
}

std::string XmlFile::substitute(const pugi::xml_node& node, const std::string& value) const {
    if (value.find('$') == std::string::npos) return value;
    auto isStart = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; };
    auto isBody = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    std::string out;
    for (size_t i = 0; i < value.size(); ++i) {
        if (value[i] != '$') {
            out += value[i];
            continue;
        }
        if (i + 1 >= value.size() || !isStart(value[i + 1]))
            fail(node, "'$' not followed by a parameter name in " + quoteText(value));
        size_t j = i + 1;
        while (j < value.size() && isBody(value[j])) ++j;
        std::string name = value.substr(i + 1, j - i - 1);
        auto it = defines_.values.find(name);
        if (it == defines_.values.end())
            fail(node, "undefined parameter '$" + name + "' (add <default name=\"" + name +
                           "\" value=\"...\"/> or pass -D " + name + "=...)");
        defines_.used.insert(name);
        out += it->second;
        i = j - 1;
    }
    return out;
}

double XmlFile::number(const pugi::xml_node& node, std::string_view text,
                       const std::string& what) const {
    double v = 0;
    if (!meshio::parseDouble(text, v))
        fail(node, "cannot read " + quoteText(text) + " as a finite number (" + what + ")");
    return v;
}

std::vector<double> XmlFile::numbers(const pugi::xml_node& node, std::string_view text,
                                     const std::string& what,
                                     std::initializer_list<size_t> counts) const {
    std::vector<std::string_view> tok = meshio::tokenize(text);
    if (std::find(counts.begin(), counts.end(), tok.size()) == counts.end()) {
        std::string expected;
        for (size_t c : counts) expected += (expected.empty() ? "" : " or ") + std::to_string(c);
        fail(node, what + " needs " + expected + " numbers, got " + std::to_string(tok.size()) +
                       " in " + quoteText(text));
    }
    std::vector<double> out;
    for (std::string_view t : tok) out.push_back(number(node, t, what));
    return out;
}

}  // namespace caustica::mitsuba
