"""What ff-track-bench --tune logs to stderr, read back and checked against its
own rules, recomputed here from the logged figures: a hill climb from the
recommended constants, two rounds of 81 direction-and-fade candidates around
the best so far and 3 position-filter candidates; a candidate "fits" when its
|lag| and frictionmap ratio are within bounds, is acceptable when it also
chatters at rest within the rest bound, and the best is the acceptable one
with the least heightmap ratio (the least heightmap + chatter while none is
acceptable); the trade-off lines pick, per chatter bound, the least heightmap
ratio among the candidates that fit."""
import itertools
import re

LINE = re.compile(r"^(start |dir   |pos   |<=[\d.]+|best  ) dir q=(\S+)\s+pos q=(\S+)\s+fade=([\d.]+)-([\d.]+) sigma "
                  r"maneuver=(\S+)/(\S+)ms  HM/thesis ([\d.]+) \(([^)]*)\)  \|lag\| ([\d.]+) ms  "
                  r"FM/thesis ([\d.]+)  rest ([\d.]+) \(([^)]*)\)(  \(lag or frictionmap constraint violated\))?$")
TRADE_OFF_BOUNDS = (0.005, 0.01, 0.02, 0.04, 0.08)
DIRECTION_GRID = list(itertools.product((0.7, 1.0, 1.4), (2.0, 2.5, 3.0), (2.0, 2.5, 3.0), (9.0, 12.0, 16.0)))
POSITION_FACTORS = (0.6, 1.5, 2.2)


def parse(stderr):
    out = []
    for line in stderr.splitlines():
        m = LINE.match(line)
        if m:
            g = m.groups()
            out.append(dict(stage=g[0].strip(), dir_q=float(g[1]), pos_q=float(g[2]), rest_sigmas=float(g[3]),
                            moving_sigmas=float(g[4]), threshold=float(g[5]), time_ms=float(g[6]), hm=float(g[7]),
                            hm_levels=[float(v) for v in g[8].split("/")], lag=float(g[9]), fm=float(g[10]),
                            rest=float(g[11]), rest_levels=[float(v) for v in g[12].split("/")],
                            flagged=g[13] is not None))
    return out


CONSTANTS = ("dir_q", "pos_q", "rest_sigmas", "moving_sigmas", "threshold", "time_ms")


def constants(c):
    return tuple(c[k] for k in CONSTANTS)


def check(test, stderr, rest_bound, max_lag_ms, max_fm_ratio, levels):
    lines = parse(stderr)
    candidates = [c for c in lines if c["stage"] in ("start", "dir", "pos")]
    test.assertEqual([c["stage"] for c in candidates], ["start"] + (["dir"] * 81 + ["pos"] * 3) * 2)
    test.assertEqual(constants(candidates[0]), (45, 750, 2.5, 5.0, 14, 12))  # recommended()'s
    for c in candidates:
        test.assertEqual(len(c["hm_levels"]), levels)
        test.assertAlmostEqual(c["hm"], sum(c["hm_levels"]) / levels, delta=6e-4)  # the mean over the sets
        test.assertEqual(c["rest"], max(c["rest_levels"]))  # the worst set
        if abs(c["lag"] - max_lag_ms) > 0.006 and abs(c["fm"] - max_fm_ratio) > 6e-4:  # clear of rounding
            test.assertEqual(c["flagged"], c["lag"] > max_lag_ms or c["fm"] > max_fm_ratio, c)

    def acceptable(c):
        return not c["flagged"] and c["rest"] <= rest_bound

    def score(c):  # from the per-set figures, printed to 4 places where the mean has 3
        heightmap = sum(c["hm_levels"]) / levels
        return heightmap if acceptable(c) else heightmap + c["rest"]

    def best_of(c, pool):
        """c is what `better` keeps of the pool, to the printed figures' rounding."""
        if any(acceptable(p) for p in pool):
            pool = [p for p in pool if acceptable(p)]
            return acceptable(c) and score(c) <= min(score(p) for p in pool) + 1.1e-4
        return score(c) <= min(score(p) for p in pool) + 2.1e-4

    def found(pool, **fixed):
        """The candidates of the pool with these constants (the log prints q to whole numbers)."""
        return [c for c in pool if all(abs(c[k] - v) <= 0.5 + 1e-9 for k, v in fixed.items())]

    # The climb, replayed: each round's grid lies around the best found before it,
    # and the position filter's candidates around the best of that grid.
    seen = [candidates[0]]
    rounds = (candidates[1:85], candidates[85:])
    for grid in rounds:
        centre_q = grid[27]["dir_q"]  # the grid's factor 1.0
        centres = found(seen, dir_q=centre_q, pos_q=grid[0]["pos_q"], time_ms=grid[0]["time_ms"])
        test.assertTrue(any(best_of(c, seen) for c in centres), (centre_q, grid[0]))
        for c, (qf, lo, width, threshold) in zip(grid[:81], DIRECTION_GRID):
            test.assertAlmostEqual(c["dir_q"], centre_q * qf, delta=1.0)
            test.assertEqual((c["pos_q"], c["rest_sigmas"], c["moving_sigmas"], c["threshold"], c["time_ms"]),
                             (grid[0]["pos_q"], lo, lo + width, threshold, grid[0]["time_ms"]))
        seen += grid[:81]
        first = grid[81]
        directions = found(seen, dir_q=first["dir_q"], rest_sigmas=first["rest_sigmas"],
                           moving_sigmas=first["moving_sigmas"], threshold=first["threshold"])
        test.assertTrue(any(best_of(c, seen) for c in directions), first)
        direction_q = [c["pos_q"] for c in directions if best_of(c, seen)]
        for c, qf in zip(grid[81:], POSITION_FACTORS):
            test.assertTrue(any(abs(c["pos_q"] - q * qf) <= 1.5 for q in direction_q), (c, direction_q))
            test.assertEqual(constants(c)[:1] + constants(c)[2:], constants(first)[:1] + constants(first)[2:])
        seen += grid[81:]
    logged_best = next(c for c in lines if c["stage"] == "best")
    test.assertTrue(found(seen, **dict(zip(CONSTANTS, constants(logged_best)))), logged_best)  # one of them
    test.assertTrue(best_of(logged_best, seen))

    test.assertIn("\ntrade-off (|lag| <= %g ms, frictionmap <= %gx the thesis pipeline's): rest chatter bound -> best\n"
                  % (max_lag_ms, max_fm_ratio), stderr)
    trade_off = {float(c["stage"][2:]): c for c in lines if c["stage"].startswith("<=")}
    for bound in TRADE_OFF_BOUNDS:
        fitting = [c for c in candidates if not c["flagged"] and c["rest"] <= bound]
        test.assertEqual(bound in trade_off, bool(fitting), bound)
        if fitting:
            pick = trade_off[bound]
            test.assertFalse(pick["flagged"])
            test.assertLessEqual(pick["rest"], bound)
            test.assertEqual(pick["hm"], min(c["hm"] for c in fitting))
    return logged_best
