# SPDX-License-Identifier: Apache-2.0
"""choices: the modeling choices the source left open, with the values these runs used (the
logged controller configuration, the runs' overrides) and the schema's defaults."""
import math

import numpy as np

from ..analyses.delay import rms
from ..keys import BARY, COND_EXP1_KEYS, KEY_CASE, KEY_COEFF_TABLE
from ..load.logs import has
from ..load.overrides import seed_of
from .checks import final_pose_miss
from .choices_runs import campaign_rows, thruster_rows
from .fmt import f, g, mm, table
from .settings import coeff_rows, default_text, overridden_text, where_set

INTRO = ["## Modeling choices the source left open", "",
         "What the paper leaves open and this project chose (docs/MODEL.md), with the values "
         "read from the runs' logged controller configuration, the campaign and "
         "scenario files, and the documented defaults.", ""]


def v3(a):
    return "(" + ", ".join(g(x, 4) for x in np.asarray(a).ravel()) + ")"


def _logged(rep):
    """The logged configurations of experiment 1's VII runs (stagnant, unsteady: lowest seed)
    and the unsteady run with its log."""
    e1 = rep.exp("exp1_cases") or rep.exp("exp3_tracking")
    if e1 is None:
        return dict(e1=None, cfg_s=None, cfg_u=None, log_u=None, ru=None)
    rs = e1.one(dict(COND_EXP1_KEYS["stagnant"], **{KEY_CASE: BARY}))
    ru = e1.one(dict(COND_EXP1_KEYS["unsteady"], **{KEY_CASE: BARY}))
    return dict(e1=e1, cfg_s=e1.logged_config(rs) if rs else None,
                cfg_u=e1.logged_config(ru) if ru else None, log_u=e1.log(ru) if ru else None,
                ru=ru)


def _vehicle_rows(cfg, cfg_s, cfg_u):
    derr = ""
    if cfg_s is not None and cfg_u is not None:
        rho_u, rho_s = float(cfg_u["density_kg_m3"][0]), float(cfg_s["density_kg_m3"][0])
        derr = f"{f(100 * (1 - rho_u / rho_s), 1)} % "
    m0 = float(cfg["vehicle_mass_kg"][0])
    side = math.sqrt(6.0 * float(cfg["vehicle_inertia_kg_m2"][0][0]) / m0)
    return [
        ["gravity", f"g = {v3(cfg['gravity_m_s2'][0])} m/s² (logged config) — docs/MODEL.md §6.3: "
         f"the paper's energies and its insensitivity to a {derr}density error are only "
         "consistent with negligible net weight/buoyancy loads (a real vehicle is trimmed "
         "neutral; the paper's volumes are not)", "§6.3"],
        ["vehicle drag coefficient CD0", f"{g(cfg['vehicle_drag_coeff'][0], 4)} "
         "(logged config); not printed in the paper, the value consistent with its "
         "analytic results", "§3.2"],
        ["vehicle inertia", f"diag{v3(cfg['vehicle_inertia_kg_m2'][0])} kg·m² "
         f"(logged config): not in the paper; that of a uniform cube of side "
         f"√(6·I/m0) = {f(side, 2)} m and m0 = {g(m0, 4)} kg", "§3.2"],
        ["vehicle center of buoyancy", f"{v3(cfg['vehicle_cob_m'][0])} m from the "
         "CoM (logged config)", "§3.2"]]


def _flow_row(rep, lg):
    sch = rep.schema
    seeds = sorted({seed_of(r) for e in rep.exps.values() for r in e.runs
                    if seed_of(r) is not None})
    seed_txt = (f"seeds {seeds[0]}–{seeds[-1]} (run.seed replicates: every unsteady "
                f"condition is a distribution over seeds, docs/MODEL.md §10)" if len(seeds) > 1 else
                f"seed = {seeds[0] if seeds else default_text(sch, 'run.seed')} (one seed per "
                f"condition: an anecdote, docs/MODEL.md §10)")
    amp, harm = ("environment.unsteady_flow.amplitude_m_s", "environment.unsteady_flow.harmonics")
    txt = (f"A_v = {default_text(sch, amp)} m/s, n = {default_text(sch, harm)} harmonics per "
           f"axis, period t_F = run duration (documented defaults"
           + overridden_text(rep.exps, amp, harm) + "); " + seed_txt)
    if has(lg["log_u"], "UVMS_TRUTH"):
        fl = lg["log_u"]["UVMS_TRUTH"]["flow_velocity_m_s"]
        txt += (f"; measured in exp1 VII unsteady (seed {seed_of(lg['ru'])}): RMS per axis "
                f"{v3(rms(fl) * 1e3)} mm/s, peak |v∞| "
                f"{f(np.max(np.linalg.norm(fl, axis=1)) * 1e3, 1)} mm/s."
                " The paper gives neither A_v nor n; only the plant sees the unsteady part")
    return ["unsteady flow [28]", txt, "§6.1"]


def _coeff_row(rep):
    ct = coeff_rows(rep.schema.default(KEY_COEFF_TABLE))
    ct_txt = ("; ".join(f"{g(d, 3)} d_L: drag ×{g(dr, 3)}, added mass ×{g(am, 3)}"
                        for d, dr, am in ct) if ct else
              f"not given by the configuration schema ({KEY_COEFF_TABLE})")
    over = where_set(rep.exps, {KEY_COEFF_TABLE})
    return ["variable hydrodynamic coefficients", "plant only (the firmware model keeps "
            f"constant coefficients); default table, an **approximation** of McLain & Rock "
            f"(1998) (plant DefaultCoeffTable()): {ct_txt}"
            + (f" (overridden: {'; '.join(over)})" if over else "")
            + "; used in experiments 4 (swept), 5 and 6", "§6.4"]


def _environment_rows(rep, lg):
    cfg_s, cfg_u = lg["cfg_s"], lg["cfg_u"]
    cfg = cfg_s if cfg_s is not None else cfg_u
    rows = [_flow_row(rep, lg)]
    if cfg_s is not None and cfg_u is not None:
        rows.append(["density error", f"controller model ρ = {g(cfg_u['density_kg_m3'][0], 5)} "
                     f"kg/m³ under density error, {g(cfg_s['density_kg_m3'][0], 5)} kg/m³ "
                     "otherwise (logged configs); the plant always uses the latter "
                     "(docs/MODEL.md §3.2)", "§6.2"])
    if cfg is not None:
        rows.append(["angle of attack [21]", f"{'on' if int(cfg['angle_of_attack'][0]) else 'off'} "
                     "in experiments 1–3, 5–8 (logged config, C_D = C_D0L·sin²α, in plant "
                     "and model); swept in experiment 4", "§4"])
    return rows + [_coeff_row(rep)]


def column_check(rep):
    """SPEC §8: every final column should put the EE at the same inertial point."""
    rows = [[f(p, 0), mm(d, 1)] for p, d in final_pose_miss(rep).items()]
    if not rows:
        return []
    return (["**docs/MODEL.md §8 final-pose check.** The barycenter columns of the joint "
             "table (docs/MODEL.md §8, the paper's) are meant to put the EE at the same "
             "inertial point as the vehicle column. Distance between the final EE positions "
             "of VII and IV (experiment 2, condition A, summary.json):", ""]
            + table(["m_P [kg] (column)", "|p_EE(VII) − p_EE(IV)| at the end [mm]"], rows))


def section(rep):
    lg = _logged(rep)
    cfg = lg["cfg_s"] if lg["cfg_s"] is not None else lg["cfg_u"]
    rows = _vehicle_rows(cfg, lg["cfg_s"], lg["cfg_u"]) if cfg is not None else []
    rows += _environment_rows(rep, lg)
    if cfg is not None:
        rows += thruster_rows(rep, cfg, lg["e1"])
    rows += campaign_rows(rep)
    md = table(["choice", "what these runs used", "docs/MODEL.md"], rows)
    return INTRO + md + column_check(rep)
