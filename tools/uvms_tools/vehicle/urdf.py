# SPDX-License-Identifier: Apache-2.0
"""urdf: an arm described in URDF as the arm part of a scenario's vehicle description
([[arm.link]] in the general form of docs/MODEL.md §2 "General links", and the mount).

URDF places each joint at a fixed pose (origin xyz, rpy) on its parent link and turns it about
an axis; the models here turn joint k about the z axis of frame k−1 and place frame k by
    frame k = frame k−1 · Rz(θ_k) · T(t_k) · Rot(ρ_k)        (DH part α = a = d = 0).
The conversion (docs/SCENARIOS.md "Your arm from URDF"): A_k is a rotation with A_k·e_z = the
axis of movable joint k, O_k the joint's origin transform (with the fixed joints before it
composed in), C_k the child link frame of joint k, E the tip frame from C_N. Then
    frame B = root · O_1 · A_1,   frame k = C_k · O_{k+1} · A_{k+1}  (k < N),  frame N = C_N · E,
so that the fixed part of step k is P_k = A_kᵀ · O_{k+1} · A_{k+1} (P_N = A_Nᵀ · E): t_k its
translation, ρ_k its rotation vector. The joint angle is URDF's q (no offset). Body k (the
links moved by joint k and not by joint k+1, fixed joints merged) has its mass, CoM and
inertia tensor combined in C_k and re-expressed in frame k: G = A_k·R(P_k), c = Gᵀ·c_C,
I = Gᵀ·I_C·G, the CoM measured from joint k's point (the origin of C_k).

Errors name the element: a missing <inertial> on a moving link, a joint type the firmware
cannot run (prismatic, floating, planar), a <mimic> joint on the chain, more movable joints
than the firmware's 7, a branching chain without --tip, a malformed number.
"""
import math
import xml.etree.ElementTree as ET

import numpy as np

MAX_JOINTS = 7  # the firmware's UVMS_MAX_JOINTS
MOVABLE = ("revolute", "continuous")
UNSUPPORTED = ("prismatic", "floating", "planar")


class UrdfError(ValueError):
    """A URDF the models cannot run; the message names the element."""


# ---- small rigid-transform helpers (4×4 homogeneous) -----------------------------------------

def rot_rpy(r, p, y):
    """URDF's fixed-axis roll, pitch, yaw: R = Rz(y)·Ry(p)·Rx(r)."""
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def transform(R=None, t=None):
    T = np.eye(4)
    if R is not None:
        T[:3, :3] = R
    if t is not None:
        T[:3, 3] = t
    return T


def rotvec(R):
    """Rotation vector (unit axis × angle in [0, π]) of a rotation matrix, accurate at every
    angle: the angle from atan2(|w|/2, (tr − 1)/2), w the antisymmetric part; near π the axis
    from the largest column of the symmetric part, its sign from w."""
    w = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    s, c = 0.5 * np.linalg.norm(w), 0.5 * (np.trace(R) - 1.0)
    angle = math.atan2(s, c)
    if angle < 1e-15:
        return np.zeros(3)
    if c > 0.0:
        return w / (2.0 * s) * angle
    S = 0.5 * (R + R.T) - c * np.eye(3)  # = (1 − c)·e·eᵀ
    k = int(np.argmax(np.diag(S)))
    axis = S[:, k] / np.linalg.norm(S[:, k])
    if np.dot(axis, w) < 0.0:
        axis = -axis
    return axis * angle


def fold_z(axis):
    """A rotation A with A·e_z = axis (unit): the shortest turn of e_z onto the axis."""
    z = np.array([0.0, 0.0, 1.0])
    c = float(np.dot(z, axis))
    if c > 1.0 - 1e-15:
        return np.eye(3)
    if c < -1.0 + 1e-15:
        return np.diag([1.0, -1.0, -1.0])  # π about x
    k = np.cross(z, axis)
    s = np.linalg.norm(k)
    k = k / s
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + s * K + (1.0 - c) * (K @ K)


# ---- parsing ---------------------------------------------------------------------------------

def _floats(el, attr, n, what, default=None):
    text = el.get(attr) if el is not None else None
    if text is None:
        if default is not None:
            return np.array(default, dtype=float)
        raise UrdfError(f"{what}: missing attribute {attr!r}")
    try:
        vals = [float(x) for x in text.split()]
    except ValueError:
        raise UrdfError(f"{what}: {attr}={text!r} is not {n} numbers") from None
    if len(vals) != n or not all(math.isfinite(v) for v in vals):
        raise UrdfError(f"{what}: {attr}={text!r} is not {n} finite numbers")
    return np.array(vals)


def _origin(el, what):
    o = el.find("origin") if el is not None else None
    xyz = _floats(o, "xyz", 3, f"{what} <origin>", [0.0, 0.0, 0.0])
    rpy = _floats(o, "rpy", 3, f"{what} <origin>", [0.0, 0.0, 0.0])
    return transform(rot_rpy(*rpy), xyz)


def _inertial(link_el, name):
    """(mass, com in the link frame, 3×3 inertia about the CoM in the link frame) or None."""
    el = link_el.find("inertial")
    if el is None:
        return None
    what = f"link {name!r} <inertial>"
    m_el = el.find("mass")
    if m_el is None:
        raise UrdfError(f"{what}: no <mass>")
    mass = float(_floats(m_el, "value", 1, f"{what} <mass>")[0])
    if mass < 0:
        raise UrdfError(f"{what} <mass>: value {mass} is negative")
    T = _origin(el, what)
    i_el = el.find("inertia")
    if i_el is None:
        raise UrdfError(f"{what}: no <inertia>")
    f = {k: float(_floats(i_el, k, 1, f"{what} <inertia>")[0])
         for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
    I = np.array([[f["ixx"], f["ixy"], f["ixz"]], [f["ixy"], f["iyy"], f["iyz"]],
                  [f["ixz"], f["iyz"], f["izz"]]])
    R = T[:3, :3]
    return mass, T[:3, 3], R @ I @ R.T


def _cylinder(link_el):
    """The radius and length of the link's first <collision> cylinder, or None."""
    for col in link_el.findall("collision"):
        cyl = col.find("geometry/cylinder")
        if cyl is not None:
            return float(cyl.get("radius", "nan")), float(cyl.get("length", "nan"))
    return None


def parse(text, source="URDF"):
    """{links: {name: element}, joints: [dict]} of a URDF document."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError as e:
        raise UrdfError(f"{source}: not XML ({e})") from None
    if root.tag != "robot":
        raise UrdfError(f"{source}: the root element is <{root.tag}>, expected <robot>")
    links = {}
    for el in root.findall("link"):
        name = el.get("name")
        if not name:
            raise UrdfError(f"{source}: a <link> without a name")
        links[name] = el
    joints = []
    for el in root.findall("joint"):
        name = el.get("name") or "?"
        what = f"joint {name!r}"
        parent, child = el.find("parent"), el.find("child")
        if parent is None or child is None:
            raise UrdfError(f"{what}: needs <parent link=...> and <child link=...>")
        j = {"name": name, "type": el.get("type"), "parent": parent.get("link"),
             "child": child.get("link"), "origin": _origin(el, what), "el": el}
        for end in ("parent", "child"):
            if j[end] not in links:
                raise UrdfError(f"{what}: {end} link {j[end]!r} is not a <link> of the robot")
        joints.append(j)
    return {"links": links, "joints": joints, "source": source}


# ---- the chain -------------------------------------------------------------------------------

def chain(robot, tip=None):
    """The joints from the root link to the tip link, in order."""
    by_child = {}
    for j in robot["joints"]:
        if j["child"] in by_child:
            raise UrdfError(f"link {j['child']!r} is the child of two joints "
                            f"({by_child[j['child']]['name']!r}, {j['name']!r})")
        by_child[j["child"]] = j
    roots = [n for n in robot["links"] if n not in by_child]
    if len(roots) != 1:
        raise UrdfError(f"{robot['source']}: {len(roots)} root links ({', '.join(roots)}); "
                        "expected one tree")
    if tip is None:
        parents = {j["parent"] for j in robot["joints"]}
        leaves = [n for n in robot["links"] if n not in parents]
        if len(leaves) != 1:
            raise UrdfError(f"{robot['source']}: the tree branches ({len(leaves)} leaf links: "
                            f"{', '.join(sorted(leaves))}); name the arm's tip with --tip LINK")
        tip = leaves[0]
    if tip not in robot["links"]:
        raise UrdfError(f"--tip {tip!r}: no such <link>")
    out, at = [], tip
    while at in by_child:
        j = by_child[at]
        out.append(j)
        at = j["parent"]
    return out[::-1], roots[0], tip


def _check_joint(j):
    what = f"joint {j['name']!r}"
    if j["type"] in UNSUPPORTED:
        raise UrdfError(f"{what}: type {j['type']!r}: the firmware runs revolute joints only "
                        "(revolute, continuous; fixed joints are merged)")
    if j["type"] not in MOVABLE + ("fixed",):
        raise UrdfError(f"{what}: unknown type {j['type']!r}")
    if j["el"].find("mimic") is not None:
        raise UrdfError(f"{what}: a <mimic> joint: the firmware moves each joint on its own "
                        "(stop the chain before it with --tip)")


# ---- conversion ------------------------------------------------------------------------------

def _body(robot, names_T, joint_name):
    """Mass, CoM and inertia about the CoM, in the frame C of the body's first link, of the
    links `names_T` ([(name, T_C_link)]) merged (parallel-axis theorem)."""
    parts = []
    for name, T in names_T:
        inert = _inertial(robot["links"][name], name)
        if inert is None:
            continue
        m, c, I = inert
        R = T[:3, :3]
        parts.append((m, T[:3, :3] @ c + T[:3, 3], R @ I @ R.T))
    if not parts:
        raise UrdfError(f"link {names_T[0][0]!r} (moved by joint {joint_name!r}) has no "
                        "<inertial>: its mass and inertia are needed")
    M = sum(m for m, _, _ in parts)
    com = sum(m * c for m, c, _ in parts) / M if M > 0 else parts[0][1]
    I = np.zeros((3, 3))
    for m, c, Ic in parts:
        d = c - com
        I += Ic + m * (np.dot(d, d) * np.eye(3) - np.outer(d, d))
    return M, com, I


def _subtree(robot, start, T_start, stop):
    """[(link, transform from the start link's frame)] of the links rigidly carried by `start`:
    itself, and every link below it except past the joints in `stop` (the chain's movable
    joints). Joints off the chain are held at their zero angle; their names are returned too."""
    children = {}
    for j in robot["joints"]:
        children.setdefault(j["parent"], []).append(j)
    out, held, stack = [], [], [(start, T_start)]
    while stack:
        link, T = stack.pop()
        out.append((link, T))
        for j in children.get(link, []):
            if j["name"] in stop:
                continue
            if j["type"] != "fixed":
                held.append(j["name"])
            stack.append((j["child"], T @ j["origin"]))
    return out, held


def _clean(v, tol):
    """Rounding noise (|x| < tol) written as 0, so that e.g. a principal-axes tensor stays on
    the firmware's diagonal path."""
    v = np.array(v, dtype=float)
    v[np.abs(v) < tol] = 0.0
    return v


def _root_note(robot, root, stop, mount):
    """The mass that moves with the vehicle: the root and what is fixed to it."""
    parts, _ = _subtree(robot, root, np.eye(4), stop)
    names = [n for n, _ in parts if _inertial(robot["links"][n], n) is not None]
    if not names:
        return []
    M, com, _ = _body(robot, parts, "(none: fixed to the root)")
    com_v = mount[:3, :3] @ com + mount[:3, 3]
    return [f"links fixed to the vehicle ({', '.join(names)}): {M:g} kg with CoM at "
            f"({com_v[0]:.4g}, {com_v[1]:.4g}, {com_v[2]:.4g}) m in the vehicle frame; they "
            "move with the vehicle, so add their mass, inertia and volume to its description"]


def _added_mass_in_frame(values, G, child, i):
    """A side file's diagonal added mass, given in the URDF link's axes (kg ×3, kg·m² ×3),
    in the model's frame-i axes (G: frame i → link axes, as the inertia): Gᵀ·D·G per block,
    which must stay diagonal (the link's axes a permutation of frame i's, signs aside)."""
    out = []
    for block in (values[:3], values[3:]):
        D = G.T @ np.diag([float(x) for x in block]) @ G
        off = np.abs(D - np.diag(np.diag(D))).max()
        if off > 1e-9 * max(np.abs(D).max(), 1e-300):
            raise UrdfError(f"--hydro: [{child}] added_mass_kg is diagonal in {child}'s axes, "
                            f"which are turned against frame {i} (its joint axis on z) so that it "
                            f"is not diagonal there (off-diagonal {off:.3g}); give a link whose "
                            f"axes are frame {i}'s up to order and sign, or leave it to the "
                            f"shared coefficients")
        out += [float(x) for x in _clean(np.diag(D), 0.0)]
    return out


def convert(robot, tip=None, hydro=None, mount=None):
    """The arm of a parsed URDF in the models' form: {"base_offset_m", "base_rotvec_rad",
    "links": [dict of [[arm.link]] keys], "notes": [str]}. hydro: {link name: {"diameter_m",
    "drag_coeff", "added_mass_kg"}}; mount: the root link's pose in the vehicle frame (4×4), identity if None."""
    joints, root, tip = chain(robot, tip)
    for j in joints:
        _check_joint(j)
    movable = [k for k, j in enumerate(joints) if j["type"] in MOVABLE]
    if not movable:
        raise UrdfError(f"{robot['source']}: no revolute joint between {root!r} and {tip!r}")
    if len(movable) > MAX_JOINTS:
        raise UrdfError(f"{robot['source']}: {len(movable)} movable joints between {root!r} and "
                        f"{tip!r} (expected 1..{MAX_JOINTS}, the firmware's UVMS_MAX_JOINTS)")
    hydro = hydro or {}
    mount = np.eye(4) if mount is None else mount
    stop = {joints[k]["name"] for k in movable}
    notes = _root_note(robot, root, stop, mount)
    # O_k: the joint frame of movable joint k from the previous movable joint's child frame
    # (the root for k = 1), the chain's fixed joints before it composed in; E: the tip from C_N.
    O, axes, acc = [], [], np.eye(4)
    for j in joints:
        if j["type"] == "fixed":
            acc = acc @ j["origin"]
            continue
        O.append(acc @ j["origin"])
        ax_el = j["el"].find("axis")
        axis = _floats(ax_el, "xyz", 3, f"joint {j['name']!r} <axis>", [1.0, 0.0, 0.0])
        if not np.linalg.norm(axis) > 0:
            raise UrdfError(f"joint {j['name']!r} <axis>: xyz is zero")
        axes.append(axis / np.linalg.norm(axis))
        acc = np.eye(4)
    E = acc
    n = len(O)
    A = [transform(fold_z(a)) for a in axes]
    base = mount @ O[0] @ A[0]
    links = []
    for k in range(n):
        P = np.linalg.inv(A[k]) @ (O[k + 1] @ A[k + 1] if k + 1 < n else E)
        j = joints[movable[k]]
        parts, held = _subtree(robot, j["child"], np.eye(4), stop)
        if held:
            notes.append(f"link {k + 1} ({j['child']}): carries joints off the chain "
                         f"({', '.join(held)}), held rigid at their zero angle")
        M, c, I = _body(robot, parts, j["name"])
        G = A[k][:3, :3] @ P[:3, :3]
        c_f, I_f = G.T @ c, G.T @ I @ G
        tol_i = 1e-12 * max(np.trace(I_f), 1e-300)
        link = {"alpha_rad": 0.0, "a_m": 0.0, "d_m": 0.0,
                "placement_m": _clean(P[:3, 3], 1e-15),
                "placement_rotvec_rad": _clean(rotvec(P[:3, :3]), 1e-15), "mass_kg": M,
                "com_m": _clean(c_f, 1e-15), "inertia_kg_m2": _clean(np.diag(I_f), tol_i),
                "inertia_products_kg_m2": _clean([I_f[0, 1], I_f[0, 2], I_f[1, 2]], tol_i)}
        lim = j["el"].find("limit")
        if j["type"] == "revolute" and lim is not None:
            what = f"joint {j['name']!r} <limit>"  # URDF: lower and upper default to 0
            link["joint_min_rad"] = float(_floats(lim, "lower", 1, what, [0.0])[0])
            link["joint_max_rad"] = float(_floats(lim, "upper", 1, what, [0.0])[0])
        else:
            notes.append(f"link {k + 1} ({j['name']}): {j['type']} without <limit>: the "
                         "scenario's default limits ±2π apply (the controller flags a sensed "
                         "angle beyond them)")
        child = j["child"]
        if child in hydro:
            link["diameter_m"] = float(hydro[child].get("diameter_m", 0.0))
            link["drag_coeff"] = float(hydro[child].get("drag_coeff", 1.0))
            if "added_mass_kg" in hydro[child]:
                link["added_mass_kg"] = _added_mass_in_frame(hydro[child]["added_mass_kg"], G,
                                                             child, k + 1)
            notes.append(f"link {k + 1} ({child}): hydrodynamics from the side file")
        else:
            cyl = _cylinder(robot["links"][child])
            if cyl is not None and math.isfinite(cyl[0]):
                link["diameter_m"] = 2.0 * cyl[0]
                notes.append(f"link {k + 1} ({child}): diameter from its collision cylinder "
                             f"(radius {cyl[0]:g} m), drag coefficient the default")
            else:
                link["diameter_m"] = 0.0
                notes.append(f"link {k + 1} ({child}): no side-file entry and no collision "
                             "cylinder: no hydrodynamics (diameter 0)")
        if link["diameter_m"] > 0 and not np.linalg.norm(P[:3, 3]) > 1e-12:
            notes.append(f"link {k + 1} ({child}): zero length (joint {k + 1} and the next "
                         "frame share a point), so its cylinder has no volume: no buoyancy, "
                         "drag or added mass (a --tip further out gives the last link a length)")
        links.append(link)
    other = sorted(set(hydro) - {joints[k]["child"] for k in movable})
    if other:
        raise UrdfError(f"--hydro: {', '.join(other)} is not the first link of a moving body "
                        f"(expected one of: {', '.join(joints[k]['child'] for k in movable)})")
    return {"base_offset_m": _clean(base[:3, 3], 1e-15),
            "base_rotvec_rad": _clean(rotvec(base[:3, :3]), 1e-15),
            "links": links, "notes": notes, "root": root, "tip": tip,
            "joints": [joints[k]["name"] for k in movable]}


# ---- output ----------------------------------------------------------------------------------

def _num(x):
    return repr(float(0.0 if abs(x) < 1e-300 else x))


def _vec(v):
    return "[" + ", ".join(_num(x) for x in v) + "]"


def to_toml(arm, source):
    """The arm part of a vehicle description, as scenario TOML."""
    lines = [f"# The arm of {source} (uvms vehicle import-urdf): root link {arm['root']!r}, tip "
             f"{arm['tip']!r}, joints {', '.join(arm['joints'])}.",
             "# General links (docs/MODEL.md §2): joint angles are the URDF's; "
             "joint k turns about frame k−1's z.", ""]
    lines += ["[vehicle]", f"arm_base_m = {_vec(arm['base_offset_m'])}",
              f"arm_base_rotvec_rad = {_vec(arm['base_rotvec_rad'])}", ""]
    for note in arm["notes"]:
        lines.append(f"# {note}")
    for k, link in enumerate(arm["links"]):
        lines += ["", f"[[arm.link]]                      # joint {k + 1}: {arm['joints'][k]}"]
        for key, v in link.items():
            lines.append(f"{key} = {_vec(v) if isinstance(v, (np.ndarray, list)) else _num(v)}")
    return "\n".join(lines) + "\n"
