// The registry of CSV layouts (layouts.hpp).
#include "nocdyn/io/layouts.hpp"

#include <array>
#include <utility>

#include "nocdyn/error.hpp"

namespace nocdyn::io {

namespace {

constexpr std::string_view kActuatorUnit = "m or rad";  // prismatic or revolute actuator
constexpr std::string_view kForceUnit = "N or N m";

std::vector<Layout> makeLayouts() {
    using enum TableId;
    const Column t{"t", "s", "time"};
    const Column x{"x", "m", "platform point C, x"};
    const Column y{"y", "m", "platform point C, y"};
    const Column theta{"theta", "rad", "platform orientation"};
    const Column u{"u{a}", kActuatorUnit, "actuator a's displacement", Repeat::actuator};
    const Column du{"du{a}", "m/s or rad/s", "actuator a's rate", Repeat::actuator};
    const Column ddu{"ddu{a}", "m/s^2 or rad/s^2", "actuator a's acceleration", Repeat::actuator};
    const Column tau{"tau{a}", kForceUnit, "actuator a's force or torque", Repeat::actuator};
    const Column kinetic{"kinetic", "J", "kinetic energy of the mechanism"};
    return {
        {inverse_dynamics,
         "Inverse dynamics",
         "`nocdyn inverse-dynamics --output`; `nocdyn reproduce`'s `paper1.csv`, `paper2.csv`; Python "
         "`nocdyn.inverse_dynamics`",
         "One row per sample of the trajectory. With `--reactions` the columns of *Joint reactions* follow. A "
         "two-DOF robot's (motion: translation, pose [x, y]) table has no column theta.",
         {t, x, y, theta, u, du, ddu, tau, kinetic}},
        {reactions,
         "Joint reactions",
         "`nocdyn inverse-dynamics --reactions`, after the columns of *Inverse dynamics*",
         "The reaction of the inboard body on the outboard body at each joint, base frame, the joint's own effort "
         "and friction taken out (reactions.hpp): for limb i = 1..limbs and joint k = 1..3 in file order, in turn, "
         "its three columns.",
         {{"limb{i}_j{k}_fx", "N", "reaction force, x", Repeat::joint},
          {"limb{i}_j{k}_fy", "N", "reaction force, y", Repeat::joint},
          {"limb{i}_j{k}_m", "N m", "reaction couple about the outboard body's c.o.m. (P joint; 0 at an R joint)",
           Repeat::joint}}},
        {simulate,
         "Forward dynamics",
         "`nocdyn simulate --output`; Python `nocdyn.simulate`",
         "One row per output instant t0 + k / rate, and one at the end. A two-DOF robot's (motion: translation, "
         "pose [x, y]) table has no column theta.",
         {t, x, y, theta, u, du, tau, kinetic}},
        {closed_loop,
         "Closed-loop run",
         "`nocdyn control --output`; `nocdyn reproduce`'s `control_paper1.csv`, `control_paper2.csv`; Python "
         "`nocdyn.control`",
         "One row per controller tick. The errors are desired minus achieved. A two-DOF robot's (motion: "
         "translation, pose [x, y]) table has no column theta_d, theta or e_theta.",
         {t,
          {"x_d", "m", "desired x"},
          {"y_d", "m", "desired y"},
          {"theta_d", "rad", "desired theta"},
          x,
          y,
          theta,
          {"e_x", "m", "x_d - x"},
          {"e_y", "m", "y_d - y"},
          {"e_theta", "rad", "theta_d - theta"},
          u,
          {"u{a}_d", kActuatorUnit, "actuator a's desired displacement", Repeat::actuator},
          {"tau{a}", kForceUnit, "actuator a's commanded force or torque (after saturation)", Repeat::actuator}}},
        {measurements,
         "Measurements (identification log)",
         "`nocdyn control --log`; `nocdyn reproduce`'s `identification/KEY_log.csv`; read by `nocdyn identify`",
         "One row per sample, with the sensors' noise. `identify` reads the columns by name and ignores others; "
         "the rates are optional (without them `identify` differentiates u).",
         {t,
          {"u{a}", kActuatorUnit, "measured displacement of actuator a", Repeat::actuator},
          {"tau{a}", kForceUnit,
           "force or torque of actuator a at the sample's instant (measured); named tau{a}_held when it is the "
           "command held from this sample to the next (`control --log`), which `identify` then averages over "
           "the two holds around each sample",
           Repeat::actuator},
          {"du{a}", "m/s or rad/s", "actuator a's rate", Repeat::actuator, true},
          {"ddu{a}", "m/s^2 or rad/s^2", "actuator a's acceleration", Repeat::actuator, true}}},
        {held_out_forces,
         "Held-out forces",
         "`nocdyn reproduce`'s `identification/KEY_forces.csv`",
         "The identified model against the held-out samples (every 10th sample).",
         {t,
          {"tau{a}_measured", kForceUnit, "measured force or torque of actuator a", Repeat::actuator},
          {"tau{a}_predicted", kForceUnit, "predicted by the identified model", Repeat::actuator}}},
        {envelope,
         "Operating envelope",
         "`nocdyn envelope --output`; `nocdyn reproduce`'s `envelope.csv`; Python `nocdyn.envelope`",
         "One row per axis (x, y, theta; a spatial robot's x, y, z, roll, pitch, yaw, or x, y, z for motion "
         "translation) and frequency: the largest amplitude of a sinusoid along the axis about "
         "the home posture within every limit. A spatial robot has no `first_natural_frequency`. When the robot file "
         "declares compliance, the first natural "
         "frequency of the lumped model at home is written in `first_natural_frequency` (the same in every row; "
         "the column is absent otherwise), and the rows at or above the band's third bound, the lowest frequency "
         "where the axis' dynamic amplification (the damped lumped model's motion per unit of the rigid motion) "
         "leaves [1/A, A] (`--amplification` A, 1.1 by default), have the limit `resonance` (the rigid model's "
         "amplitude, not trustworthy there; no limb, joint or actuator).",
         {{"axis", "", "the axis moved: x, y or theta; x, y, z, roll, pitch or yaw (a word)"},
          {"frequency", "Hz", "frequency of the sinusoid"},
          {"amplitude", "m or rad", "largest amplitude (m for x, y and z, rad for the angles)"},
          {"limit", "", "the limit that binds: range, velocity, effort, workspace, none or resonance (a word)"},
          {"limb", "", "limb that reaches the limit first (1-based; 0: none)"},
          {"joint", "", "joint of that limb (1-based; 0: not joint-specific)"},
          {"actuator", "", "actuator at that joint (1-based; 0: a passive joint or none)"},
          {"kinematic_amplitude", "m or rad", "largest amplitude within the ranges and the workspace alone"},
          {"peak_effort_ratio", "", "largest |tau_a| / effort limit of actuator a over the period"},
          {"peak_u", kActuatorUnit, "largest |u_a| over the actuators and the period"},
          {"peak_tau", kForceUnit, "largest |tau_a| over the actuators and the period"},
          {"first_natural_frequency", "Hz", "first natural frequency of the lumped model at home", Repeat::once,
           true}}},
        {workspace,
         "Workspace grid",
         "`nocdyn workspace --output`; Python `nocdyn.workspace`",
         "One row per grid point at the given orientation.",
         {{"x", "m", "grid point, x"},
          {"y", "m", "grid point, y"},
          {"cell", "", "feasible, unreachable, range or singular (a word)"}}},
        {first_frequency,
         "First natural frequency over the workspace",
         "`nocdyn workspace --frequency-map STEM`: STEM.csv; Python `nocdyn.workspace(first_frequency=True)`",
         "One row per feasible grid point of the workspace grid, in its order.",
         {{"x", "m", "grid point, x"},
          {"y", "m", "grid point, y"},
          {"first_frequency", "Hz", "lowest natural frequency of the lumped model K v = w^2 M v at (x, y, theta)"}}},
        {loads,
         "Joint design loads",
         "`nocdyn loads --output`; Python `nocdyn.loads`",
         "One row per joint. `peak_force_frequency` is written with `--envelope` only. A two-DOF robot's table "
         "has no column peak_force_theta.",
         {{"limb", "", "limb (1-based)"},
          {"joint", "", "joint of the limb (1-based, file order)"},
          {"peak_force", "N", "largest magnitude of the joint's force"},
          {"peak_force_t", "s", "time of the largest force"},
          {"peak_force_x", "m", "pose x at the largest force"},
          {"peak_force_y", "m", "pose y at the largest force"},
          {"peak_force_theta", "rad", "pose theta at the largest force"},
          {"rms_force", "N", "RMS of the force's magnitude"},
          {"peak_moment", "N m", "largest magnitude of the joint's couple"},
          {"peak_moment_t", "s", "time of the largest couple"},
          {"peak_force_frequency", "Hz", "envelope motion of the largest force", Repeat::once, true}}},
        {shake,
         "Earthquake replay",
         "`nocdyn shake`'s `shake.csv`; Python `nocdyn.shake`",
         "One row per sample of the (scaled) record: the target, what the table achieved (the pose at the "
         "nearest controller tick), u and tau at the nearest controller tick. A two-DOF robot's (motion: "
         "translation, pose [x, y]) table has no column theta, alpha, alpha_achieved or theta_achieved.",
         {t,
          {"x", "m", "target x"},
          {"y", "m", "target y"},
          {"theta", "rad", "target theta"},
          {"ax", "m/s^2", "target acceleration, x"},
          {"ay", "m/s^2", "target acceleration, y"},
          {"alpha", "rad/s^2", "target angular acceleration"},
          {"ax_achieved", "m/s^2", "achieved acceleration, x"},
          {"ay_achieved", "m/s^2", "achieved acceleration, y"},
          {"alpha_achieved", "rad/s^2", "achieved angular acceleration"},
          {"x_achieved", "m", "achieved x (the plant's, at the nearest controller tick)"},
          {"y_achieved", "m", "achieved y"},
          {"theta_achieved", "rad", "achieved theta"},
          u,
          {"tau{a}", kForceUnit, "actuator a's commanded force or torque", Repeat::actuator}}},
        {validation,
         "Engine comparison",
         "`nocdyn validate --output`; `nocdyn reproduce`'s `*_validation.csv`; Python `nocdyn.validate`",
         "One row per sample: nocdyn's inverse dynamics against Simbody's and MuJoCo's. A spatial robot's "
         "comparison (`space: spatial`) has the columns `t,x,y,z[,roll,pitch,yaw],u1..un,tau1..taun,"
         "simbody_tau1..n,mujoco_tau1..n,simbody_dtau1..n,mujoco_dtau1..n` (no engine u columns: every engine "
         "is driven by the same pose); with `--engine simbody` or `--engine mujoco` only that engine's tau and "
         "dtau columns.",
         {t,
          u,
          tau,
          {"simbody_u{a}", kActuatorUnit, "Simbody's displacement of actuator a", Repeat::actuator},
          {"simbody_tau{a}", kForceUnit, "Simbody's force or torque of actuator a", Repeat::actuator},
          {"mujoco_u{a}", kActuatorUnit, "MuJoCo's displacement of actuator a", Repeat::actuator},
          {"mujoco_tau{a}", kForceUnit, "MuJoCo's force or torque of actuator a", Repeat::actuator},
          {"simbody_dtau{a}", kForceUnit, "simbody_tau{a} - tau{a}", Repeat::actuator},
          {"mujoco_dtau{a}", kForceUnit, "mujoco_tau{a} - tau{a}", Repeat::actuator}}},
        {design,
         "Design sweep",
         "`nocdyn design`'s `designs.csv` and `pareto.csv` (the Pareto front); Python "
         "`nocdyn.design`",
         "One row per design. A metric that could not be computed is empty.",
         {{"design", "", "number of the design, from 1"},
          {"{parameter}", "as the parameter", "value of each varied parameter (--vary)", Repeat::parameter},
          {"{metric}", "as the metric", "value of each metric (--metric)", Repeat::metric},
          {"feasible", "", "true or false"},
          {"reason", "", "why the design is infeasible (quoted text; empty when feasible)"}}},
    };
}

/// `pattern` with its first `key` replaced by `value` (built by appending: GCC 12's -Wrestrict
/// misfires on std::string::replace at -O3).
constexpr std::array<std::pair<TableId, std::string_view>, 13> kKeys{{
    {TableId::inverse_dynamics, "inverse_dynamics"},
    {TableId::reactions, "reactions"},
    {TableId::simulate, "simulate"},
    {TableId::closed_loop, "closed_loop"},
    {TableId::measurements, "measurements"},
    {TableId::held_out_forces, "held_out_forces"},
    {TableId::envelope, "envelope"},
    {TableId::workspace, "workspace"},
    {TableId::first_frequency, "first_frequency"},
    {TableId::loads, "loads"},
    {TableId::shake, "shake"},
    {TableId::validation, "validation"},
    {TableId::design, "design"},
}};

std::string replaced(std::string_view pattern, std::string_view key, std::string_view value) {
    const std::size_t at = pattern.find(key);
    if (at == std::string_view::npos) return std::string(pattern);
    std::string text(pattern.substr(0, at));
    text.append(value).append(pattern.substr(at + key.size()));
    return text;
}

std::string replaced(std::string_view pattern, std::string_view key, int value) {
    return replaced(pattern, key, std::to_string(value));
}

/// A column of the pose's theta: "theta", or one named after it ("theta_d", "e_theta",
/// "peak_force_theta"), which a two-DOF robot's tables leave out.
bool isThetaColumn(std::string_view name) {
    return name == "theta" || name.starts_with("theta_") || name.find("_theta") != std::string_view::npos;
}

std::string markdownCell(std::string_view text) {
    std::string out;
    for (const char c : text) {
        if (c == '|') out += '\\';
        out += c;
    }
    return out;
}

}  // namespace

const std::vector<Layout>& layouts() {
    static const std::vector<Layout> all = makeLayouts();
    return all;
}

const Layout& layout(TableId id) {
    for (const Layout& l : layouts()) {
        if (l.id == id) return l;
    }
    throw Error("no CSV layout with id " + std::to_string(static_cast<int>(id)));
}

std::string_view tableKey(TableId id) {
    for (const auto& [each, key] : kKeys) {
        if (each == id) return key;
    }
    throw Error("no CSV layout with id " + std::to_string(static_cast<int>(id)));
}

TableId tableId(std::string_view key) {
    std::string known;
    for (const auto& [id, each] : kKeys) {
        if (each == key) return id;
        known += (known.empty() ? "" : ", ") + std::string(each);
    }
    throw Error("no CSV layout named '" + std::string(key) + "' (known: " + known + ")");
}

std::vector<std::string> columnNames(TableId id, const LayoutSizes& sizes) {
    const std::vector<Column>& columns = layout(id).columns;
    std::vector<std::string> names;
    for (std::size_t c = 0; c < columns.size(); ++c) {
        const Column& column = columns[c];
        if (column.optional && !sizes.optional) continue;
        if (sizes.task_dimension == 2 && isThetaColumn(column.name)) continue;  // no theta: pose [x, y]
        switch (column.repeat) {
            case Repeat::once:
                names.emplace_back(column.name);
                break;
            case Repeat::actuator:
                for (int a = 1; a <= sizes.actuators; ++a) names.push_back(replaced(column.name, "{a}", a));
                break;
            case Repeat::joint: {
                // consecutive joint columns are interleaved: every column of joint k, then k + 1
                std::size_t end = c;
                while (end < columns.size() && columns[end].repeat == Repeat::joint) ++end;
                for (int i = 1; i <= sizes.limbs; ++i) {
                    for (int k = 1; k <= 3; ++k) {
                        for (std::size_t g = c; g < end; ++g)
                            names.push_back(replaced(replaced(columns[g].name, "{i}", i), "{k}", k));
                    }
                }
                c = end - 1;
                break;
            }
            case Repeat::parameter:
                names.insert(names.end(), sizes.parameters.begin(), sizes.parameters.end());
                break;
            case Repeat::metric:
                names.insert(names.end(), sizes.metrics.begin(), sizes.metrics.end());
                break;
        }
    }
    return names;
}

std::string columnList(TableId id) {
    const std::vector<Column>& columns = layout(id).columns;
    std::string text;
    bool in_optional = false;
    for (std::size_t c = 0; c < columns.size(); ++c) {
        const Column& column = columns[c];
        if (column.optional != in_optional) {
            text += column.optional ? "[" : "]";
            in_optional = column.optional;
        }
        if (c > 0) text += ",";
        switch (column.repeat) {
            case Repeat::once:
                text += column.name;
                break;
            case Repeat::actuator:
                text += replaced(column.name, "{a}", 1);
                text += "..";
                text += replaced(column.name, "{a}", "n");
                break;
            case Repeat::joint: {
                std::size_t end = c;
                while (end < columns.size() && columns[end].repeat == Repeat::joint) ++end;
                for (std::size_t g = c; g < end; ++g) {
                    if (g > c) text += ",";
                    text += replaced(replaced(columns[g].name, "{i}", 1), "{k}", 1);
                }
                text += " .. (per limb and joint)";
                c = end - 1;
                break;
            }
            case Repeat::parameter:
            case Repeat::metric:
                text += column.name;
                break;
        }
    }
    if (in_optional) text += "]";
    return text;
}

std::string outputFormatsMarkdown() {
    std::string text =
        "# Output formats\n\n"
        "<!-- Generated from the registry in src/io/layouts.cpp by `nocdyn --output-formats`; a test "
        "fails when this page and the registry differ. -->\n\n"
        "Every CSV table nocdyn writes, its columns in the order of the file. The files are plain CSV: one "
        "header line of column names, then one line per row of numbers (each the shortest decimal that reads "
        "back as the same double); a column that holds a category holds a word. Units are SI. The pose is always in "
        "the order x, y, theta.\n\n"
        "In the names, `{a}` is the actuator, 1..n in the robot file's order (`tau{a}` stands for "
        "`tau1,tau2,...,taun`, all of one quantity before the next); `{i}` is the limb and `{k}` the joint "
        "of the limb (1..3); \"m or rad\" and \"N or N m\" depend on whether the actuator is prismatic or "
        "revolute.\n";
    for (const Layout& l : layouts()) {
        text += "\n## " + std::string(l.name) + "\n\n";
        text += "Written by " + std::string(l.written_by) + ". " + std::string(l.notes) + "\n\n";
        text += "Header: `" + columnList(l.id) + "`\n\n";
        text += "| column | unit | meaning |\n| --- | --- | --- |\n";
        for (const Column& c : l.columns) {
            text += "| `" + std::string(c.name) + "`" + (c.optional ? " (optional)" : "") + " | " +
                    markdownCell(c.unit) + " | " + markdownCell(c.meaning) + " |\n";
        }
    }
    return text;
}

}  // namespace nocdyn::io
