# SPDX-License-Identifier: Apache-2.0
"""The reproduction scorecard as data (tools/uvms_tools/report/scorecard/), on synthetic campaigns
with known answers:

- Table XI's rows: one per case, quantity and reading (vehicle-reference cases once, for both
  readings; barycenter-reference cases in each reading), case I's zeros not tallied;
- scorecard.json: every row's verdict is re-decided from its own numbers (rows.evaluate_json);
  mutating one number flips its verdict (a magnitude, a ratio, the sign of a saving);
- causes: every row that is not reproduced has a cause, none is a bare "open"; a same-task
  ratio that differs while its same-motion twin is reproduced is attributed to the final pose;
- the markdown scorecard is generated from the rows (every row's value and verdict appear) and
  names the reading that reproduces each table; the tallies per reading count the rows;
- an unsteady row's dependence on the unprinted flow parameters: one entry per swept
  parameter (A_v, then n), each naming the values where the verdict holds.

Usage: test_scorecard.py SOURCE_DIR
"""
import copy
import json
import os
import sys

sys.path.insert(0, os.path.join(sys.argv[1], "tools"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checklist import Tally  # noqa: E402
from report_testkit import write_campaign  # noqa: E402
from uvms_tools.report.analyses import paper as P  # noqa: E402
from uvms_tools.report.analyses import stats  # noqa: E402
from uvms_tools.report.context import Report  # noqa: E402
from uvms_tools.report.load import schema as schema_mod  # noqa: E402
from uvms_tools.report.scorecard import flow, render, rows as R  # noqa: E402
from uvms_tools.report.scorecard.build import Scorecard  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

SCHEMA = schema_mod.from_file(os.path.join(sys.argv[1], "tests", "tools", "data",
                                           "schema_small.json"))
TALLY = Tally()
check = TALLY.check


STAGNANT = ["environment.unsteady_flow.enabled=false", "environment.density_error=false"]
VEHICLE_CASES = ("I", "IV", "V", "VI")
# Synthetic E_p [J]: the paper's Table XI energies with the same motion (so every same-motion
# ratio is the paper's), and the barycenter cases 25 % dearer with the same task (so those
# ratios differ from the paper's by more than the 0.05 tolerance).
E_MOTION = {c: P.PAPER_TABLE_XI[c][1] for c in P.PAPER_TABLE_XI}
E_TASK = {c: e * (1.0 if c in VEHICLE_CASES else 1.25) for c, e in E_MOTION.items()}


def run_row(c, energy):
    return {"propulsive_energy_J": energy, "thruster_energy_J": 2000.0 * energy,
            "mean_ee_error_m": P.PAPER_TABLE_XI[c][0] * 1e-3}


tmp = scratch_dir("uvms-scorecard-")  # removed at exit (tests/support/scratch.py)


def steps():
    root = os.path.join(tmp, "camp")
    write_campaign(os.path.join(root, "exp1_cases"), "exp1_cases", [
        (f"{c}_stagnant", [f'control.case="{c}"'] + STAGNANT, run_row(c, E_TASK[c]))
        for c in P.PAPER_TABLE_XI])
    write_campaign(os.path.join(root, "exp1_cases_same_motion"), "exp1_cases_same_motion", [
        (f"{c}_stagnant", [f'control.case="{c}"', 'trajectory.theta_final_deg="vehicle"']
         + STAGNANT, run_row(c, E_MOTION[c]))
        for c in P.PAPER_TABLE_XI if c not in VEHICLE_CASES])
    out = os.path.join(tmp, "out")
    os.makedirs(out)
    rep = Report(root, out, SCHEMA)
    card = Scorecard(rep)
    card.build()
    xi = [r for r in card.rows if r.reference == "Table XI"]
    # Vehicle cases: ε, E_p, E/E(IV) once (IV: no ratio) = 3 + 2 + 3 + 3; barycenter: 3 × 2 × 4.
    check(len(xi) == 11 + 24, f"Table XI: 35 rows (got {len(xi)})")
    check({r.reading for r in xi if r.row in ("case IV", "case V")} == {R.BOTH}
          and {r.reading for r in xi if r.row == "case VII"} == set(R.READINGS),
          "vehicle cases once for both readings, barycenter cases in each reading")
    excl = [r for r in xi if r.excluded]
    check(len(excl) == 2 and all(r.row == "case I" for r in excl),
          f"case I's energy and ratio are not tallied ({[(r.row, r.quantity) for r in excl]})")
    ratio = {(r.row, r.reading): r for r in xi if r.quantity == "E_p/E_p(IV)"}
    vm, vt = ratio[("case VII", "same motion")], ratio[("case VII", "same task")]
    check(vm.verdict == stats.REPRODUCED and abs(vm.ours.estimate - 0.1946 / 0.3391) < 1e-12,
          f"same-motion VII/IV is the paper's ratio: reproduced ({vm.verdict})")
    check(vt.verdict == stats.SAME_DIRECTION and "final pose" in vt.cause,
          f"same-task VII/IV 25 % higher: same direction, attributed to the final pose "
          f"({vt.verdict}: {vt.cause[:60]})")

    # scorecard.json: every verdict re-decided from the row's own numbers.
    path = card.write_json(out)
    doc = json.load(open(path))
    check(len(doc["rows"]) == len(card.rows), "scorecard.json has every row")
    keys = {"reference", "row", "quantity", "reading", "paper", "ours", "verdict", "cause"}
    check(all(keys <= set(o) for o in doc["rows"]), "every row names reference, row, quantity, "
          "reading, paper, ours (mean, CI, n), verdict and cause")
    same = [R.evaluate_json(o) == o["verdict"] for o in doc["rows"]]
    check(all(same), f"every verdict follows from its row ({same.count(False)} do not)")

    def mutated(pred, change):
        o = copy.deepcopy(next(o for o in doc["rows"] if pred(o)))
        before = R.evaluate_json(o)
        change(o)
        return before, R.evaluate_json(o)

    b, a = mutated(lambda o: o["row"] == "case IV" and o["quantity"] == "mean EE error ε",
                   lambda o: o["ours"].update(mean=2.0 * o["paper"]))
    check(b == stats.REPRODUCED and a == stats.DIFFERS, f"ε doubled: {b} → {a}")
    b, a = mutated(lambda o: o["row"] == "case VII" and o["quantity"] == "E_p/E_p(IV)"
                   and o["reading"] == "same task", lambda o: o["ours"].update(mean=o["paper"]))
    check(b == stats.SAME_DIRECTION and a == stats.REPRODUCED,
          f"same-task ratio set to the paper's: {b} → {a}")
    b, a = mutated(lambda o: o["row"] == "case VII" and o["quantity"] == "E_p/E_p(IV)"
                   and o["reading"] == "same motion", lambda o: o["ours"].update(mean=1.02))
    check(b == stats.REPRODUCED and a == stats.DIFFERS,
          f"a ratio on the other side of 1 differs, whatever the tolerance: {b} → {a}")
    b, a = mutated(lambda o: o["row"] == "case II" and o["quantity"] == "energy E_p"
                   and o["reading"] == "same motion",
                   lambda o: o["ours"].update(mean=-o["ours"]["mean"]))
    check(b == stats.REPRODUCED and a == stats.DIFFERS, f"an energy of the wrong sign: {b} → {a}")

    # Causes.
    bad = [(o["row"], o["quantity"], o["cause"]) for o in doc["rows"]
           if o["verdict"] != stats.REPRODUCED and not o["excluded"]
           and (o["cause"] in ("", "—") or o["cause"].strip().lower() == "open")]
    check(not bad, f"every difference has a cause, none a bare 'open' ({bad[:2]})")

    # Markdown from the rows.
    md = "\n".join(render.markdown(card))
    check(all(render.ours_text(r) in md for r in card.rows),
          "the markdown shows every row's value (generated from the rows)")
    check("Table XI: **same motion** reproduces it best" in md,
          "the markdown names the reading that reproduces Table XI")
    t_m, t_t = card.tally("same motion"), card.tally("same task")
    n_rows = sum(1 for r in card.rows if not r.excluded and r.reading in ("same motion", R.BOTH))
    check(sum(t_m.values()) == n_rows and t_m[stats.REPRODUCED] > t_t[stats.REPRODUCED],
          f"tallies per reading count their rows (same motion {t_m}, same task {t_t})")

    flow_sweeps(root, out)


UNSTEADY = ["environment.unsteady_flow.enabled=true", "environment.density_error=true"]


def flow_sweeps(root, out):
    """Case IV's ε is Table XII's at every A_v, but only at n = 1 and 2 (three times it at
    n = 5 and 10): the row's dependences say so, per parameter."""
    eps_iv = P.PAPER_TABLE_XII["IV"][0] * 1e-3

    def runs(key, values, eps_of):
        return [(f"{key[-4:]}{v}_{c}_s{s}",
                 [f'control.case="{c}"', 'trajectory.theta_final_deg="auto"', f"{key}={v}",
                  f"run.seed={s}"] + UNSTEADY,
                 {"propulsive_energy_J": P.PAPER_TABLE_XII[c][1] * (1 + 0.01 * s),
                  "mean_ee_error_m": eps_of(v) * (1 + 0.01 * s)})
                for v in values for c in ("IV", "VII") for s in (1, 2, 3)]
    write_campaign(os.path.join(root, flow.EXP), flow.EXP,
                   runs(flow.KEY_AV, (0.005, 0.01), lambda a: eps_iv))
    write_campaign(os.path.join(root, flow.EXP_N), flow.EXP_N,
                   runs(flow.KEY_N, (1, 2, 5, 10), lambda n: eps_iv * (1 if n <= 2 else 3)))
    rep = Report(root, out, SCHEMA)
    sw = flow.load(rep)
    check(sw is not None and sw.harmonics is not None, "both flow sweeps load")
    dep = flow.depends(sw, True, "IV", "same task")["eps"]
    check([d["parameter"] for d in dep] == [flow.KEY_AV, flow.KEY_N],
          f"ε depends on A_v and on n, one entry each ({[d['parameter'] for d in dep]})")
    check(dep[0]["holds_for"] == [0.005, 0.01] and dep[1]["holds_for"] == [1.0, 2.0]
          and dep[1]["swept"] == [1.0, 2.0, 5.0, 10.0],
          f"the verdict holds at every A_v and at n = 1, 2 only ({dep[0]['holds_for']}, "
          f"{dep[1]['holds_for']})")
    check("n in [1, 2]" in flow.note(dep), f"the note names the range of n ({flow.note(dep)})")


sys.exit(TALLY.run(steps, tmp))
