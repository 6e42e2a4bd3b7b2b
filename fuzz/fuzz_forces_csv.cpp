// libFuzzer harness of the CSV reader (the forces file of `nocdyn simulate`): any text either
// becomes a rectangular table of finite numbers with distinct column names and increasing
// line numbers, or is refused with nocdyn::Error. Anything else is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(bytes), size);
    nocdyn::io::Table table;
    try {
        table = nocdyn::io::parseCsv(text, "fuzz.csv");
    } catch (const nocdyn::Error&) {
        return 0;
    }
    if (table.columns.empty() || table.lines.size() != table.rows.size()) std::abort();
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
        if (table.column(table.columns[c]) != c) std::abort();  // names are distinct
    }
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        if (table.rows[r].size() != table.columns.size()) std::abort();
        if (r > 0 && !(table.lines[r] > table.lines[r - 1])) std::abort();
        for (const double value : table.rows[r]) {
            if (!std::isfinite(value)) std::abort();
        }
    }
    return 0;
}
