"""The trial screen's geometry (docs/spec.md, the study): 800 x 480 px, y down."""
import math

import numpy as np

WIDTH, HEIGHT = 800, 480
PATH_X0, PATH_LENGTH = 100.0, 600.0
PATH_Y0 = 240.0
RISE = {"top": -200.0, "middle": 0.0, "bottom": 200.0}   # T: the path ends at y = 240 + T
START_CENTRE = (60.0, 240.0)
START_RADIUS = 30.0
END_ZONE_X = 700.0
CHOICE_BOUNDARIES = (140.0, 340.0)  # halfway between the path ends


def path_y(x, target):
    """y(x) = -2T/L^3 (x-100)^3 + 3T/L^2 (x-100)^2 + 240 on [100, 700]."""
    t, l = RISE[target], PATH_LENGTH
    u = np.clip(np.asarray(x, float) - PATH_X0, 0.0, l)
    return -2.0 * t / l ** 3 * u ** 3 + 3.0 * t / l ** 2 * u ** 2 + PATH_Y0


def path_polylines(step=5.0):
    xs = np.arange(PATH_X0, PATH_X0 + PATH_LENGTH + step / 2, step)
    return [(xs, path_y(xs, t)) for t in RISE]


def in_start(x, y):
    return math.hypot(x - START_CENTRE[0], y - START_CENTRE[1]) <= START_RADIUS


def in_end_zone(x):
    return x > END_ZONE_X


def choice(crossing_y):
    """The chosen target is the path end nearest to where the finger crossed."""
    if crossing_y < CHOICE_BOUNDARIES[0]:
        return "top"
    if crossing_y < CHOICE_BOUNDARIES[1]:
        return "middle"
    return "bottom"


def target_end(target):
    return PATH_X0 + PATH_LENGTH, PATH_Y0 + RISE[target]
