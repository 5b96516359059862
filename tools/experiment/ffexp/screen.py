"""What the participant sees (800 x 480, y down), drawn with the API pygame
2.6 and pygame-ce share."""
import csv
import io
import os
import subprocess

import numpy as np
import pygame

from . import geometry

BLACK = (0, 0, 0)
LIGHT_GREY = (200, 200, 200)
WHITE = (255, 255, 255)
GREEN = (40, 200, 60)
RED = (220, 40, 40)
FORCE_LIMIT_N = 0.5
FORCE_FULL_SCALE_N = 1.0


class Screen:
    def __init__(self, surface):
        self.surface = surface
        self.font = pygame.font.Font(None, 30)
        self.big = pygame.font.Font(None, 44)
        self.background = self._background()

    def _background(self):
        s = pygame.Surface((geometry.WIDTH, geometry.HEIGHT))  # black
        pygame.draw.rect(s, LIGHT_GREY, pygame.Rect(int(geometry.END_ZONE_X) + 1, 0,
                                                    geometry.WIDTH - int(geometry.END_ZONE_X) - 1, geometry.HEIGHT))
        pygame.draw.circle(s, LIGHT_GREY, (int(geometry.START_CENTRE[0]), int(geometry.START_CENTRE[1])),
                           int(geometry.START_RADIUS))
        for xs, ys in geometry.path_polylines(step=2.0):
            pygame.draw.lines(s, WHITE, False, list(zip(xs.tolist(), ys.tolist())), 3)
        return s

    def text(self, message, pos, font=None, colour=WHITE, centre=False):
        img = (font or self.font).render(message, True, colour)
        rect = img.get_rect(center=pos) if centre else img.get_rect(topleft=pos)
        self.surface.blit(img, rect)

    def force_indicator(self, force_n):
        """Top right: a bar for the pressing force, red above 0.5 N."""
        x, y, w, h = int(geometry.END_ZONE_X) - 170, 12, 150, 16
        pygame.draw.rect(self.surface, LIGHT_GREY, pygame.Rect(x, y, w, h), 1)
        if np.isfinite(force_n):
            frac = min(max(force_n / FORCE_FULL_SCALE_N, 0.0), 1.0)
            colour = RED if force_n > FORCE_LIMIT_N else GREEN
            pygame.draw.rect(self.surface, colour, pygame.Rect(x + 1, y + 1, int((w - 2) * frac), h - 2))
        limit_x = x + int(w * FORCE_LIMIT_N / FORCE_FULL_SCALE_N)
        pygame.draw.line(self.surface, WHITE, (limit_x, y - 3), (limit_x, y + h + 2), 1)

    def amplitude_bar(self, amplitude):
        """The simulator's rendered amplitude (no plate vibrates): bottom right."""
        if not np.isfinite(amplitude):
            return
        x, y, w, h = int(geometry.END_ZONE_X) - 170, geometry.HEIGHT - 26, 150, 12
        pygame.draw.rect(self.surface, (90, 90, 90), pygame.Rect(x, y, w, h), 1)
        pygame.draw.rect(self.surface, (80, 140, 255), pygame.Rect(x + 1, y + 1, int((w - 2) * min(max(amplitude, 0), 1)), h - 2))

    def trial(self, n, total, score, force_n, amplitude=None):
        self.surface.blit(self.background, (0, 0))
        self.text(f"Trial {n}/{total}   SCORE {score}", (geometry.WIDTH // 2, 20), centre=True)
        self.force_indicator(force_n)
        if amplitude is not None:
            self.amplitude_bar(amplitude)

    def feedback(self, n, total, score, force_n, hit, target, field=None):
        self.surface.blit(self.background, (0, 0))
        if field is not None:
            self.surface.blit(field, (0, 0))
        ex, ey = geometry.target_end(target)
        bar = pygame.Rect(int(geometry.END_ZONE_X) + 20, 0, 40, geometry.HEIGHT)
        pygame.draw.rect(self.surface, GREEN if hit else RED, bar)
        pygame.draw.circle(self.surface, (240, 190, 90), (int(ex) + 40, int(ey)), 18)  # the "cookie"
        self.text(f"Trial {n}/{total}   SCORE {score}", (geometry.WIDTH // 2, 20), centre=True)
        self.force_indicator(force_n)

    def message(self, title, lines=(), force_n=float("nan")):
        self.surface.fill(BLACK)
        self.text(title, (geometry.WIDTH // 2, 160), self.big, centre=True)
        for i, line in enumerate(lines):
            self.text(line, (geometry.WIDTH // 2, 220 + 34 * i), centre=True, colour=LIGHT_GREY)
        self.force_indicator(force_n)


def field_surface(binary, rendering, target, strength, step=8):
    """The rendered field from the core (ff-scene-render), as a translucent
    overlay: bright where the plate vibrates (slippery) moving right."""
    if binary is None or not os.access(binary, os.X_OK):
        return None
    cmd = [binary, "--scene", rendering, "--target", target, "--strength", f"{strength:g}", "--step", str(step)]
    r = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if r.returncode != 0:
        return None
    rows = [line for line in r.stdout.splitlines() if line and not line.startswith("#")]
    data = list(csv.DictReader(io.StringIO("\n".join(rows))))
    surf = pygame.Surface((geometry.WIDTH, geometry.HEIGHT), pygame.SRCALPHA)
    for d in data:
        a = float(d["amplitude"])
        x, y = float(d["x"]), float(d["y"])
        surf.fill((60, 120, 255, int(150 * a)), pygame.Rect(int(x - step / 2), int(y - step / 2), step, step))
    return surf
