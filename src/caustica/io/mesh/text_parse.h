// text_parse.h — strict number parsing for the text formats io/ reads (XML attributes, OBJ, PLY).
// A token is accepted only if all of it is a number; NaN and infinities are refused.
#pragma once

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace caustica::meshio {

/// `s` without its leading and trailing blanks.
inline std::string_view trimBlanks(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

/// Parses all of `s` (surrounding blanks and one leading '+' allowed) as a T with
/// std::from_chars; a floating-point T must also be finite.
template <class T>
inline bool parseWholeNumber(std::string_view s, T& out) {
    s = trimBlanks(s);
    if (s.size() > 1 && s.front() == '+' && s[1] != '-') s.remove_prefix(1);
    if (s.empty()) return false;
    T v = 0;
    auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || ptr != s.data() + s.size()) return false;
    if constexpr (std::is_floating_point_v<T>) {
        if (!std::isfinite(v)) return false;
    }
    out = v;
    return true;
}

/// Parses all of `s` (surrounding blanks allowed) as a finite double.
inline bool parseDouble(std::string_view s, double& out) {
    return parseWholeNumber(s, out);
}

/// Parses all of `s` (surrounding blanks allowed) as a decimal 64-bit integer.
inline bool parseInt64(std::string_view s, int64_t& out) {
    return parseWholeNumber(s, out);
}

/// Splits `s` at any of the characters in `delims`, dropping empty pieces.
inline std::vector<std::string_view> tokenize(std::string_view s,
                                              std::string_view delims = ", \t\r\n") {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < s.size()) {
        size_t j = s.find_first_of(delims, i);
        if (j == std::string_view::npos) j = s.size();
        if (j > i) out.push_back(s.substr(i, j - i));
        i = j + 1;
    }
    return out;
}

/// Quotes text for a one-line error message: blanks trimmed, line breaks and tabs turned into
/// spaces, very long text shortened.
inline std::string quoteText(std::string_view s) {
    s = trimBlanks(s);
    std::string out(1, '\'');
    for (char c : s.substr(0, s.size() > 40 ? 37 : s.size()))
        out += std::isspace(static_cast<unsigned char>(c)) ? ' ' : c;
    out.append(s.size() > 40 ? "...'" : "'");
    return out;
}

}  // namespace caustica::meshio
