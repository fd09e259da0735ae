# SPDX-License-Identifier: Apache-2.0
"""headline: the answer — is holding the barycenter cheaper than holding the vehicle? —
over every comparison of every campaign, each configuration counted once."""
from ..analyses import headline as H
from ..analyses import paper, stats
from ..keys import BARY, VEH
from ..num import div
from .fmt import f, fmt_ci, fmt_dist, fmt_n, fmt_range, table

# Below this deviation from 1 a ratio's saving is called "small" in the headline (5 %).
RATIO_SMALL = 0.05

INTRO = [
    "Energy = thruster (electrical) energy E_el = ∫Σmax(V_j·I_j, 0) dt. Each comparison is a "
    "pair of runs that differ only in the stabilized point (case IV vs VII, or V vs "
    "VIII), paired per seed; verdict from the 95 % confidence interval of the paired "
    "ratio E(barycenter)/E(vehicle): *cheaper* if it lies entirely below 1, *dearer* "
    "if entirely above, else *no significant difference*; a deterministic (unseeded, "
    "stagnant) comparison is one exact number and its ratio decides.", "",
    "**Counting evidence.** Several campaigns contain the same configuration (e.g. "
    "experiment 1's condition (b) is experiment 2's condition C at 10 kg and "
    "experiment 4's U/ρ/α/- combination): a configuration is counted once, whichever "
    "campaigns ran it (same effective settings: base scenario, campaign settings and "
    "overrides with the documented defaults filled in, and the same seeds; or "
    "bit-identical per-seed energies). Every unsteady-flow comparison uses the same "
    "seeds, i.e. the same flow realisations, so comparisons of different "
    "configurations over those seeds are correlated, not independent samples.", ""]


def _primary(comps, unsteady):
    """Experiment 1's IV/VII comparison in one condition (by the runs' unsteady-flow value)."""
    return next((c for c in comps if c["exp"] == "exp1_cases"
                 and c["pair"] == f"{BARY}/{VEH}" and c["unsteady"] == unsteady), None)


def _paper_test(key_s, key_u):
    p11, p12 = paper.PAPER_TABLE_XI, paper.PAPER_TABLE_XII
    parts = []
    if key_s is not None and key_s["paired"].n:
        d = key_s["paired"].dist
        parts.append(f"{f(100 * (1 - d.mean), 1)} % less energy in stagnant flow (ratio "
                     f"{f(d.mean, 3)}, one deterministic run; the paper's Table XI: "
                     f"{f(100 * (1 - p11[BARY][1] / p11[VEH][1]), 1)} %)")
    if key_u is not None and key_u["paired"].n:
        d = key_u["paired"].dist
        ci = (f" (95 % CI {f(100 * (1 - d.hi), 1)}–{f(100 * (1 - d.lo), 1)} %)"
              if d.has_ci else "")
        parts.append(f"{f(100 * (1 - d.mean), 1)} %{ci} less under unsteady flow with "
                     f"density error (mean ratio {f(d.mean, 3)} {fmt_ci(d, 3)}, 95 % CI "
                     f"over {fmt_n(d)} seeds; barycenter cheaper in "
                     f"{key_u['paired'].n_below_1} of {d.n} seeds → {key_u['verdict']}; "
                     f"the paper's Table XII: "
                     f"{f(100 * (1 - p12[BARY][1] / p12[VEH][1]), 1)} %)")
    return ("- **The paper's own test** (experiment 1, vehicle IV vs barycenter "
            "VII: the primary evidence; every other seeded comparison reuses its "
            "seeds): the barycenter uses " + "; and ".join(parts) + ".")


def _seeds_text(comps, uniq, key_u):
    seedsets = sorted({c["seeds"] for c in uniq})
    shared = len(seedsets) == 1 and len(uniq) > 1
    ks = [c["paired"].n_below_1 for c in uniq]
    ns = sorted({c["paired"].n for c in uniq})
    sd = seedsets[0] if seedsets and seedsets[0] else ()
    if shared and sd:
        return (f" Every one of them runs over the same {len(sd)} seeds "
                f"(run.seed {sd[0]}–{sd[-1]}), so its seed pairs are shared with the "
                f"others (the {sum(1 for c in comps if c['exp'] == 'exp4_fidelity')} "
                f"unsteady rows of experiment 4 among them) and are not independent "
                f"evidence; per configuration the barycenter is cheaper in "
                f"{fmt_range(ks, 0)} of {'/'.join(map(str, ns))} seeds, and the "
                f"independent count is experiment 1's"
                + (f" {key_u['paired'].n_below_1} of {key_u['paired'].n}"
                   if key_u is not None else "") + ".")
    return (f" Barycenter cheaper in {fmt_range(ks, 0)} of "
            f"{'/'.join(map(str, ns))} seeds per configuration.")


def _flow_line(rep, unst, head, first, dup_of, key_u):
    comps = [c for c in rep.comparisons if c["unsteady"] == unst and c["paired"].n]
    if not comps:
        return []
    uniq = [c for c in comps if id(c) in first]
    dups = [c for c in comps if id(c) in dup_of]
    verd = H.verdict_counts(uniq)
    n, k = len(uniq), verd.get(stats.CHEAPER, 0)
    exps = sorted({c["exp"] for c in comps})
    txt = (f"- **{head}: {H.answer(k, n)}.** {len(comps)} comparisons in {len(exps)} "
           f"campaign{'s' if len(exps) > 1 else ''} are {n} distinct configurations"
           + (f" ({len(dups)} repeat a configuration counted elsewhere: "
              + "; ".join(f"{H.cmp_name(c)} = {H.cmp_name(dup_of[id(c)])}" for c in dups)
              + ")" if dups else "")
           + f". Mean ratio barycenter/vehicle "
             f"{fmt_range([c['paired'].dist.mean for c in uniq], 3)}; verdicts: "
           + H.verdict_text(verd) + f" (of {n} configurations).")
    if max(c["paired"].n for c in uniq) > 1:
        txt += _seeds_text(comps, uniq, key_u)
    else:
        txt += (" Deterministic runs: each ratio is one exact number, and the "
                "configurations are sweeps (payload, travel, duration, model options) "
                "around the same maneuvers, not replicates.")
    small = H.small_savings(uniq, RATIO_SMALL)
    if small:
        txt += (f" Of the cheaper ones, {len(small)} {'saves' if len(small) == 1 else 'save'} "
                f"less than {f(100 * RATIO_SMALL, 0)} %: "
                + "; ".join(f"{H.cmp_name(c)} ({f(c['paired'].dist.mean, 3)})" for c in small)
                + ".")
    others = [c for c in uniq if c["verdict"] != stats.CHEAPER]
    if others and k:
        txt += " Not cheaper: " + "; ".join(
            f"{H.cmp_name(c)} ({f(c['paired'].dist.mean, 3)})"
            for c in others[:6]) + (" …" if len(others) > 6 else "") + "."
    return [txt]


def _closing_lines(key_s, groups, notes):
    lines = []
    if key_s and "err_den" in key_s:
        lines.append(f"- Accuracy: in experiment 1 (stagnant) the mean EE error is "
                     f"{fmt_dist(key_s['err_den'], 2, 1e3)} mm for IV and "
                     f"{fmt_dist(key_s['err_num'], 2, 1e3)} mm for VII. docs/MODEL.md §1 "
                     f"states the paper's answer: barycenter stabilization uses markedly "
                     f"less energy with similar EE accuracy, provided feedback is present.")
    lost = sum(c["paired"].n_failed for g in groups for c in g[:1])
    lines.append("- Failed runs: " + (
        f"{lost} seed pairs of these configurations are incomplete because a run failed or "
        f"is missing (\"k failed\" next to each statistic; the runs are listed under "
        f"*Runs*)." if lost else
        "none: every run behind these comparisons finished."))
    return lines + [f"- Note: {x}" for x in notes]


def _table_row(comps, dup_of):
    label, pair = comps[0]["label"], comps[0]["pair"]
    comps = [c for c in comps if c["paired"].n]
    if not comps:
        return [label, pair, "0", "", "not measured", "", "", "", ""]
    ns = sorted({fmt_n(c["paired"].dist) for c in comps})
    if len(comps) == 1:
        d = comps[0]["paired"].dist
        rtxt = fmt_dist(d, 3) + (f" {fmt_ci(d, 3)}" if d.has_ci else "")
    else:
        rtxt = fmt_range([c["paired"].dist.mean for c in comps], 3) + \
            f" ({len(comps)} comparisons: " + ", ".join(c["sub"] for c in comps) + ")"
    err = ""
    if "err_den" in comps[0]:
        err = f"{fmt_dist(comps[0]['err_den'], 2, 1e3)} → {fmt_dist(comps[0]['err_num'], 2, 1e3)}"
    ks = [c["paired"].n_below_1 for c in comps]
    nn = sorted({c["paired"].n for c in comps})
    cheaper = (f"{ks[0]} of {nn[0]}" if len(comps) == 1 else
               f"{sum(ks)} of {len(comps)} comparisons (one run each)" if nn == [1] else
               f"{fmt_range(ks, 0)} of {'/'.join(map(str, nn))} per comparison (the "
               f"same seeds)")
    rep_ = [f"{c['sub'] or 'it'} = {H.cmp_name(dup_of[id(c)])}" for c in comps if id(c) in dup_of]
    return [label, pair, "/".join(ns), rtxt, H.verdict_text(H.verdict_counts(comps)), cheaper,
            err, "; ".join(rep_) or "—"]


def _per_experiment(rep, dup_of):
    rows = [_table_row(comps, dup_of) for comps in H.row_groups(rep.comparisons).values()]
    md = ["Per experiment (a configuration repeated in several campaigns appears in each "
          "of its rows, and is counted once above; the seeded rows share their seeds):", ""]
    return md + table(["comparison", "barycenter/vehicle", "seeds per comparison",
                       "E ratio: mean ± 95 % CI half-width [CI] (or range of means)", "verdicts",
                       "barycenter cheaper in (seed pairs)", "mean ε vehicle → barycenter [mm]",
                       "same configuration as (counted once)"], rows)


def section(rep):
    md = ["## Answer: is holding the barycenter cheaper than holding the vehicle?", ""]
    if not rep.comparisons:
        return md + ["No vehicle/barycenter pair was found in the campaigns.", ""]
    groups, notes = H.dedupe_comparisons(rep.comparisons, rep.defaults)
    first = {id(g[0]): g for g in groups}
    dup_of = {id(c): g[0] for g in groups for c in g[1:]}
    md += [f"Thruster drive of these runs: {rep.drive_text()} (docs/MODEL.md §5). " + INTRO[0]]
    md += INTRO[1:]
    key_s, key_u = _primary(rep.comparisons, False), _primary(rep.comparisons, True)
    lines = [_paper_test(key_s, key_u)] if key_s is not None or key_u is not None else []
    lines += ["- **The saving's size** in each reading of docs/MODEL.md §8 is in the answer box "
              "at the top and the scorecard's *The text's savings*."]
    for unst, head in ((False, "Without unsteady flow"),
                       (True, "With the unsteady flow of docs/MODEL.md §6.1")):
        lines += _flow_line(rep, unst, head, first, dup_of, key_u)
    lines += _closing_lines(key_s, groups, notes)
    return md + lines + [""] + _per_experiment(rep, dup_of)
