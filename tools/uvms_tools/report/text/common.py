# SPDX-License-Identifier: Apache-2.0
"""common: Markdown pieces every section uses."""
from ..load.overrides import finished, seed_of


def status_mark(run):
    """'' for a finished run, ' (missing)' or ' (status: failure)' otherwise."""
    if run is None:
        return " (missing)"
    return "" if finished(run) else f" ({run.get('status')}: {run.get('failure')})"


def img(md, path, caption):
    """Append a figure with its caption."""
    md += [f"![{caption}]({path})", "", f"*{caption}*", ""]


def missing(name):
    return [f"*Experiment `{name}` was not found among the campaign outputs: this section "
            f"is skipped.*", ""]


def campaign_comment(e):
    """The campaign file's leading comment, quoted."""
    return [f"*Campaign file:* {e.comment}", ""] if e.comment else []


def open_experiment(rep, name):
    """(experiment, first lines of its section): the campaign's comment, or (None, the note
    that it is missing)."""
    e = rep.exp(name)
    return (None, missing(name)) if e is None else (e, campaign_comment(e))


def seeds_text(e, cond):
    """'20 runs, seeds 1–20', 'one run' or 'n runs'."""
    runs = e.select(cond)
    n = len(runs)
    seeds = sorted({seed_of(r) for r in runs if seed_of(r) is not None})
    if n <= 1:
        return "one run"
    return (f"{n} runs, seeds {seeds[0]}–{seeds[-1]}" if seeds and len(seeds) == n
            else f"{n} runs")


def switches_text(cfg):
    """Table X meaning from the logged controller configuration (controller_config_t)."""
    att = int(cfg["attitude_control"][0])
    ref = "barycenter" if int(cfg["position_reference"][0]) == 1 else "vehicle"
    ff = int(cfg["position_feedforward"][0])
    fb = int(cfg["position_feedback"][0])
    if not att and not ff and not fb:
        return "no control (thrusters idle)"
    return (f"attitude {'on' if att else 'off'}, {ref} ref., FF {'on' if ff else 'off'}, "
            f"FB {'on' if fb else 'off'}")
