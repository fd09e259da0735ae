# SPDX-License-Identifier: Apache-2.0
"""context: the state one report is built from and accumulates: the schema, the campaigns,
the figure writer, and what the sections hand on to the scorecard, the headline and the
observations (comparisons, notes, tracking and motor results, analytic limits)."""
import os
from collections import Counter

from .analyses import energy, stats
from .figures.common import Figures
from .keys import BARY, E_EL, E_P, ERR, KEY_CASE, KEY_PAYLOAD, KEY_RHO, KEY_UNSTEADY, VEH
from .keys import KEY_AOA, KEY_DENSITY, KEY_VARC
from .load.logs import has
from .load.runs import discover
from .num import isnum

# Keys the report selects runs by: the schema must give their defaults.
SELECTION_KEYS = (KEY_UNSTEADY, KEY_DENSITY, KEY_AOA, KEY_VARC, KEY_PAYLOAD)


class Report:
    """root: the campaigns root; out_dir: where report.md and figures/ go; schema:
    load.schema.Schema (every default of a key a run does not set)."""

    def __init__(self, root, out_dir, schema):
        schema.require_defaults(SELECTION_KEYS)
        self.root = os.path.abspath(root)
        self.out = os.path.abspath(out_dir)
        self.schema = schema
        self.defaults = schema.defaults()
        self.exps = discover(self.root, self.defaults)
        self.figs = Figures(self.out)
        self.comparisons = []   # headline entries (dicts, see add_comparison)
        self.notes = []         # observations for the closing section
        self.track_summary = {}  # experiment 3: run -> RMS|F_des − F_prod| / RMS|F_des|
        self.track_lags = []     # experiment 3: (case, cond), best delay [s]
        self.split_summary = {}  # experiment 3, stagnant: case -> (∫Σ|P_pos|, ∫Σ|P_att|)
        self.energy_info = {}
        self.motor = None
        self.analytic_limits = None
        self.exp8b = None
        self.scorecard = None
        self.prop_from_logs = False
        self._prop = {}

    def exp(self, name):
        return self.exps.get(name)

    # -- drive
    def drives(self):
        return Counter(r.get("drive") for e in self.exps.values() for r in e.runs)

    def drive(self):
        """The drive of the runs ("current", "voltage"), "mixed", or None (not recorded)."""
        d = {k for k in self.drives() if k}
        if not d:
            return None
        return d.pop() if len(d) == 1 else "mixed"

    def drive_text(self):
        d = self.drive()
        if d is None:
            return ("not recorded in summary.json (runs of a build without the drive setting, "
                    "whose only power stage was the voltage drive)")
        if d == "mixed":
            return "mixed: " + ", ".join(f"{k} ({n} runs)" for k, n in self.drives().items() if k)
        return f"**{d}** drive"

    # -- metrics
    def metric(self, e, name):
        """A metric for Experiment.series: the summary field; for the propulsive energy, when
        summary.json lacks it (older builds), computed from the truth log (SPEC §5) with the
        run's plant density (its override, else the schema's default)."""
        if name != E_P:
            return name

        def prop(run):
            v = run.get(E_P)
            if isnum(v):
                return float(v)
            key = (e.name, run.get("id"))
            if key not in self._prop:
                self._prop[key] = self._prop_from_log(e, run)
            return self._prop[key]
        return prop

    def _prop_from_log(self, e, run):
        lg = e.log(run, ["UVMS_TRUTH", "UVMS_CONFIG"])
        rho = e.value(run, KEY_RHO)
        if not has(lg, "UVMS_TRUTH", "UVMS_CONFIG") or not isnum(rho):
            return None
        tr = lg["UVMS_TRUTH"]
        self.prop_from_logs = True
        return energy.propulsive_from_truth(tr["t_s"], tr["thrust_N"], float(rho),
                                            float(lg["UVMS_CONFIG"]["propeller_diameter_m"][0]))

    # -- headline comparisons
    def add_comparison(self, exp, label, cond_common, row=None, sub="", num=BARY, den=VEH,
                       with_err=False):
        """Record a barycenter-vs-vehicle comparison (paired per seed) for the headline and
        return its stats.Paired. cond_common: the override values both sides share; row: those
        that define its row in the per-experiment table (default cond_common). Whether it is an
        unsteady-flow comparison comes from the runs' own values of the key."""
        e = self.exp(exp)
        cn, cd = dict(cond_common, **{KEY_CASE: num}), dict(cond_common, **{KEY_CASE: den})
        pa = e.paired(E_EL, cn, cd)
        # What identifies the configuration (for counting evidence once, the headline): the
        # vehicle run's effective settings without case and seed, and the per-seed energies.
        den_runs = e.slots(cd)
        num_runs = e.slots(cn)
        rep_run = next(iter(den_runs.values()), None)
        num_s, den_s = e.series(E_EL, cn), e.series(E_EL, cd)
        flows = {bool(e.value(r, KEY_UNSTEADY)) for r in [*den_runs.values(), *num_runs.values()]}
        ent = dict(exp=exp, label=label, sub=sub, row=cond_common if row is None else row,
                   cond=dict(cond_common), unsteady=any(flows), paired=pa, pair=f"{num}/{den}",
                   verdict=stats.compare(pa), config=e.config(rep_run) if rep_run else {},
                   seeds=tuple(sorted(s for s in den_runs if s is not None)),
                   energies=tuple((s, num_s[s], den_s[s]) for s in pa.seeds))
        if with_err:
            ent["err_den"] = e.dist(ERR, cd)
            ent["err_num"] = e.dist(ERR, cn)
        self.comparisons.append(ent)
        return pa
