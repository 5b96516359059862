"""The study design (docs/spec.md): 2 renderings x 3 strengths x 3 targets x
10 repetitions = 180 trials. Each rendering fills one 90-trial half, shuffled
as one set; the shuffle is seeded by the participant number; odd participants
start with the frictionmap, even ones with the heightmap; a pause after
trials 45, 90 and 135."""
import random

from .logs import RENDERINGS, STRENGTHS, TARGETS

REPETITIONS = 10
TRIALS = len(RENDERINGS) * len(STRENGTHS) * len(TARGETS) * REPETITIONS
PAUSE_AFTER = (45, 90, 135)


def rendering_order(participant):
    return ("frictionmap", "heightmap") if participant % 2 else ("heightmap", "frictionmap")


def order_name(participant):
    return "-".join(r[0] + "m" for r in rendering_order(participant))  # "fm-hm" or "hm-fm"


def plan(participant):
    """The 180 trials in presentation order: dicts trial, rendering, strength, target."""
    if not isinstance(participant, int) or participant < 1:
        raise ValueError("the participant number is a positive integer")
    rng = random.Random(participant)
    out = []
    for rendering in rendering_order(participant):
        half = [(s, t) for s in STRENGTHS for t in TARGETS for _ in range(REPETITIONS)]
        rng.shuffle(half)
        for s, t in half:
            out.append(dict(trial=len(out) + 1, rendering=rendering, strength=s, target=t))
    return out
