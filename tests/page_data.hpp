// Reading what the animation pages (render/animation*.html) embed, as their scripts do.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace nocdyn::test {

/// How many times `what` occurs in `text` (overlapping occurrences counted).
inline std::size_t occurrences(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

/// The page's embedded data, parsed as the page's script does.
inline nlohmann::json pageData(const std::string& page) {
    const std::string open = "<script type=\"application/json\" id=\"nocdyn-data\">";
    const std::size_t begin = page.find(open);
    EXPECT_NE(begin, std::string::npos);
    const std::size_t start = begin + open.size();
    return nlohmann::json::parse(page.substr(start, page.find("</script>", start) - start));
}

}  // namespace nocdyn::test
