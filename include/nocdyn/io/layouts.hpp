// The column layouts of every CSV table nocdyn writes (command line, Python, `reproduce`), in
// one registry: each column's name, unit and meaning. Writers take their header from here, and
// docs/output-formats.md is generated from it (a test compares the two). The pose is always in
// the order x, y, theta (likewise x_d, y_d, theta_d and e_x, e_y, e_theta).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace nocdyn::io {

/// Every CSV table the project writes.
enum class TableId {
    inverse_dynamics,  ///< nocdyn inverse-dynamics, reproduce's paper1.csv and paper2.csv
    reactions,         ///< the joint reactions appended by --reactions
    simulate,          ///< nocdyn simulate
    closed_loop,       ///< nocdyn control --output, reproduce's control_paper{1,2}.csv
    measurements,      ///< nocdyn control --log, reproduce's identification logs; read by identify
    held_out_forces,   ///< reproduce's identification KEY_forces.csv
    envelope,          ///< nocdyn envelope, reproduce's envelope.csv
    workspace,         ///< nocdyn workspace --output
    first_frequency,   ///< nocdyn workspace --frequency-map STEM: STEM.csv
    loads,             ///< nocdyn loads
    shake,             ///< nocdyn shake's shake.csv
    validation,        ///< nocdyn validate, reproduce's *_validation.csv
    design,            ///< nocdyn design's designs.csv
};

/// How a column of a layout expands into the names of a file.
enum class Repeat {
    once,       ///< one column, named as is
    actuator,   ///< one per actuator a = 1..n: "{a}" in the name replaced by a
    joint,      ///< one per limb i = 1..limbs and joint k = 1..3: "{i}" and "{k}" replaced; consecutive
                ///< joint columns are interleaved (all of joint k before joint k + 1)
    parameter,  ///< one per design parameter: the name "{parameter}" replaced by the parameter's
    metric,     ///< one per design metric: the name "{metric}" replaced by the metric's
};

struct Column {
    std::string_view name;     ///< e.g. "x", "tau{a}", "limb{i}_j{k}_fx"
    std::string_view unit;     ///< SI unit, "" for a count, a code or a word
    std::string_view meaning;  ///< one line
    Repeat repeat = Repeat::once;
    bool optional = false;  ///< written only in some runs (the layout's notes say when)
};

struct Layout {
    TableId id;
    std::string_view name;        ///< the heading in docs/output-formats.md
    std::string_view written_by;  ///< commands and files
    std::string_view notes;       ///< what a row is; when the optional columns appear
    std::vector<Column> columns;
};

/// What a layout's repeated columns expand to.
struct LayoutSizes {
    int actuators = 0;
    int limbs = 0;
    std::vector<std::string> parameters{};  ///< Repeat::parameter
    std::vector<std::string> metrics{};     ///< Repeat::metric
    bool optional = false;                  ///< include the optional columns
    /// The robot's task coordinates: 3 ([theta, x, y]) or 2 (a two-DOF robot, motion:
    /// translation, pose [x, y]: its tables have no column "theta").
    int task_dimension = 3;
};

/// Every layout, in the order of docs/output-formats.md.
[[nodiscard]] const std::vector<Layout>& layouts();

/// One layout.
[[nodiscard]] const Layout& layout(TableId id);

/// The id's name, as the enumerator is spelled ("closed_loop"): how Python names a layout.
[[nodiscard]] std::string_view tableKey(TableId id);

/// The id of a name of tableKey; throws nocdyn::Error for an unknown one.
[[nodiscard]] TableId tableId(std::string_view key);

/// The header of a file of layout `id`: the column names, repeated columns expanded.
[[nodiscard]] std::vector<std::string> columnNames(TableId id, const LayoutSizes& sizes = {});

/// The header in short, for help texts: "t,x,y,theta,u1..un,...", optional columns in brackets
/// ("t,u1..un,tau1..taun[,du1..dun,ddu1..ddun]").
[[nodiscard]] std::string columnList(TableId id);

/// docs/output-formats.md: every layout's columns with units and meanings (Markdown).
[[nodiscard]] std::string outputFormatsMarkdown();

}  // namespace nocdyn::io
