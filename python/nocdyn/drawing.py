"""A robot drawn as SVG (Robot._repr_svg_, Jupyter's picture of a robot): the base joints, the
limbs, the platform at a pose (default home) and the operation point C; actuated joints marked
(a filled square for a prismatic joint's slider with its rail, a filled disc for a revolute
one). The geometry is the library's (drawing.hpp), the same the animation page draws."""

from __future__ import annotations

import html

import numpy as np

_WIDTH, _HEIGHT, _MARGIN = 420, 420, 30


def robot_svg(robot, pose=None):
    """SVG text of the robot at pose [x, y, theta] ([x, y] for a two-DOF robot; default: home)."""
    n = robot.task_dimension
    pose = robot.home if pose is None else np.asarray(pose, dtype=float)
    if pose.shape != (n,):
        raise ValueError(f"pose: expected {n} values [{'x, y, theta' if n == 3 else 'x, y'}], got shape {pose.shape}")
    if n == 2:  # the tool point's x, y; theta is no coordinate of a two-DOF robot (0)
        pose = np.array([pose[0], pose[1], 0.0])
    d = robot._core._drawing([float(v) for v in pose])
    points = [d["C"]] + list(d["platform"])
    for limb in d["limbs"]:
        for joint in limb:
            points += [joint["position"], joint["rail_start"], joint["rail_end"]]
    xy = np.array(points, dtype=float)
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    span = max(float(np.max(hi - lo)), 1e-9)
    scale = min(_WIDTH, _HEIGHT) - 2 * _MARGIN
    centre = (lo + hi) / 2.0

    def at(p):  # metres -> pixels, y up
        x = _WIDTH / 2 + (p[0] - centre[0]) / span * scale
        y = _HEIGHT / 2 - (p[1] - centre[1]) / span * scale
        return f"{x:.2f},{y:.2f}"

    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{_WIDTH}" height="{_HEIGHT}" '
             f'viewBox="0 0 {_WIDTH} {_HEIGHT}" font-family="sans-serif" font-size="11">',
             f"<title>{html.escape(robot.name)}</title>",
             f'<rect width="{_WIDTH}" height="{_HEIGHT}" fill="white"/>']
    # rails of the prismatic joints (their stroke), under everything
    for limb in d["limbs"]:
        for joint in limb:
            if joint["type"] == "P":
                parts.append(f'<polyline points="{at(joint["rail_start"])} {at(joint["rail_end"])}" '
                             'stroke="#999" stroke-width="6" stroke-linecap="round" fill="none"/>')
    # links: joint 1 -> joint 2 -> joint 3 -> the platform
    for limb in d["limbs"]:
        chain = " ".join(at(joint["position"]) for joint in limb)
        parts.append(f'<polyline points="{chain}" stroke="#1f77b4" stroke-width="3" fill="none"/>')
    platform = " ".join(at(p) for p in d["platform"])
    parts.append(f'<polygon points="{platform}" fill="#ffbb78" fill-opacity="0.6" stroke="#d62728" '
                 'stroke-width="2"/>')
    for j, limb in enumerate(d["limbs"]):
        base = limb[0]["position"]
        bx, by = at(base).split(",")
        parts.append(f'<rect x="{float(bx) - 7:.2f}" y="{float(by) + 4:.2f}" width="14" height="4" fill="#333"/>')
        parts.append(f'<text x="{float(bx) + 8:.2f}" y="{float(by) + 16:.2f}">{j + 1}</text>')
        for joint in limb:
            x, y = (float(v) for v in at(joint["position"]).split(","))
            actuated = joint["actuator"] >= 0
            if joint["type"] == "P":
                fill = "#2ca02c" if actuated else "white"
                parts.append(f'<rect x="{x - 6:.2f}" y="{y - 6:.2f}" width="12" height="12" fill="{fill}" '
                             'stroke="black"/>')
            else:
                fill = "#2ca02c" if actuated else "white"
                parts.append(f'<circle cx="{x:.2f}" cy="{y:.2f}" r="{6 if actuated else 4}" fill="{fill}" '
                             'stroke="black"/>')
            if actuated:
                parts.append(f'<text x="{x + 8:.2f}" y="{y - 8:.2f}" fill="#2ca02c">u{joint["actuator"] + 1}</text>')
    cx, cy = (float(v) for v in at(d["C"]).split(","))
    parts.append(f'<circle cx="{cx:.2f}" cy="{cy:.2f}" r="3" fill="#d62728"/>')
    parts.append(f'<text x="{cx + 5:.2f}" y="{cy - 5:.2f}" fill="#d62728">C</text>')
    parts.append(f'<text x="8" y="{_HEIGHT - 8}">{html.escape(robot.name)}: {robot.limbs} limbs, '
                 f'{robot.actuators} actuators (green: actuated)</text>')
    parts.append("</svg>")
    return "\n".join(parts)
