"""The accuracy bench's set-up: the methods compared, the five scenes they strike, the effects timed."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from pool_env.physics import BALL_MASS, BALL_RADIUS, SEED_MASS, SEED_RADIUS, Balls, Physics, Table, rack, strike

# The cue is a 5 ms push (the report's eq. 2.1); force = m v / 5 ms gives the speed v.
CONTACT = 0.005

# (label, simulate options); the second is the seed report's own method (section 3.1.2).
METHODS = (
    ("a posteriori", {"detection": "posteriori"}),
    ("a priori (report)", {"detection": "priori"}),
    ("a priori + re-check", {"detection": "priori", "recheck": True}),
)
REPORT_METHOD = "a priori (report)"
# The report's model and scene (Physics.seed(), Table.seed(), its ball) for its own loop
# (method="seed") beside the report's detection with exact motion (method="fixed"):
# (label, method, options).
SEED_METHODS = (
    ("a priori (report)", "fixed", {"detection": "priori"}),
    ("report's loop", "seed", {}),
)
REPORT_LOOP = "report's loop"
REGULATION = (BALL_RADIUS, BALL_MASS)  # (radius m, mass kg)
REPORT_BALL = (SEED_RADIUS, SEED_MASS)  # the report's table 3.1: 2.5 cm, 0.15 kg
WITHIN = 1e-3  # "within 1 mm": the break's mean final position error


def _unit(v):
    v = np.asarray(v, dtype=np.float64)
    return v / math.hypot(*v)


def _rotate(v, degrees):
    a = math.radians(degrees)
    return np.array([math.cos(a) * v[0] - math.sin(a) * v[1], math.sin(a) * v[0] + math.cos(a) * v[1]])


def _shot(xy, aim, speed, run, offset, table, ball):
    """Strike ball 0 along `aim` at `speed`; run k backs the cue ball off 2.9 mm per k along the
    aim (same geometry, contacts at another phase of the frame grid). `ball` = (radius, mass)."""
    aim = _unit(aim)
    xy = np.array(xy, dtype=np.float64)
    xy[0] -= aim * 0.0029 * run
    balls = Balls(xy, radius=ball[0], mass=ball[1])
    offset = (0.0, 0.0) if offset is None else offset
    return strike(balls, force=aim * speed * ball[1] / CONTACT, offset=offset), table


# Every scene: (speed m/s, run, offset or None for the scene's own hit, table or None for the
# eight-foot table, ball (radius, mass)) -> (struck Balls, table).

def single(speed, run, offset=None, table=None, ball=REGULATION):
    """One ball from near the head rail, a little draw unless told: slides, rolls, stops (friction only)."""
    return _shot([[0.35, 0.45]], (1.0, 0.2), speed, run, (0.0, -0.3) if offset is None else offset, table, ball)


def cut(speed, run, offset=None, table=None, ball=REGULATION):
    """A 30 degree cut of an object ball into the far corner pocket, cue ball 0.7 m away."""
    obj, pocket = np.array([1.80, 0.80]), np.array([2.24, 1.12])
    u = _unit(pocket - obj)
    ghost = obj - 2 * ball[0] * u
    cue = ghost - 0.7 * _rotate(u, 30.0)
    # Aimed 3 mm off the ghost ball: the frictional model throws the object ball off the line
    # of centres, and this aim drops it at both speeds.
    aim = ghost + 0.003 * np.array([-u[1], u[0]]) - cue
    return _shot([cue, obj], aim, speed, run, offset, table, ball)


def bank(speed, run, offset=None, table=None, ball=REGULATION):
    """A full-ball hit banking the object ball off the near long rail into the far corner."""
    obj, pocket = np.array([1.45, 0.40]), np.array([2.24, 1.12])
    # Aim at the pocket's mirror image in the rail, moved 4 cm along it for the cushion's
    # non-mirror rebound (restitution and friction).
    u = _unit(np.array([pocket[0] + 0.04, 2 * ball[0] - pocket[1]]) - obj)
    cue = obj - (2 * ball[0] + 0.5) * u
    return _shot([cue, obj], u, speed, run, offset, table, ball)


def combination(speed, run, offset=None, table=None, ball=REGULATION):
    """Three balls: the cue ball sends ball 1 into ball 2, which drops in the far corner."""
    b2, pocket = np.array([1.85, 0.86]), np.array([2.24, 1.12])
    u2 = _unit(pocket - b2)
    d1 = _rotate(u2, 4.0)
    b1 = b2 - 2 * ball[0] * u2 - 0.25 * d1
    ghost1 = b1 - 2 * ball[0] * d1
    cue = ghost1 - 0.5 * _rotate(d1, -3.0)
    aim = ghost1 - 0.001 * np.array([-d1[1], d1[0]]) - cue
    return _shot([cue, b1, b2], aim, speed, run, offset, table, ball)


def break_shot(speed, run, offset=None, table=None, ball=REGULATION):
    """The full rack (0.2 mm jitter, seed = run), cue ball from the head spot at the apex ball."""
    table = Table.eight_foot() if table is None else table
    balls = rack(table, seed=run, radius=ball[0], mass=ball[1])
    aim = _unit(balls.xy[1] - balls.xy[0])
    offset = (0.0, 0.0) if offset is None else offset
    return strike(balls, force=aim * speed * ball[1] / CONTACT, offset=offset), table


@dataclasses.dataclass(frozen=True)
class Scene:
    name: str
    build: object
    speeds: tuple  # slow, fast (m/s)
    what: str


SCENES = (
    Scene("single", single, (0.4, 0.8), "one ball to rest, friction only"),
    Scene("cut", cut, (1.5, 5.0), "30 degree cut into a corner pocket"),
    Scene("bank", bank, (2.5, 5.0), "object ball banked off a long rail into a corner"),
    Scene("combination", combination, (1.5, 5.0), "cue ball, ball 1, ball 2 into a corner"),
    Scene("break", break_shot, (4.0, 8.0), "16-ball break, jittered rack (seed = run)"),
)


def build(scene, speed, run, offset=None, table=None, ball=REGULATION):
    balls, t = scene.build(speed, run, offset, table, ball)
    return balls, (Table.eight_foot() if t is None else t)


EFFECTS = (
    ("seed physics, no pockets (the report's scene)", Physics.seed(), Table.seed, None),
    ("seed physics, pockets", Physics.seed(), Table.eight_foot, None),
    ("standard, spin off, no pockets", dataclasses.replace(Physics.standard(), spin=False), Table.seed, None),
    ("standard, spin off, pockets", dataclasses.replace(Physics.standard(), spin=False), Table.eight_foot, None),
    ("standard, no pockets", Physics.standard(), Table.seed, None),
    ("standard, pockets", Physics.standard(), Table.eight_foot, None),
    ("standard, pockets, English on every shot", Physics.standard(), Table.eight_foot, (0.3, 0.2)),
)
TRANSITIONS = ("sliding_rolling", "rolling_spinning", "rolling_stationary", "spinning_stationary",
               "sliding_stationary", "sliding_spinning")
