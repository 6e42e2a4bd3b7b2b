// PEER AT2 ground-motion records (see at2.hpp).
#include "nocdyn/io/at2.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <string_view>

#include "file_util.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/escape.hpp"

namespace nocdyn::io {

namespace {

// Plausible time steps of a record [s].
constexpr double kMinDt = 1e-6;
constexpr double kMaxDt = 1.0;
// Largest |acceleration| accepted [g].
constexpr double kMaxG = 100.0;

std::string at(const std::string& source, std::size_t line) { return source + ":" + std::to_string(line) + ": "; }

/// Splits on blanks (space, tab, CR); the pieces view `text`.
std::vector<std::string_view> words(std::string_view text) {
    std::vector<std::string_view> out;
    std::size_t k = 0;
    while (k < text.size()) {
        while (k < text.size() && (text[k] == ' ' || text[k] == '\t' || text[k] == '\r')) ++k;
        const std::size_t start = k;
        while (k < text.size() && text[k] != ' ' && text[k] != '\t' && text[k] != '\r') ++k;
        if (k > start) out.push_back(text.substr(start, k - start));
    }
    return out;
}

/// The numbers of one blank-free word as Fortran writes them: a D exponent (1.0D-03) read as E,
/// and values written without a blank between them (-0.1234E-02-0.5678E-03, fixed-width fields
/// filled to the edge) split where a sign follows anything but an exponent letter.
std::vector<std::string> values(std::string_view word) {
    std::vector<std::string> out(1);
    for (std::size_t i = 0; i < word.size(); ++i) {
        char c = word[i];
        if ((c == '+' || c == '-') && i > 0) {
            const char before = word[i - 1];
            if (before != 'e' && before != 'E' && before != 'd' && before != 'D') out.emplace_back();
        }
        const bool exponent = (c == 'd' || c == 'D') && i > 0 &&
                              (std::isdigit(static_cast<unsigned char>(word[i - 1])) != 0 || word[i - 1] == '.');
        if (exponent) c = 'E';
        out.back() += c;
    }
    return out;
}

std::string upper(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

struct Header {
    std::string npts, dt;  ///< the two numbers as written
};

/// The fourth line in one of its three forms; std::nullopt-like empty strings when unknown.
bool parseHeaderLine(std::string_view line, Header& header) {
    std::string text = upper(line);
    // "NPTS= 3000, DT= .0100 SEC" and "NPTS= 1451, dt= .02000": make '=' and ',' blanks
    if (text.find('=') != std::string::npos) {
        std::replace(text.begin(), text.end(), '=', ' ');
        std::replace(text.begin(), text.end(), ',', ' ');
        const std::vector<std::string_view> w = words(text);
        if ((w.size() == 4 || (w.size() == 5 && w[4] == "SEC")) && w[0] == "NPTS" && w[2] == "DT") {
            header = {std::string(w[1]), std::string(w[3])};
            return true;
        }
        return false;
    }
    // "3930 0.00500 NPTS, DT"
    std::replace(text.begin(), text.end(), ',', ' ');
    const std::vector<std::string_view> w = words(text);
    if (w.size() == 4 && w[2] == "NPTS" && w[3] == "DT") {
        header = {std::string(w[0]), std::string(w[1])};
        return true;
    }
    return false;
}

}  // namespace

double GroundMotionRecord::duration() const {
    return acceleration.empty() ? 0.0 : dt * static_cast<double>(acceleration.size() - 1);
}

GroundMotionRecord parseAt2(const std::string& text, const std::string& source) {
    std::string_view rest(text);
    detail::stripByteOrderMark(rest);
    std::size_t line_number = 0;
    // a line ends at LF, CR LF, CR CR LF (a CR LF file passed through another CR LF
    // conversion) or a lone CR (the old Macintosh files)
    const auto nextLine = [&](std::string_view& line) {
        if (rest.empty()) return false;
        const std::size_t end = rest.find_first_of("\r\n");
        line = rest.substr(0, end);
        if (end == std::string_view::npos) {
            rest = {};
        } else {
            std::size_t k = end;
            while (k < rest.size() && rest[k] == '\r') ++k;
            if (k < rest.size() && rest[k] == '\n') ++k;
            rest = rest.substr(k);
        }
        ++line_number;
        return true;
    };
    GroundMotionRecord record;
    record.source = source;
    std::string_view line;
    for (int k = 0; k < 4; ++k) {
        if (!nextLine(line)) {
            throw Error(at(source, line_number) + "AT2 header cut short: 4 header lines expected, found " +
                        std::to_string(line_number));
        }
        if (k < 2) {
            std::string& folded = k == 0 ? record.title : record.event;
            const std::vector<std::string_view> w = words(line);
            for (std::size_t i = 0; i < w.size(); ++i) {
                if (i > 0) folded += ' ';
                folded += w[i];
            }
        }
    }
    Header header;
    if (!parseHeaderLine(line, header)) {
        throw Error(at(source, 4) +
                    "expected 'NPTS= N, DT= STEP [SEC]' or 'N STEP NPTS, DT' (the number of points and the time step)");
    }
    const auto npts_value = detail::parseDecimal(header.npts);
    if (!npts_value || *npts_value < 1.0 || *npts_value > static_cast<double>(kMaxAt2Points) ||
        *npts_value != static_cast<double>(static_cast<std::size_t>(*npts_value))) {
        throw Error(at(source, 4) + "NPTS '" + header.npts + "' is not a whole number from 1 to " +
                    std::to_string(kMaxAt2Points));
    }
    const auto npts = static_cast<std::size_t>(*npts_value);
    const auto dt = detail::parseDecimal(header.dt);
    if (!dt || !(*dt >= kMinDt && *dt <= kMaxDt)) {
        throw Error(at(source, 4) + "DT '" + header.dt + "' is not a time step from 1e-06 to 1 s");
    }
    record.dt = *dt;
    record.acceleration.reserve(npts);
    std::size_t last_line = 0;  // the line of the NPTS-th value
    while (nextLine(line)) {
        for (const std::string_view glued : words(line)) {
            for (const std::string& word : values(glued)) {
                // a value beyond NPTS: the header or the data is wrong, and neither is cut
                // silently; only zeros filling the line of the last value (padding) are allowed
                if (record.acceleration.size() == npts) {
                    const auto padding = detail::parseDecimal(word);
                    if (line_number == last_line && padding && *padding == 0.0) continue;
                    throw Error(at(source, line_number) + "the data go on past NPTS = " + std::to_string(npts) +
                                " values (value " + std::to_string(npts + 1) + " is '" +
                                terminalText(std::string_view(word).substr(0, 32)) +
                                "'): the header's NPTS disagrees with the data");
                }
                const auto value = detail::parseDecimal(word);
                if (!value) {
                    // the word shown escaped: a NUL or control byte would cut or garble the message
                    const std::string shown = terminalText(std::string_view(word).substr(0, 32));
                    throw Error(at(source, line_number) + "value " + std::to_string(record.acceleration.size() + 1) +
                                " '" + shown + "' " + detail::numberProblem(shown));
                }
                if (!(std::abs(*value) <= kMaxG)) {
                    throw Error(at(source, line_number) + "value " + std::to_string(record.acceleration.size() + 1) +
                                " is " + terminalText(std::string_view(word).substr(0, 32)) + " g, beyond +-100 g");
                }
                record.acceleration.push_back(*value * kStandardGravity);
                if (record.acceleration.size() == npts) last_line = line_number;
            }
        }
    }
    if (record.acceleration.size() < npts) {
        throw Error(at(source, line_number) + "the record ends after " + std::to_string(record.acceleration.size()) +
                    " of the NPTS = " + std::to_string(npts) + " values");
    }
    return record;
}

GroundMotionRecord readAt2File(const std::string& path) {
    return parseAt2(detail::readRegularFile(path, "AT2 record", kMaxAt2Bytes), path);
}

}  // namespace nocdyn::io
