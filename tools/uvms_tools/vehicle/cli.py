# SPDX-License-Identifier: Apache-2.0
"""cli: `uvms vehicle import-urdf` (the command line; the conversion is urdf.py)."""
import argparse
import math
import sys
import tomllib

import numpy as np

from . import urdf

EXIT_OK, EXIT_BAD_INPUT, EXIT_USAGE = 0, 1, 2

DESCRIPTION = """\
import-urdf: write the arm part of a vehicle description (scenario TOML: [vehicle]
arm_base_m, arm_base_rotvec_rad and one [[arm.link]] per revolute joint, in the general form of
docs/MODEL.md §2) from an arm's URDF. The chain runs from the root link to --tip (or to the
only leaf); fixed joints are merged into the links they join; joint angles are the URDF's.
Each moving link needs an <inertial>. URDF has no hydrodynamics: a link's cylinder diameter and
drag coefficient come from --hydro, else from its collision cylinder (drag coefficient 1.0),
else it has none; the output says which, per link. A link's own diagonal added mass comes only
from --hydro (else the scenario's shared coefficients apply, docs/MODEL.md §3.3). Paste the output into a scenario and give
its trajectory the joints' angles (docs/SCENARIOS.md "Your arm from URDF").

--hydro FILE (TOML), one table per link name:
    [forearm]
    diameter_m = 0.04
    drag_coeff = 1.1
    added_mass_kg = [0.1, 0.1, 0.0, 2e-4, 2e-4, 0.0]   # optional: kg ×3, kg·m² ×3, the
                                                        # diagonal in the URDF link's axes

Exit status: 0 written; 1 bad input (the URDF or the side file: the message names the element);
2 usage error."""


class UsageError(Exception):
    pass


class Parser(argparse.ArgumentParser):
    def error(self, message):
        raise UsageError(message)


def build_parser():
    p = Parser(prog="uvms vehicle", formatter_class=argparse.RawDescriptionHelpFormatter,
               description="Describe your own vehicle for the models.\n\n" + DESCRIPTION)
    sub = p.add_subparsers(dest="command", metavar="import-urdf")
    imp = sub.add_parser("import-urdf", formatter_class=argparse.RawDescriptionHelpFormatter,
                         description=DESCRIPTION, help="the arm part of a description from URDF")
    imp.error = p.error
    imp.add_argument("urdf", metavar="ARM.urdf", help="the arm's URDF file")
    imp.add_argument("--tip", metavar="LINK", help="the link whose origin is the end effector "
                     "(required when the tree branches, e.g. before a gripper's mimic joints)")
    imp.add_argument("--hydro", metavar="FILE", help="TOML side file of link diameters and drag")
    imp.add_argument("--mount-xyz", nargs=3, type=float, default=[0.0, 0.0, 0.0],
                     metavar=("X", "Y", "Z"), help="the root link's origin in the vehicle frame "
                     "(from the vehicle CoM) [m]; default 0 0 0")
    imp.add_argument("--mount-rpy", nargs=3, type=float, default=[0.0, 0.0, 0.0],
                     metavar=("R", "P", "Y"), help="the root link's orientation in the vehicle "
                     "frame, URDF roll pitch yaw [rad]; default 0 0 0")
    imp.add_argument("--out", metavar="FILE", help="write here instead of standard output")
    return p


def read_hydro(path):
    try:
        with open(path, "rb") as f:
            table = tomllib.load(f)
    except OSError as e:
        raise urdf.UrdfError(f"--hydro {path}: {e.strerror}") from None
    except tomllib.TOMLDecodeError as e:
        raise urdf.UrdfError(f"--hydro {path}: not TOML ({e})") from None
    for name, entry in table.items():
        if not isinstance(entry, dict):
            raise urdf.UrdfError(f"--hydro {path}: [{name}] is not a table")
        for key, v in entry.items():
            if key not in ("diameter_m", "drag_coeff", "added_mass_kg"):
                raise urdf.UrdfError(f"--hydro {path}: [{name}] {key}: unknown key (expected "
                                     "diameter_m, drag_coeff, added_mass_kg)")
            if key == "added_mass_kg":
                if not (isinstance(v, list) and len(v) == 6 and all(
                        isinstance(x, (int, float)) and math.isfinite(x) and x >= 0 for x in v)):
                    raise urdf.UrdfError(f"--hydro {path}: [{name}] added_mass_kg = {v!r} "
                                         "(expected 6 numbers >= 0)")
                continue
            if not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0:
                raise urdf.UrdfError(f"--hydro {path}: [{name}] {key} = {v!r} (expected a "
                                     "number >= 0)")
    return table


def import_urdf(args):
    try:
        with open(args.urdf, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        raise urdf.UrdfError(f"{args.urdf}: {e.strerror}") from None
    robot = urdf.parse(text, args.urdf)
    hydro = read_hydro(args.hydro) if args.hydro else None
    if hydro:
        unknown = sorted(set(hydro) - set(robot["links"]))
        if unknown:
            raise urdf.UrdfError(f"--hydro {args.hydro}: no <link> named {', '.join(unknown)}")
    mount = urdf.transform(urdf.rot_rpy(*args.mount_rpy), np.array(args.mount_xyz))
    arm = urdf.convert(robot, args.tip, hydro, mount)
    out = urdf.to_toml(arm, args.urdf)
    if args.out:
        with open(args.out, "w", encoding="utf-8") as f:
            f.write(out)
    else:
        sys.stdout.write(out)


def main(argv=None):
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
        if args.command is None:
            raise UsageError("missing subcommand (import-urdf)")
    except UsageError as e:
        print(f"uvms vehicle: error: {e}", file=sys.stderr)
        print("usage: uvms vehicle import-urdf ARM.urdf [--tip LINK] [--hydro FILE] "
              "[--mount-xyz X Y Z] [--mount-rpy R P Y] [--out FILE]  (see --help)", file=sys.stderr)
        return EXIT_USAGE
    try:
        import_urdf(args)
    except urdf.UrdfError as e:
        print(f"uvms vehicle: error: {e}", file=sys.stderr)
        return EXIT_BAD_INPUT
    return EXIT_OK
