// The application layer names a bad value by its field (time_scale); the command line names it
// by its option (--time-scale).
#pragma once

#include <string>
#include <utility>

#include "app/options.hpp"
#include "nocdyn/error.hpp"

namespace nocdyn::cli {

/// job(), with an app::OptionError rethrown as nocdyn::Error "--field-name: message".
template <class Job>
auto namingOptions(Job&& job) {
    try {
        return std::forward<Job>(job)();
    } catch (const app::OptionError& e) {
        std::string name = e.field();
        for (char& c : name) c = c == '_' ? '-' : c;
        throw Error("--" + name + ": " + e.message());
    }
}

}  // namespace nocdyn::cli
