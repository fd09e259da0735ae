# SPDX-License-Identifier: Apache-2.0
"""End-to-end tests of the SIL harness through the real binaries (issue 5).

Usage: test_sil_e2e.py BUILD_SIL_DIR SOURCE_DIR CASE
CASE: transports | determinism | replay | replay_detects_tampering | logplayer |
      corrupt_injection | controller_silent | bad_scenario

Every run is short (a few simulated seconds of a paper scenario, its trajectory shortened to
the run) and writes into a fresh temporary directory.
"""
import json
import math
import os
import subprocess
import sys
import threading
import time
import zlib

import lcm
import uvms  # lcm-gen --python output (PYTHONPATH)
from lcm_urls import private_url  # tests/sil/lcm_urls.py

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

SIL, SRC, CASE = sys.argv[1], sys.argv[2], sys.argv[3]
UVMS = os.path.join(SIL, "uvms")
SCENARIO = os.path.join(SRC, "sil", "scenarios", "paper", "case_VII_unsteady.toml")
SHORT = ["--set", "run.duration_s=1.5", "--set", "trajectory.duration_s=1.5"]
TMP = scratch_dir("uvms-e2e-")  # removed at exit (tests/support/scratch.py)


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def run(args, expect=0, timeout=120):
    p = subprocess.run([UVMS] + args, capture_output=True, text=True, timeout=timeout)
    print("$ uvms", " ".join(args), "->", p.returncode)
    print(p.stdout, p.stderr, sep="")
    if expect is not None and p.returncode != expect:
        fail(f"exit {p.returncode}, expected {expect}")
    return p


def run_scenario(name, transport, extra=()):
    out = os.path.join(TMP, name)
    run(["run", SCENARIO, "--out", out, "--transport", transport] + SHORT + list(extra))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(out, "run.lcmlog"), "rb") as f:
        log = f.read()
    return out, summary, log




def log_events(path):
    return [(e.channel, e.timestamp, e.data) for e in lcm.EventLog(path, "r")]


# Wall-clock-dependent fields: timing, and how often the start-up handshake had to re-send.
# Not results: wall-clock figures, the transport itself, and the provenance (it records the
# --set lines, which differ between these runs by construction).
WALL_KEYS = {"wall_time_s", "real_time_factor", "plant_wall_s", "transport", "config_retries", "provenance"}


# A fixed session (sil/msg/session.h): by default every run draws its own, which every message
# carries, so only runs given the same session can have byte-identical logs.
SAME_SESSION = ["--session", "5e55105e55105e55"]


def case_transports():
    # udpm with the default busy-poll before blocking (link.spin_us, sil/link/lcm_wait.h) on the
    # private link (a port per direction), udpm blocking at once (spin_us = 0), udpm with both
    # directions on one URL given (--url) and on two given (--url, --publish-url), and memq: the
    # waiting strategy and the link's layout must not change a bit.
    _, a, log_a = run_scenario("udpm", "udpm", SAME_SESSION)
    _, c, log_c = run_scenario("udpm_blocking", "udpm", ["--set", "link.spin_us=0"] + SAME_SESSION)
    _, d, log_d = run_scenario("udpm_shared", "udpm", ["--url", private_url()] + SAME_SESSION)
    url_a, url_b = private_url(), private_url()
    while url_b == url_a:  # the kernel may hand the same free port out twice
        url_b = private_url()
    _, e, log_e = run_scenario("udpm_given_split", "udpm",
                               ["--url", url_a, "--publish-url", url_b] + SAME_SESSION)
    _, b, log_b = run_scenario("memq", "memq", SAME_SESSION)
    for s in (a, b, c, d, e):
        if s["status"] != "finished" or s["ticks"] != 50 or s["missed_ticks"] != 0:
            fail(f"run did not finish cleanly: {s}")
    for name, other, log_other in (("memq", b, log_b), ("udpm with spin_us = 0", c, log_c),
                                   ("udpm on one URL", d, log_d),
                                   ("udpm on two URLs given", e, log_e)):
        diff = {k: (a[k], other[k]) for k in a if k not in WALL_KEYS and a[k] != other[k]}
        if diff:
            fail(f"udpm and {name} summaries differ: {diff}")
        if log_a != log_other:
            fail(f"udpm and {name} logs differ")
    print(f"udpm (spin and blocking; a private link, one URL, two URLs) and memq: identical "
          f"summaries and logs ({len(log_a)} bytes)")


def case_determinism():
    _, a, log_a = run_scenario("first", "memq", SAME_SESSION)
    _, b, log_b = run_scenario("second", "memq", SAME_SESSION)
    if log_a != log_b:
        fail("the same scenario and session gave different logs")
    _, c, log_c = run_scenario("third", "memq")  # a session of its own
    if a["session"] != SAME_SESSION[1] or c["session"] in (a["session"], "0" * 16):
        fail(f"sessions {a['session']}, {c['session']}: the fixed one, then a fresh one expected")
    ev_a = log_events(os.path.join(TMP, "first", "run.lcmlog"))
    ev_c = log_events(os.path.join(TMP, "third", "run.lcmlog"))
    if len(ev_a) != len(ev_c):
        fail("a run of its own session has a different number of events")
    for (ch_a, t_a, d_a), (ch_c, t_c, d_c) in zip(ev_a, ev_c):
        # bytes 24..32 are the session (after fingerprint, utime, tick); the last 4 the CRC
        if (ch_a, t_a, d_a[:24], d_a[32:-4]) != (ch_c, t_c, d_c[:24], d_c[32:-4]):
            fail(f"{ch_a} at {t_a} us differs beyond its session")
        if d_c[24:32] != bytes.fromhex(c["session"]):
            fail(f"{ch_c} at {t_c} us does not carry the run's session {c['session']}")
    ev = log_events(os.path.join(TMP, "first", "run.lcmlog"))
    channels = {}
    for ch, _, _ in ev:
        channels[ch] = channels.get(ch, 0) + 1
    expected = {"UVMS_CONFIG": 1, "UVMS_SCENE": 1, "UVMS_TELEMETRY": 51, "UVMS_STATUS": 2, "UVMS_TRUTH": 51,
                "UVMS_SENSORS": 50, "UVMS_ACTUATORS": 50}
    if channels != expected:
        fail(f"log channel counts {channels}, expected {expected}")
    # Timestamps are simulated time: tick k at k * 30000 us, never wall clock.
    sens = [uvms.sensors_t.decode(d) for ch, _, d in ev if ch == "UVMS_SENSORS"]
    stamps = [t for ch, t, _ in ev if ch == "UVMS_SENSORS"]
    if stamps != [30000 * k for k in range(50)] or [s.tick for s in sens] != list(range(50)):
        fail("sensor timestamps/ticks are not the simulated tick times")
    print(f"two runs: byte-identical logs ({len(log_a)} bytes); channel counts {channels}")


def case_replay():
    out, _, _ = run_scenario("replay", "udpm")
    p = run(["replay", os.path.join(out, "run.lcmlog")])
    if "identical: 50 actuator messages" not in p.stdout:
        fail("replay did not report 50 identical actuator messages")


def reseal(data):
    """Recompute the trailing CRC-32 (IEEE, = zlib.crc32) of an encoded uvms message."""
    return data[:-4] + (zlib.crc32(data[:-4]) & 0xFFFFFFFF).to_bytes(4, "big")


def case_replay_detects_tampering():
    out, _, _ = run_scenario("tamper", "memq")
    src = os.path.join(out, "run.lcmlog")
    dst = os.path.join(out, "tampered.lcmlog")
    log_in, log_out = lcm.EventLog(src, "r"), lcm.EventLog(dst, "w", overwrite=True)
    for e in log_in:
        data = e.data
        if e.channel == "UVMS_ACTUATORS":
            m = uvms.actuators_t.decode(data)
            if m.tick == 17:
                m.motor_voltage_V = list(m.motor_voltage_V)
                m.motor_voltage_V[3] = math.nextafter(m.motor_voltage_V[3], math.inf)  # 1 ulp
                data = reseal(m.encode())
        log_out.write_event(e.timestamp, e.channel, data)
    log_out.close()
    p = run(["replay", dst], expect=1)
    if "tick 17, field motor_voltage_V[3]" not in p.stdout:
        fail("replay did not name tick 17, field motor_voltage_V[3]")
    # A sensors message a recorder missed (lcm-logger on a busy link): incomplete, not a
    # difference of the controller.
    lost = os.path.join(out, "lost.lcmlog")
    log_in, log_out = lcm.EventLog(src, "r"), lcm.EventLog(lost, "w", overwrite=True)
    for e in log_in:
        if e.channel == "UVMS_SENSORS" and uvms.sensors_t.decode(e.data).tick == 23:
            continue
        log_out.write_event(e.timestamp, e.channel, e.data)
    log_out.close()
    p = run(["replay", lost], expect=3)
    if "the actuators of tick 23 without its sensors" not in p.stderr:
        fail("replay did not call a missing sensors message incomplete")


def case_logplayer():
    out, _, _ = run_scenario("play", "memq")
    url = private_url()
    counts, lock = {}, threading.Lock()
    lc = lcm.LCM(url)

    def handler(channel, data):
        with lock:
            counts[channel] = counts.get(channel, 0) + 1
            if channel == "UVMS_SENSORS":
                uvms.sensors_t.decode(data)  # the played bytes decode

    lc.subscribe("UVMS_.*", handler)
    player = subprocess.Popen(["lcm-logplayer", "-s", "5", "-l", url,
                               os.path.join(out, "run.lcmlog")])
    deadline = time.time() + 30
    while player.poll() is None and time.time() < deadline:
        lc.handle_timeout(50)
    for _ in range(20):
        lc.handle_timeout(50)
    if player.returncode != 0:
        fail(f"lcm-logplayer exited with {player.returncode}")
    expected = {}
    for ch, _, _ in log_events(os.path.join(out, "run.lcmlog")):
        expected[ch] = expected.get(ch, 0) + 1
    print("received", counts, "logged", expected)
    if counts != expected:
        fail("the listener did not receive every logged message")


def lcm_logger(url, path):
    """A real lcm-logger on url writing path (Debian's 1.3.1 takes --lcm-url=, not -l URL)."""
    logger = subprocess.Popen(["lcm-logger", f"--lcm-url={url}", "-f", path],
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(0.5)  # subscribed before the first message
    return logger


def stop_logger(logger):
    time.sleep(0.5)  # the last messages written (--flush-interval 100 ms)
    logger.send_signal(2)  # SIGINT: lcm-logger closes its file
    try:
        logger.wait(timeout=10)
    except subprocess.TimeoutExpired:
        logger.kill()
        fail("lcm-logger did not stop on SIGINT")


def case_lcm_tools():
    """README "Record and play back with LCM's tools", with the real programs: a udpm run
    recorded by lcm-logger on the run's URL replays identical (events on other channels counted
    and ignored; truth_t published with link.publish_truth); without publish_truth the replay
    says how to record it; a run log played by lcm-logplayer into lcm-logger replays identical;
    `uvms replay DIR` takes a run directory."""
    url = private_url()
    recorded = os.path.join(TMP, "logger.lcmlog")
    logger = lcm_logger(url, recorded)
    # Paced (link.realtime_factor): a listener on a busy link can miss messages; the replay
    # would then say which (incomplete), but this test is about a complete recording.
    paced = ["--set", "link.realtime_factor=2"]
    run(["run", SCENARIO, "--out", os.path.join(TMP, "logged"), "--transport", "udpm", "--url", url,
         "--set", "link.publish_truth=true"] + paced + SHORT)
    stop_logger(logger)
    p = run(["replay", recorded])
    if "identical" not in p.stdout:
        fail("the lcm-logger recording did not replay identical")
    # Without truth_t on the link: refused, saying how to record it.
    url2 = private_url()
    bare = os.path.join(TMP, "bare.lcmlog")
    logger = lcm_logger(url2, bare)
    run(["run", SCENARIO, "--out", os.path.join(TMP, "bare"), "--transport", "udpm", "--url", url2]
        + paced + SHORT)
    stop_logger(logger)
    p = run(["replay", bare], expect=3)
    if "link.publish_truth=true" not in p.stderr:
        fail("a recording without truth_t does not say how to record it")
    # A run log played by lcm-logplayer and re-recorded by lcm-logger.
    out, _, _ = run_scenario("replayed", "memq")
    url3 = private_url()
    copy = os.path.join(TMP, "copy.lcmlog")
    logger = lcm_logger(url3, copy)
    player = subprocess.run(["lcm-logplayer", "-s", "2", f"--lcm-url={url3}",
                             os.path.join(out, "run.lcmlog")], timeout=60)
    stop_logger(logger)
    if player.returncode != 0:
        fail(f"lcm-logplayer exited with {player.returncode}")
    p = run(["replay", copy])
    if "identical" not in p.stdout:
        fail("the played and re-recorded log did not replay identical")
    p = run(["replay", out])  # the run directory itself
    if "identical" not in p.stdout:
        fail("uvms replay DIR did not replay the run's log")
    # --url A --publish-url B (the layout of uvms run's private link): a logger on each URL
    # records one direction: the plant's messages on B, the controller's on A, nothing of the
    # other side on either.
    url_a = private_url()
    url_b = private_url()
    while url_b == url_a:  # the kernel may hand the same free port out twice
        url_b = private_url()
    rec_a, rec_b = os.path.join(TMP, "dir_a.lcmlog"), os.path.join(TMP, "dir_b.lcmlog")
    logger_a, logger_b = lcm_logger(url_a, rec_a), lcm_logger(url_b, rec_b)
    run(["run", SCENARIO, "--out", os.path.join(TMP, "split"), "--transport", "udpm", "--url", url_a,
         "--publish-url", url_b] + paced + SHORT)
    stop_logger(logger_a)
    stop_logger(logger_b)
    heard = {name: {e.channel for e in lcm.EventLog(path, "r") if e.channel.startswith("UVMS_")}
             for name, path in (("A", rec_a), ("B", rec_b))}
    print("channels heard on each URL:", heard)
    if heard["A"] != {"UVMS_ACTUATORS", "UVMS_TELEMETRY"}:
        fail(f"the listening URL carried {sorted(heard['A'])}, not only the controller's answers")
    if heard["B"] != {"UVMS_CONFIG", "UVMS_SENSORS", "UVMS_STATUS"}:
        fail(f"the publishing URL carried {sorted(heard['B'])}, not only the plant's messages")


def case_corrupt_injection():
    url = private_url()
    out = os.path.join(TMP, "inject")
    proc = subprocess.Popen([UVMS, "run", SCENARIO, "--out", out, "--transport", "udpm",
                             "--url", url, "--set", "run.duration_s=3",
                             "--set", "trajectory.duration_s=3",
                             "--set", "link.realtime_factor=10"],  # >= 0.3 s of junk
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    lc = lcm.LCM(url)
    valid = uvms.sensors_t()
    valid.tick = 10 ** 9
    good = reseal(valid.encode())
    junk = [b"", b"\x00" * 3, os.urandom(64), good[:40], good[:-1],
            good[:20] + bytes([good[20] ^ 0x40]) + good[21:]]
    sent = 0
    while proc.poll() is None:
        for ch in ("UVMS_SENSORS", "UVMS_ACTUATORS", "UVMS_TELEMETRY", "UVMS_CONFIG",
                   "UVMS_STATUS"):
            lc.publish(ch, junk[sent % len(junk)])
            sent += 1
        time.sleep(0.002)
    print(proc.stdout.read())
    if proc.returncode != 0:
        fail(f"run under injected junk exited {proc.returncode}")
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    print({k: s[k] for k in ("status", "ticks", "missed_ticks", "rx_rejected",
                             "controller_rx_rejected")}, "junk messages sent:", sent)
    if s["status"] != "finished" or s["ticks"] != 100:
        fail("the run did not complete under injected junk")
    if s["rx_rejected"] <= 0 or s["controller_rx_rejected"] <= 0:
        fail("junk was not counted on both sides")
    p = run(["replay", os.path.join(out, "run.lcmlog")])
    if "identical" not in p.stdout:
        fail("the log of the injected run does not replay identically")


def case_controller_silent():
    url = private_url()
    out = os.path.join(TMP, "silent")
    os.makedirs(out)
    ctrl = subprocess.Popen([os.path.join(SIL, "uvms-controller"), "--url", url])
    plant = subprocess.Popen([os.path.join(SIL, "uvms-plant"), SCENARIO, "--url", url, "--out",
                              out, "--set", "link.timeout_s=0.05", "--set", "link.max_missed=3",
                              "--set", "link.realtime_factor=1"])
    time.sleep(1.0)  # real-time pacing: about 33 ticks done
    ctrl.kill()
    ctrl.wait()
    rc = plant.wait(timeout=60)
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    print({k: s[k] for k in ("status", "failure", "reason", "ticks", "missed_ticks")})
    if rc != 3 or s["status"] != "failed" or s["failure"] != "controller_silent":
        fail("a dead controller did not end the run as controller_silent")
    if s["missed_ticks"] != 4:
        fail(f"expected 4 missed ticks (max_missed 3 + 1), got {s['missed_ticks']}")


def check_thruster_types():
    """Thrusters of two types (sil/scenarios/vehicles/mixed_thrusters_VII_stagnant.toml): the
    logged configuration carries each thruster's set and bound; the plant's thrust of each
    vertical T200 is its own law at the logged shaft speed (CT1 = 0: T = ρD⁴/(4π²)·CT2·ω|ω|,
    evaluated here from the set's published numbers, not the code's); the controller keeps
    the vertical motors within their 16 V supply."""
    path = os.path.join(SRC, "sil", "scenarios", "vehicles", "mixed_thrusters_VII_stagnant.toml")
    out = os.path.join(TMP, "types")
    run(["run", path, "--out", out, "--transport", "memq"] + SHORT)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    if summary["status"] != "finished":
        fail(f"the two-type vehicle's run did not finish: {summary['status']}")
    ev = log_events(os.path.join(out, "run.lcmlog"))
    cfg = uvms.controller_config_t.decode(next(d for ch, _, d in ev if ch == "UVMS_CONFIG"))
    t200 = dict(D=0.076, ct2=-0.3734, km=0.02166)  # sil/scenario/motor_sets.cpp's T200 set
    for j in range(8):
        vertical = j >= 4
        want = (t200["D"], t200["ct2"], t200["km"], 16.0, 39.9) if vertical else (0.05, -0.5, 10.0, 1e5, 1e6)
        got = (cfg.propeller_diameter_m[j], cfg.ct2[j], cfg.motor_torque_constant_Nm_A[j],
               cfg.voltage_limit_V[j], cfg.thrust_limit_N[j])
        if any(abs(g - w) > 1e-6 * abs(w) for g, w in zip(got, want)):  # float build: rounded
            fail(f"thruster {j + 1}: configuration (D, CT2, km, V limit, thrust limit) {got}, expected {want}")
    rho = cfg.density_kg_m3
    kt = rho * t200["D"] ** 4 / (4 * math.pi ** 2)
    worst, moved, vmax = 0.0, 0.0, 0.0
    for ch, _, d in ev:
        if ch == "UVMS_TRUTH":
            t = uvms.truth_t.decode(d)
            for j in range(4, 8):
                w = t.motor_speed_rad_s[j]
                law = kt * t200["ct2"] * w * abs(w)
                worst = max(worst, abs(t.thrust_N[j] - law))
                moved = max(moved, abs(law))
        elif ch == "UVMS_ACTUATORS":
            a = uvms.actuators_t.decode(d)
            vmax = max([vmax] + [abs(a.motor_voltage_V[j]) for j in range(4, 8)])
    if not moved > 1e-3 or worst > 1e-9 * moved:
        fail(f"vertical T200 thrust vs its law: worst |T − law| {worst:.3g} N of {moved:.3g} N")
    if vmax > 16.0 * (1 + 1e-6):
        fail(f"a vertical motor's commanded |V| reached {vmax:.4g} V, above its 16 V supply")
    print(f"two thruster types: each thruster's set and bound in the log; vertical T200 thrust = "
          f"its law to {worst:.2e} N (up to {moved:.3g} N); vertical |V| ≤ {vmax:.3g} V")


def case_vehicle_description():
    """A vehicle described in the scenario (issue 30): sil/scenarios/vehicles/'s vectored
    eight-thruster layout, and a lighter body over --set. Both processes get the description:
    the controller's configuration and the plant's scene message in the log carry the layout
    given and the body; the run finishes at rank 6."""
    layout = os.path.join(SRC, "sil", "scenarios", "vehicles", "vectored_VII_stagnant.toml")
    out = os.path.join(TMP, "vehicle")
    body = ["vehicle.mass_kg=90", "vehicle.volume_m3=0.12", "vehicle.inertia_kg_m2=[15, 16, 18]"]
    args = ["run", layout, "--out", out, "--transport", "memq"] + SHORT
    for b in body:
        args += ["--set", b]
    run(args)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    if summary["status"] != "finished" or summary["alloc_min_rank"] != 6:
        fail(f"the vectored layout's run did not finish at rank 6: {summary['status']}")
    ev = log_events(os.path.join(out, "run.lcmlog"))
    cfg = uvms.controller_config_t.decode(next(d for ch, _, d in ev if ch == "UVMS_CONFIG"))
    scene = uvms.scene_t.decode(next(d for ch, _, d in ev if ch == "UVMS_SCENE"))
    c = math.sqrt(0.5)
    want_dir = [(c, -c, 0), (c, c, 0), (c, c, 0), (c, -c, 0), (0, 0, 1), (0, 0, 1), (0, 0, 1),
                (0, 0, 1)]
    want_pos = [(0.5, 0.5, 0), (0.5, -0.5, 0), (-0.5, 0.5, 0), (-0.5, -0.5, 0), (0.4, 0.5, -0.3),
                (0.4, -0.5, -0.3), (-0.4, 0.5, -0.3), (-0.4, -0.5, -0.3)]
    for name, msg in (("controller_config_t", cfg), ("scene_t", scene)):
        if msg.num_thrusters != 8:
            fail(f"{name}: {msg.num_thrusters} thrusters, expected 8")
        for j in range(8):
            for k in range(3):
                if abs(msg.thruster_direction[j][k] - want_dir[j][k]) > 1e-6 or \
                        abs(msg.thruster_position_m[j][k] - want_pos[j][k]) > 1e-6:
                    fail(f"{name}: thruster {j + 1} at {msg.thruster_position_m[j]} along "
                         f"{msg.thruster_direction[j]}, expected {want_pos[j]} along {want_dir[j]}")
    if abs(cfg.vehicle_mass_kg - 90) > 1e-9 or list(cfg.vehicle_inertia_kg_m2) != [15, 16, 18]:
        fail(f"controller_config_t: vehicle {cfg.vehicle_mass_kg} kg, {cfg.vehicle_inertia_kg_m2}")
    print(f"vectored layout and body in both processes; mean EE error "
          f"{summary['mean_ee_error_m'] * 1e3:.3f} mm, static allocation potential "
          f"{summary['alloc_static_potential'] * 100:.3f} %")
    check_thruster_types()
    # An arm of the scenario's own (two links): both processes run N = 2.
    arm = os.path.join(SRC, "sil", "scenarios", "vehicles", "planar_arm_VII_stagnant.toml")
    out = os.path.join(TMP, "arm")
    run(["run", arm, "--out", out, "--transport", "memq"] + SHORT)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    ev = log_events(os.path.join(out, "run.lcmlog"))
    cfg = uvms.controller_config_t.decode(next(d for ch, _, d in ev if ch == "UVMS_CONFIG"))
    scene = uvms.scene_t.decode(next(d for ch, _, d in ev if ch == "UVMS_SCENE"))
    truth = uvms.truth_t.decode([d for ch, _, d in ev if ch == "UVMS_TRUTH"][-1])
    if summary["status"] != "finished" or cfg.num_joints != 2 or scene.num_joints != 2:
        fail(f"two-link arm: {summary['status']}, {cfg.num_joints} and {scene.num_joints} joints")
    if list(scene.link_a_m[:2]) != [0.4, 0.3] or any(truth.joint_position_rad[2:]):
        fail(f"two-link arm: a = {scene.link_a_m[:2]}, joints past 2 = {truth.joint_position_rad[2:]}")
    print(f"two-link arm in both processes; mean EE error {summary['mean_ee_error_m'] * 1e3:.3f} mm")
    # The second vehicle (docs/MODEL.md §12): BlueROV2 Heavy + Alpha 5 at Earth gravity, both
    # processes, the first 3 s of its 20 s motion (its whole run is the campaign's): rank 6, no
    # saturation, no contact, the description in the controller's configuration.
    rov = os.path.join(SRC, "sil", "scenarios", "bluerov2", "bluerov2_heavy_alpha5.toml")
    out = os.path.join(TMP, "bluerov2")
    run(["run", rov, "--out", out, "--transport", "memq", "--set", "run.duration_s=3"])
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    ev = log_events(os.path.join(out, "run.lcmlog"))
    cfg = uvms.controller_config_t.decode(next(d for ch, _, d in ev if ch == "UVMS_CONFIG"))
    if summary["status"] != "finished" or summary["alloc_min_rank"] != 6 or \
            summary["saturated_ticks"] != 0 or not summary["min_clearance_m"] > 0:
        fail(f"BlueROV2: {summary['status']}, rank {summary['alloc_min_rank']}, "
             f"{summary['saturated_ticks']} saturated ticks, clearance {summary['min_clearance_m']}")
    want_dq = [141, 217, 190, 1.19, 0.47, 1.5]  # the float controller's config rounds to float
    if cfg.num_joints != 4 or any(abs(a - b) > 1e-6 * b for a, b in
                                  zip(cfg.vehicle_quadratic_damping, want_dq)):
        fail(f"BlueROV2: {cfg.num_joints} joints, D_Q {list(cfg.vehicle_quadratic_damping)}")
    if summary["ticks"] != 100 or not summary["max_vehicle_excursion_m"] < 0.01:
        fail(f"BlueROV2 case IV: {summary['ticks']} ticks, the vehicle moved "
             f"{summary['max_vehicle_excursion_m']} m while holding it")
    print(f"BlueROV2 Heavy + Alpha 5: mean EE error {summary['mean_ee_error_m'] * 1e3:.3f} mm, "
          f"max attitude error {summary['max_attitude_error_rad'] * 1e3:.1f} mrad, vehicle "
          f"excursion {summary['max_vehicle_excursion_m'] * 1e3:.2f} mm, E_p "
          f"{summary['propulsive_energy_J']:.1f} J")


def case_bad_scenario():
    path = os.path.join(TMP, "bad.toml")
    with open(path, "w") as f:
        f.write("# a scenario with a typo\n[run]\nduration_s = 2.0\n\n[control]\ncase = \"IV\"\n"
                "feedfoward = true\n")
    p = run(["run", path, "--out", os.path.join(TMP, "bad")], expect=1)
    if "bad.toml:7" not in p.stderr or "feedfoward" not in p.stderr:
        fail("the error does not name the file, line 7 and the key")
    if os.path.exists(os.path.join(TMP, "bad", "run.lcmlog")):
        fail("a rejected scenario still started a run")
    # A URL to publish on needs the URL to listen on, and two processes.
    for args in (["--publish-url", private_url()],
                 ["--url", private_url(), "--publish-url", private_url(), "--transport", "memq"]):
        p = run(["run", SCENARIO, "--out", os.path.join(TMP, "bad_urls")] + args, expect=2)
        if "--publish-url needs --url and --transport udpm" not in p.stderr:
            fail(f"uvms run {' '.join(args)}: the error does not say what --publish-url needs")


globals()["case_" + CASE]()
print("PASS", CASE)
