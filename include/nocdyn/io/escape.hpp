// Text from files (robot, trajectory and parameter names, messages quoting a file's bytes)
// written into another format goes through the one helper of that format, so that no name
// can end a string, open a key, start a comment, close a CDATA section or drive a terminal.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>
#include "nocdyn/text.hpp"

namespace nocdyn::io {

namespace detail {

/// The byte as \xHH (two hex digits).
inline std::string hexEscape(unsigned char c) { return text::format("\\x%02X", static_cast<unsigned>(c)); }

inline bool isControl(unsigned char c) { return c < 0x20 || c == 0x7F; }

}  // namespace detail

/// A YAML double-quoted scalar that reads back as exactly `text`: backslash and quote escaped,
/// control bytes as \n, \t, \r or \xHH (bytes from 0x80 up are kept: UTF-8 passes through).
inline std::string yamlQuoted(std::string_view text) {
    std::string out = "\"";
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (ch == '"' || ch == '\\') {
            out += '\\';
            out += ch;
        } else if (ch == '\n') {
            out += "\\n";
        } else if (ch == '\t') {
            out += "\\t";
        } else if (ch == '\r') {
            out += "\\r";
        } else if (detail::isControl(c)) {
            out += detail::hexEscape(c);
        } else {
            out += ch;
        }
    }
    return out + "\"";
}

/// Text shown as it is on one terminal line (or in a YAML or CSV comment): control bytes
/// (ESC, BEL, newline, ...) written as \xHH, so that text from a file cannot set a terminal's
/// title, move its cursor, or start a new line (a new key) in a file.
inline std::string terminalText(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (detail::isControl(c) && ch != '\t') {
            out += detail::hexEscape(c);
        } else {
            out += ch;
        }
    }
    return out;
}

/// Message text for the terminal: as terminalText, but a message's own line breaks (from
/// several-line errors) kept.
inline std::string terminalMessage(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (const char ch : text) {
        if (ch == '\n') {
            out += ch;
        } else {
            out += terminalText(std::string_view(&ch, 1));
        }
    }
    return out;
}

/// XML (SVG) and HTML character data and attribute values: & < > " ' as entities, control
/// bytes (not allowed in XML 1.0) as U+FFFD. "]]>" cannot occur: its '>' is an entity.
inline std::string xmlText(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (const char ch : text) {
        switch (ch) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&#39;";
                break;
            default:
                if (detail::isControl(static_cast<unsigned char>(ch)) && ch != '\t' && ch != '\n') {
                    out += "\xEF\xBF\xBD";
                } else {
                    out += ch;
                }
        }
    }
    return out;
}

/// Text in a Markdown table cell that shows as it is: the characters that end a cell (|), open
/// markup (* ` [ ] ~ \) or HTML (< > &) escaped, control bytes (and so line breaks, which would
/// end the row) as \xHH. A name cannot forge a row, a link or HTML. ('_' is kept: GitHub's
/// Markdown reads no emphasis inside a word, as in file names like elcentro_1940_ns.)
inline std::string markdownText(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (const char ch : text) {
        switch (ch) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '|':
            case '\\':
            case '`':
            case '*':
            case '[':
            case ']':
            case '~':
                out += '\\';
                out += ch;
                break;
            default:
                if (detail::isControl(static_cast<unsigned char>(ch))) {
                    out += "\\\\x";  // shown as \xHH: the backslash itself escaped
                    out += detail::hexEscape(static_cast<unsigned char>(ch)).substr(2);
                } else {
                    out += ch;
                }
        }
    }
    return out;
}

}  // namespace nocdyn::io
