"""ff-analyse: participant folders -> figures and a one-page summary."""
import argparse
import datetime
import math
import os
import sys

import ff_files

from . import VERSION, analysis, figures, logs, stats

EPILOG = """\
Reads each folder's session.json, trials.csv, frames.csv and (if present)
exclusions.csv; writes to REPORT_DIR:
  summary.md                     one page: participants, cell means, ANOVAs, tests, learning fits
  fig11_hit_rates.png ... fig15_learning.png   the paper's figures
  participant_<n>.png            appendix-L panels per participant
Definitions: docs/experiment.md. Exit codes: 0 ok, 2 bad input (one line naming file and line).

example:
  ff-analyse logs/P01 logs/P02 logs/P03 -o report
"""


def parse(argv):
    ap = argparse.ArgumentParser(prog="ff-analyse", description="Analyse ff-experiment logs into the study's figures and statistics.",
                                 epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("folders", nargs="+", metavar="LOG_DIR", help="participant folder(s) written by ff-experiment")
    ap.add_argument("-o", "--output", required=True, metavar="REPORT_DIR", help="where the report goes (created)")
    ap.add_argument("--no-participant-pages", action="store_true", help="skip the appendix-L page per participant")
    return ap.parse_args(argv)


def summary_text(participants, group, figure_names):
    L = []
    L.append("# frictionfield study: summary")
    L.append("")
    L.append(f"ff-analyse {VERSION}, {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC; "
             f"{len(participants)} participant(s): " + ", ".join(
                 f"{p.number} ({p.order}, {len(p.trials)} trials, {len(p.excluded)} excluded)" for p in participants))
    L.append("")
    L.append("| measure | rendering | s=1.00 | s=0.66 | s=0.33 |")
    L.append("|---|---|---|---|---|")
    for m in analysis.MEASURES:
        y = analysis.cell_array(participants, m)
        for i, r in enumerate(analysis.RENDERINGS):
            cells = []
            for k in range(3):
                v = y[:, i, k]
                v = v[[not math.isnan(a) for a in v]]
                # the sample SD; one participant's value is shown alone
                cells.append(f"{v.mean():.2f} ± {stats.sample_sd(v):.2f}" if len(v) > 1 else
                             f"{v.mean():.2f}" if len(v) else "–")
            L.append(f"| {m.replace('_', ' ')} | {r} | " + " | ".join(cells) + " |")
    L.append("")
    L.append("Hit rate over all trials of a cell (30 per participant, chance 1/3); movement time and "
             "direction changes over correct trials. Mean ± SD over participants (sample SD, n − 1; "
             "a cell with one participant's value shows it alone).")
    for m in analysis.MEASURES:
        if m not in group["anova"]:
            continue
        L.append("")
        L.append(f"**{m.replace('_', ' ')}**, RM-ANOVA rendering × strength"
                 + (" with order between" if "group" in group["anova"][m] else "") + ":")
        for eff, r in group["anova"][m].items():
            L.append(f"- {eff}: {stats.format_f(r)}; GG: {stats.format_f(r, corrected=True)}")
        ph = "; ".join(f"{a} vs {b}: {stats.format_p(r['p_bonferroni'])}" for (a, b), r in group["posthoc"][m].items())
        L.append(f"- strength, Bonferroni paired t: {ph}")
        w = "; ".join(f"s={s}: {stats.format_p(r['p'])}" for s, r in group["wilcoxon"][m].items())
        L.append(f"- heightmap vs frictionmap, Wilcoxon per strength: {w}")
    L.append("")
    for r, d in group["blocks"].items():
        L.append(f"- {r}: hit rate block 1 vs 2 (45 trials each), Wilcoxon {stats.format_p(d['test']['p'])}")
    for r, d in group["learning"].items():
        a, b, c = d["fit"]
        if not (math.isfinite(b) and b > 1e-3 and a > 0):
            L.append(f"- {r}: movement time shows no power-law learning trend (fit degenerate: a = {a:.3g}, b = {b:.3g})")
            continue
        L.append(f"- {r}: movement time learning curve y = a·x^-b + c: a = {a:.2f}, b = {b:.3f}, c = {c:.2f} (start a+c = {a + c:.2f} s)")
    for n in group["notes"]:
        L.append(f"- note: {n}")
    L.append("")
    L.append("Figures: " + ", ".join(f"[{f}]({f})" for f in figure_names))
    return "\n".join(L) + "\n"


def run(argv):
    args = parse(argv)
    participants = []
    seen = {}
    for folder in args.folders:
        if not os.path.isdir(folder):
            raise logs.LogError(folder, 0, "not a folder")
        p = analysis.Participant(folder)
        if p.number in seen:
            raise logs.LogError(os.path.join(folder, "session.json"), 1,
                                f"participant {p.number} is also {seen[p.number]}")
        seen[p.number] = folder
        participants.append(p)
        torn = logs.torn_note(os.path.join(folder, "trials.csv"))
        if torn:  # left out by the reader; said here, so that an edited file's last trial is not lost unseen
            print(f"ff-analyse: {torn}: left out as an unfinished trial", file=sys.stderr)
    group = analysis.group_statistics(participants)
    os.makedirs(args.output, exist_ok=True)  # -o names the report's folder, made here (ff_files makes none)
    names = figures.group_figures(participants, group, args.output)
    if not args.no_participant_pages:
        for p in participants:
            name = f"participant_{p.number}.png"
            figures.participant_page(p, os.path.join(args.output, name))
            names.append(name)
    text = summary_text(participants, group, names)
    ff_files.write_whole(os.path.join(args.output, "summary.md"), lambda f: f.write(text))
    print(f"ff-analyse: {len(participants)} participant(s) -> {os.path.join(args.output, 'summary.md')}")
    return 0


def main(argv=None):
    try:
        return run(sys.argv[1:] if argv is None else argv)
    except logs.LogError as e:
        print(f"ff-analyse: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"ff-analyse: {ff_files.error_text(e)}", file=sys.stderr)
        return 2
