// A name from a file (a robot's, a limb's) inside a message of the library: control bytes (ESC,
// BEL, newline, ...; not tab) written as \xHH, so that a name cannot drive a terminal or start a
// line of its own in an error. (io::terminalText is the same rule for the output layers.)
#pragma once

#include <string>
#include <string_view>

namespace nocdyn::text {

[[nodiscard]] inline std::string printable(std::string_view text) {
    constexpr char kHex[] = "0123456789ABCDEF";
    std::string out;
    out.reserve(text.size());
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if ((c < 0x20 || c == 0x7F) && ch != '\t') {
            out += "\\x";
            out += kHex[c >> 4];
            out += kHex[c & 0xF];
        } else {
            out += ch;
        }
    }
    return out;
}

}  // namespace nocdyn::text
