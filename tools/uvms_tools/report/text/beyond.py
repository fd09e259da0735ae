# SPDX-License-Identifier: Apache-2.0
"""beyond: the section "Beyond the paper: Earth and Europa gravity, minimum-power allocation,
feedforward lead, a second vehicle" from the campaigns of sil/campaigns/beyond/
(beyond_gravity, beyond_allocation, beyond_lead, beyond_bluerov2). It follows
the paper's experiments and stays out of the scorecard and the headline, which answer the
paper's question under the paper's own conditions."""
from ..keys import BEYOND, KEY_KPN, KEY_PAYLOAD, KEY_TRIM_PAYLOAD
from ..load.logs import has
from ..load.overrides import same_value
from . import beyond_alloc, beyond_lead, beyond_vehicle, gravity_decomp
from .beyond_gravity import Grid, answer_part, ballast_line, metrics_part
from .common import campaign_comment
from .fmt import g

TITLE = ("## Beyond the paper: Earth and Europa gravity, minimum-power allocation, "
         "feedforward lead, a second vehicle")
INTRO = ("The paper's experiments run at g = 0 with the pseudoinverse allocation. Here the "
         "same maneuver is run at the gravity of Europa and of Earth, with the vehicle trimmed "
         "(docs/MODEL.md §6.3); with the minimum-power allocation min_power (the thrusts of "
         "least Σ|T|^1.5 that deliver the pseudoinverse's wrench, docs/MODEL.md §7.3) beside "
         "the pseudoinverse; and with the feedforward lead, which commands the feedforward "
         "ahead by the thrusters' lag (docs/MODEL.md §7.5), off and on. Every comparison is "
         "paired per seed (the same unsteady flow) and reported as mean ± half-width of the "
         "95 % CI over the seeds.")


def missing_campaigns(rep):
    """The campaigns of this section not found under the campaigns root."""
    return [n for n, _ in BEYOND if rep.exp(n) is None]


def _logged(e, key):
    """A field of the logged controller configuration of the campaign's first run, or None."""
    lg = e.log(e.one(), ["UVMS_CONFIG"]) if e.runs else None
    return float(lg["UVMS_CONFIG"][key][0]) if has(lg, "UVMS_CONFIG") else None


def _setup(rep, gr, ea):
    e = gr.e
    trimmed = all(same_value(e.value(r, KEY_TRIM_PAYLOAD), e.value(r, KEY_PAYLOAD))
                  for r in e.runs)
    kpn = _logged(e, "kpn_Nm_rad")
    kpn_a = _logged(ea, "kpn_Nm_rad") if ea is not None else None
    dflt = " (the default, the paper's)" if same_value(kpn_a, rep.schema.default(KEY_KPN)) else ""
    return [f"Attitude stiffness K_PN = {g(kpn, 4)} N·m/rad in the gravity campaign (logged "
            f"controller configuration"
            + (f"; {g(kpn_a, 4)} N·m/rad{dflt} in `beyond_allocation`" if kpn_a else "")
            + "). The vehicle is trimmed for the payload it carries"
            + (" (environment.trim_payload_kg = payload.mass_kg in every run)."
               if trimmed else " **except in some runs** (environment.trim_payload_kg ≠ "
                               "payload.mass_kg).") + " The g = 0 rows share the gains, "
            "payloads and flows (untrimmed: at g = 0 a ballast weighs nothing).", ""]


def section(rep):
    md = [TITLE, "", INTRO, ""]
    miss = missing_campaigns(rep)
    if miss:
        md += [f"*Not found among the campaign outputs: {', '.join(f'`{n}`' for n in miss)}; "
               f"the parts that need {'it are' if len(miss) == 1 else 'them are'} skipped.*", ""]
    eg, ea = rep.exp("beyond_gravity"), rep.exp("beyond_allocation")
    gr = Grid(eg) if eg is not None and eg.runs else None
    if gr is not None:
        md += campaign_comment(eg) + _setup(rep, gr, ea) + ballast_line(gr)
        md += metrics_part(rep, gr)
        md += answer_part(rep, gr)[0]
        md += gravity_decomp.section(rep) + gravity_decomp.t200_section(rep)
    if ea is not None or gr is not None:
        md += beyond_alloc.section(rep, ea, gr)
    md += beyond_lead.section(rep)
    md += beyond_vehicle.section(rep)
    return md
