// xml_file.h — one Mitsuba XML file being parsed: turns pugixml offsets into line numbers, reads
// attributes with $name substitution, parses numbers, and throws caustica::Error naming the
// file and the element's line.
#pragma once

#include <pugixml.hpp>

#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "caustica/io/mitsuba/xml_entities.h"

namespace caustica::mitsuba {

/// Values for $name substitution: the caller's defines (-D name=value) win over <default>s.
struct Defines {
    std::map<std::string, std::string> values;
    std::set<std::string> fromCaller;  // names the caller gave (to report unused ones)
    std::set<std::string> used;        // names substituted at least once
};

class XmlFile {
public:
    XmlFile(std::string path, std::string text, Defines& defines);

    const std::string& path() const { return path_; }
    const std::string& text() const { return text_; }
    Defines& defines() const { return defines_; }

    /// 1-based line of a byte offset into the file.
    int lineOf(ptrdiff_t offset) const;
    int line(const pugi::xml_node& node) const { return lineOf(node.offset_debug()); }
    SourceLocation where(const pugi::xml_node& node) const { return {path_, line(node)}; }
    [[noreturn]] void fail(const pugi::xml_node& node, const std::string& reason) const;

    /// Refuses attributes not in `allowed` (Mitsuba does the same).
    void checkAttributes(const pugi::xml_node& node,
                         std::initializer_list<std::string_view> allowed) const;
    bool has(const pugi::xml_node& node, const char* name) const {
        return !node.attribute(name).empty();
    }
    /// The attribute's value after $name substitution ("" when absent).
    std::string attribute(const pugi::xml_node& node, const char* name) const;
    /// Like attribute(), but a missing or empty attribute is an error.
    std::string required(const pugi::xml_node& node, const char* name) const;

    /// A finite number, or an error naming `what` (e.g. "value of <float name=\"fov\">").
    double number(const pugi::xml_node& node, std::string_view text, const std::string& what) const;
    /// Numbers separated by commas and/or blanks; their count must be one of `counts`.
    std::vector<double> numbers(const pugi::xml_node& node, std::string_view text,
                                const std::string& what,
                                std::initializer_list<size_t> counts) const;

private:
    std::string substitute(const pugi::xml_node& node, const std::string& value) const;

    std::string path_;
    std::string text_;
    std::vector<size_t> lineStarts_;
    Defines& defines_;
};

}  // namespace caustica::mitsuba
