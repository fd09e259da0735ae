#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""End-to-end checks of the real `uvms` binary's `model` subcommand: exit codes, the single
error line on bad input, the output's keys and array lengths, and --config.

usage: test_model_cli_e2e.py UVMS_BINARY CASE     (CASE: one of the functions in CASES)
Exit status 0 when the case passes; a message on stderr otherwise.
"""
import json
import os
import subprocess
import sys
import tempfile

N_JOINTS = 7  # the paper's arm (SPEC §3.1)

# Every documented output key and its array shape (list of lengths, outermost first).
OUTPUT_SHAPES = {
    "ee_position_m": [3],
    "barycenter_m": [3],
    "base_point_m": [3],
    "link_com_m": [N_JOINTS, 3],
    "base_force_N": [3],
    "base_moment_Nm": [3],
    "joint_torque_Nm": [N_JOINTS],
    "vehicle_drag_N": [3],
}
FEEDFORWARD_KEYS = ["attitude_moment_Nm", "vehicle_force_N", "barycenter_force_N",
                    "attitude_moment_barycenter_Nm", "barycenter_accel_m_s2"]


def valid_input():
    # A moving, loaded state: values are arbitrary but fixed.
    return {
        "vehicle": {
            "position_m": [0.5, -0.2, 1.0],
            "quaternion_wxyz": [0.9, 0.1, -0.2, 0.3],
            "velocity_m_s": [0.05, -0.02, 0.01],
            "angular_velocity_rad_s": [0.01, 0.02, -0.03],
            "acceleration_m_s2": [0.1, 0.0, -0.05],
            "angular_acceleration_rad_s2": [0.0, 0.02, 0.0],
        },
        "joints": {
            "position_rad": [3.0, 1.2, 3.3, 2.5, 0.4, 0.8, 0.6],
            "velocity_rad_s": [0.1, -0.2, 0.15, 0.3, -0.25, 0.2, 0.1],
            "acceleration_rad_s2": [0.3, 0.2, -0.4, 0.5, 0.1, -0.3, 0.6],
        },
        "density_kg_m3": 1025,
        "flow_m_s": [0.0, 0.0, 0.0],
        "gravity_m_s2": [0.0, 0.0, -9.81],
        "payload_kg": 10,
        "angle_of_attack": True,
    }


class Failure(Exception):
    pass


def expect(cond, message):
    if not cond:
        raise Failure(message)


def run(uvms, args, stdin_text):
    p = subprocess.run([uvms] + args, input=stdin_text, capture_output=True, text=True,
                       timeout=60)
    return p.returncode, p.stdout, p.stderr


def expect_one_error_line(code, out, err, want_code, *fragments):
    expect(code == want_code, f"exit code {code}, expected {want_code}; stderr: {err!r}")
    expect(out == "", f"stdout not empty: {out!r}")
    lines = err.splitlines()
    expect(len(lines) == 1 and err.endswith("\n"), f"expected one stderr line, got {err!r}")
    expect(lines[0].startswith("uvms model: error: "), f"bad error prefix: {lines[0]!r}")
    for f in fragments:
        expect(f in lines[0], f"{f!r} not in {lines[0]!r}")


def check_shape(value, shape, name):
    expect(isinstance(value, list) and len(value) == shape[0],
           f"{name}: expected {shape[0]} elements, got {value!r}")
    for v in value:
        if len(shape) > 1:
            check_shape(v, shape[1:], name)
        else:
            expect(isinstance(v, float) or isinstance(v, int), f"{name}: not a number: {v!r}")


def with_config(config):
    """Write config to a temporary file and return its path (deleted by the caller)."""
    fd, path = tempfile.mkstemp(prefix="uvms_model_cli_e2e_", suffix=".json")
    with os.fdopen(fd, "w") as f:
        json.dump(config, f)
    return path


def case_valid_input(uvms):
    code, out, err = run(uvms, ["model"], json.dumps(valid_input()))
    expect(code == 0, f"exit code {code}; stderr: {err!r}")
    expect(err == "", f"stderr not empty: {err!r}")
    expect(out.count("\n") == 1, "output is not one line")
    result = json.loads(out)
    expect(set(result) == set(OUTPUT_SHAPES) | {"feedforward"},
           f"keys: {sorted(result)}")
    for key, shape in OUTPUT_SHAPES.items():
        check_shape(result[key], shape, key)
    expect(set(result["feedforward"]) == set(FEEDFORWARD_KEYS),
           f"feedforward keys: {sorted(result['feedforward'])}")
    for key in FEEDFORWARD_KEYS:
        check_shape(result["feedforward"][key], [3], key)


def case_garbage_stdin(uvms):
    for text in ["garbage\nmore garbage\n", "", "[1, 2", "{} {}"]:
        code, out, err = run(uvms, ["model"], text)
        expect_one_error_line(code, out, err, 1, "stdin: invalid JSON")


def case_missing_field(uvms):
    inp = valid_input()
    del inp["joints"]["velocity_rad_s"]
    code, out, err = run(uvms, ["model"], json.dumps(inp))
    expect_one_error_line(code, out, err, 1, 'missing field "joints.velocity_rad_s"')
    inp = valid_input()
    del inp["angle_of_attack"]
    code, out, err = run(uvms, ["model"], json.dumps(inp))
    expect_one_error_line(code, out, err, 1, 'missing field "angle_of_attack"')


def case_bad_field(uvms):
    inp = valid_input()
    inp["vehicle"]["position_m"] = [0.0, 1.0]
    code, out, err = run(uvms, ["model"], json.dumps(inp))
    expect_one_error_line(code, out, err, 1, '"vehicle.position_m"', "expected 3 elements")
    inp = valid_input()
    inp["density_kg_m3"] = -3
    code, out, err = run(uvms, ["model"], json.dumps(inp))
    expect_one_error_line(code, out, err, 1, '"density_kg_m3"')
    inp = valid_input()
    inp["joints"]["torque_Nm"] = [0.0] * N_JOINTS
    code, out, err = run(uvms, ["model"], json.dumps(inp))
    expect_one_error_line(code, out, err, 1, 'unknown field "joints.torque_Nm"')


def case_duplicate_key(uvms):
    # nlohmann::json alone would keep the last value; the command refuses the ambiguity.
    text = json.dumps(valid_input()).replace('"payload_kg": 10', '"payload_kg": 0, "payload_kg": 10')
    expect(text.count('"payload_kg"') == 2, "the test input does not repeat payload_kg")
    code, out, err = run(uvms, ["model"], text)
    expect_one_error_line(code, out, err, 1, 'stdin: duplicate key "payload_kg"')
    fd, path = tempfile.mkstemp(prefix="uvms_model_cli_e2e_", suffix=".json")
    with os.fdopen(fd, "w") as f:
        f.write('{"links": [{}, {"mass_kg": 1.0, "mass_kg": 2.0}]}')
    try:
        code, out, err = run(uvms, ["model", "--config", path], json.dumps(valid_input()))
        expect_one_error_line(code, out, err, 1, path + ': duplicate key "links[1].mass_kg"')
    finally:
        os.remove(path)


def case_config_unknown_key(uvms):
    path = with_config({"vehicle": {"mass_kg": 100.0, "mass_lb": 220.0}})
    try:
        code, out, err = run(uvms, ["model", "--config", path], json.dumps(valid_input()))
        expect_one_error_line(code, out, err, 1, path, 'unknown key "vehicle.mass_lb"')
    finally:
        os.remove(path)


def case_config_invalid_params(uvms):
    path = with_config({"vehicle": {"mass_kg": -1.0}})
    try:
        code, out, err = run(uvms, ["model", "--config", path], json.dumps(valid_input()))
        expect_one_error_line(code, out, err, 1, path, "UVMS_ERR_RANGE")
    finally:
        os.remove(path)


def case_config_mass_moves_barycenter(uvms):
    code, out, err = run(uvms, ["model"], json.dumps(valid_input()))
    expect(code == 0, f"default run failed: {err!r}")
    default = json.loads(out)
    path = with_config({"vehicle": {"mass_kg": 60.0}})
    try:
        code, out, err = run(uvms, ["model", f"--config={path}"], json.dumps(valid_input()))
        expect(code == 0, f"config run failed: {err!r}")
        light = json.loads(out)
    finally:
        os.remove(path)
    shift = sum((a - b) ** 2 for a, b in zip(light["barycenter_m"], default["barycenter_m"])) ** 0.5
    expect(shift > 1e-3, f"barycenter moved only {shift} m with half the vehicle mass")
    # The vehicle mass changes neither the EE nor the arm's Newton-Euler at given accelerations.
    expect(light["ee_position_m"] == default["ee_position_m"], "EE moved")
    expect(light["base_force_N"] == default["base_force_N"], "f1 changed")
    # A 3-link config needs 3-element joint arrays.
    path = with_config({"links": [{}, {}, {}]})
    try:
        code, out, err = run(uvms, ["model", "--config", path], json.dumps(valid_input()))
        expect_one_error_line(code, out, err, 1, '"joints.position_rad"', "expected 3 elements")
    finally:
        os.remove(path)


def case_usage_errors(uvms):
    for args in (["model", "--bogus"], ["model", "--config"], ["model", "input.json"]):
        code, out, err = run(uvms, args, json.dumps(valid_input()))
        expect(code == 2, f"{args}: exit code {code}, expected 2")
        expect(out == "", f"{args}: stdout not empty")
        expect("usage: uvms model" in err, f"{args}: no usage line in {err!r}")
    for args in (["frobnicate"], []):
        code, out, err = run(uvms, args, "")
        expect(code == 2, f"{args}: exit code {code}, expected 2")
        expect("usage: uvms <subcommand>" in err, f"{args}: no usage line in {err!r}")


def case_help(uvms):
    code, out, err = run(uvms, ["--help"], "")
    expect(code == 0 and "model" in out and err == "", f"uvms --help: {code} {out!r} {err!r}")
    code, out, err = run(uvms, ["model", "--help"], "")
    expect(code == 0 and out.startswith("usage: uvms model") and err == "",
           f"uvms model --help: {code} {err!r}")
    for key in list(OUTPUT_SHAPES) + FEEDFORWARD_KEYS:
        expect(f'"{key}"' in out, f"--help does not document {key}")


CASES = {name[len("case_"):]: fn for name, fn in globals().items() if name.startswith("case_")}


def main():
    if len(sys.argv) != 3 or sys.argv[2] not in CASES:
        print(f"usage: {sys.argv[0]} UVMS_BINARY {{{'|'.join(CASES)}}}", file=sys.stderr)
        return 2
    try:
        CASES[sys.argv[2]](sys.argv[1])
    except Failure as e:
        print(f"FAIL {sys.argv[2]}: {e}", file=sys.stderr)
        return 1
    print(f"PASS {sys.argv[2]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
