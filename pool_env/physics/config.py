"""Physics configuration: model switches and cloth/ball-contact coefficients, with presets."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .frozen import unchecked

# Model names accepted by the engine, in the order of their numeric ids (the id is
# what the compiled engine dispatches on).
BALL_BALL_MODELS = ("seed", "elastic", "frictional")
CUSHION_MODELS = ("seed", "restitution", "han2005", "mathavan2010")

# The cushion models that touch the ball at the cushion's nose height h rather than at its
# equator: a ball meets a rail when its centre is R cos(theta) from the nose line,
# sin(theta) = h / R - 1 (the contact point is on the ball's surface at height h).
NOSE_HEIGHT_MODELS = ("han2005", "mathavan2010")

# The collision models (ball-ball, cushion) of the standard and carom presets: the only ones
# the event engine's core compiles; any other runs on its full engine (see engine.run).
CORE_MODELS = ("frictional", "han2005")

# The seed report's rolling-resistance angle (table 3.1): the rolling ball decelerates
# at 5/7 g theta (report eq. 2.11), so the equivalent rolling coefficient is 5/7 theta.
SEED_THETA = 0.01


# Each coefficient's valid values, as __post_init__ checks them (`Physics.variant`): a finite
# number > 0 (the smallest positive double up to the largest), in [0, 1], or finite and >= 0.
_POSITIVE, _FRACTION, _NONNEGATIVE = (5e-324, 1.7976931348623157e308), (0.0, 1.0), (0.0, 1.7976931348623157e308)
# The coefficients in the order the compiled engine reads them (motion.P_*): name -> index.
PARAM_INDEX = {name: k for k, name in enumerate(("mu_s", "mu_r", "mu_sp", "g", "e_b", "e_c", "f_c", "e_t", "mu_t"))}
COEFFICIENT_RANGES = {"mu_s": _POSITIVE, "mu_r": _POSITIVE, "mu_sp": _POSITIVE, "g": _POSITIVE, "e_b": _FRACTION,
                      "e_c": _FRACTION, "e_t": _FRACTION, "f_c": _NONNEGATIVE, "mu_t": _NONNEGATIVE}


def _named(valid) -> tuple:
    """The coefficients whose valid values are `valid` (one of the ranges above), in order."""
    return tuple(name for name, values in COEFFICIENT_RANGES.items() if values is valid)


@dataclasses.dataclass(frozen=True)
class Physics:
    """How balls move and collide. Frozen: derive variants with `dataclasses.replace`.

    | field | meaning | unit |
    | --- | --- | --- |
    | `ball_ball` | ball-ball model: `seed`, `elastic` or `frictional` | name |
    | `cushion` | ball-cushion model: `seed`, `restitution`, `han2005` or `mathavan2010` | name |
    | `mu_s` | sliding friction, ball on cloth | 1 |
    | `mu_r` | rolling resistance: a rolling ball decelerates at `mu_r * g` | 1 |
    | `mu_sp` | spinning friction: z-spin decays at `5 mu_sp g / (2 R)` | 1 |
    | `e_b` | ball-ball coefficient of restitution | 1 |
    | `e_c` | ball-cushion coefficient of restitution | 1 |
    | `f_c` | ball-cushion friction (han2005, mathavan2010) | 1 |
    | `e_t` | ball-table (slate) coefficient of restitution: a landing ball rebounds at e_t v_z | 1 |
    | `mu_t` | ball-table friction during a bounce (TP A-14's model: airborne.table_impulse) | 1 |
    | `g` | gravitational acceleration | m/s^2 |
    | `spin` | track z-spin (English) and the spinning state; off means z-spin is dropped | bool |
    """

    ball_ball: str = "frictional"
    cushion: str = "han2005"
    mu_s: float = 0.2
    mu_r: float = 0.01
    mu_sp: float = 0.01
    e_b: float = 0.95
    e_c: float = 0.85
    f_c: float = 0.2
    g: float = 9.81
    spin: bool = True
    # The slate: e_t = 0.5 and a friction equal to the cloth's sliding friction are pooltool's
    # defaults (pooltool.objects.ball.params.BallParams.e_t, and its FrictionalInelasticTable
    # model, which takes u_s for the ball-table friction), after Alciatore's TP A-14 model.
    e_t: float = 0.5
    mu_t: float = 0.2

    def __post_init__(self):
        if self.ball_ball not in BALL_BALL_MODELS:
            raise ValueError(
                f"unknown ball_ball model {self.ball_ball!r}; choose one of {', '.join(BALL_BALL_MODELS)}"
            )
        if self.cushion not in CUSHION_MODELS:
            raise ValueError(f"unknown cushion model {self.cushion!r}; choose one of {', '.join(CUSHION_MODELS)}")
        for name in _named(_POSITIVE):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"Physics.{name} must be a finite number > 0, got {value!r}")
        for name in _named(_FRACTION):
            value = getattr(self, name)
            if not (math.isfinite(value) and 0 <= value <= 1):
                raise ValueError(f"Physics.{name} must be in [0, 1], got {value!r}")
        for name in _named(_NONNEGATIVE):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0):
                raise ValueError(f"Physics.{name} must be a finite number >= 0, got {value!r}")
        # The engine's view of the coefficients, built once (see motion.P_*).
        params = np.array([getattr(self, name) for name in PARAM_INDEX])
        object.__setattr__(self, "_params", params)
        # The model ids the compiled code dispatches on (each name's position in its tuple).
        ids = (BALL_BALL_MODELS.index(self.ball_ball), CUSHION_MODELS.index(self.cushion))
        object.__setattr__(self, "_model_ids", ids)
        engine = (params, ids[0], ids[1], bool(self.spin), self.can_create_spin(), self.cushion in NOSE_HEIGHT_MODELS)
        object.__setattr__(self, "_engine_args", engine)
        core = (params, None, None, *engine[3:]) if (self.ball_ball, self.cushion) == CORE_MODELS else None
        object.__setattr__(self, "_core_engine_args", core)

    @classmethod
    def seed(cls) -> Physics:
        """The seed report's model, exactly: centre hits, no spin transfer, balls roll after
        every collision, e_b = 0.97, e_c = 0.5, rolling deceleration 5/7 g theta with
        theta = 0.01 rad. The report gives no sliding friction; mu_s = 0.2 is our choice."""
        return cls(
            ball_ball="seed", cushion="seed", mu_s=0.2, mu_r=5.0 / 7.0 * SEED_THETA,
            mu_sp=0.01, e_b=0.97, e_c=0.5, f_c=0.0, g=9.81, spin=False,
        )

    @classmethod
    def standard(cls) -> Physics:
        """The realistic default: Alciatore's frictional ball-ball contact (throw and spin
        transfer), Han (2005) cushion with height and friction, spin tracked, and common cloth
        values (mu_s 0.2, mu_r 0.01; cf. the defaults of pooltool and Alciatore's
        "Illustrated Principles of Pool and Billiards", appendix)."""
        return cls()

    @classmethod
    def carom(cls) -> Physics:
        """Carom cloth and cushions (three-cushion): pooltool's published three-cushion ball
        parameters (pooltool.objects.ball.params, BILLIARD_GENERIC, the default of its
        THREECUSHION game) for the cushion, e_c = 0.85 and f_c = 0.5 (a carom cushion grips the
        ball harder than a pool cushion's 0.2: running English off a rail is the game's tool);
        the cloth as the standard preset (Alciatore, "Illustrated Principles of Pool and
        Billiards", appendix: mu_s 0.2, mu_r 0.01; pooltool lists u_s = 0.5 there, which its
        source calls not well researched, and a sliding friction that high would stop draw
        and follow almost at once); e_b 0.95 as the standard (phenolic balls alike)."""
        return cls(ball_ball="frictional", cushion="han2005", mu_s=0.2, mu_r=0.01, mu_sp=0.01, e_b=0.95,
                   e_c=0.85, f_c=0.5)

    def variant(self, **coefficients) -> Physics:
        """This physics with the given coefficients (float fields) replaced: the same as
        `dataclasses.replace(self, **coefficients)`, the same ValueError for a value out of its
        range, without the dataclass's set-up (a randomized reset draws one at every reset)."""
        for name, value in coefficients.items():
            low, high = COEFFICIENT_RANGES.get(name, (1.0, 0.0))
            if not (value.__class__ is float and low <= value <= high):  # replace says what is wrong
                return dataclasses.replace(self, **coefficients)
        return self._with(coefficients)

    def _with(self, coefficients: dict) -> Physics:
        """`variant` of coefficients already checked (each a float in its COEFFICIENT_RANGES):
        the physics' friends' (randomize.py draws inside ranges checked at both ends)."""
        state = self.__dict__.copy()
        state.update(coefficients)
        params = self._params.copy()
        for name, value in coefficients.items():
            params[PARAM_INDEX[name]] = value
        state["_params"] = params
        state["_engine_args"] = (params, *self._engine_args[1:])
        if self._core_engine_args is not None:
            state["_core_engine_args"] = (params, *self._core_engine_args[1:])
        return unchecked(Physics, state)

    def can_create_spin(self) -> bool:
        """True when a collision model can give a ball z-spin it did not have."""
        return self.ball_ball == "frictional" or self.cushion in ("han2005", "mathavan2010")

    def model_ids(self) -> tuple[int, int]:
        """The ball-ball and cushion model ids the compiled engine dispatches on."""
        return self._model_ids

    def core_engine_args(self) -> tuple | None:
        """engine_args with the model ids None, which selects CORE_MODELS in the event engine's
        core (see engine.run); None when the models are others."""
        return self._core_engine_args

    def engine_args(self) -> tuple:
        """What engine.simulate_scene reads, built once: (the coefficients, the ball-ball and
        cushion model ids, spin tracked, whether a collision can create z-spin, whether the
        cushion touches at the nose height)."""
        return self._engine_args

    def as_array(self) -> np.ndarray:
        """The coefficients in the order the compiled engine reads them (see motion.P_*)."""
        return self._params


def cushion_reach(radius, height, cushion):
    """How far a ball's centre is from a rail's nose line (or a facing) when it touches it
    (m): R cos(theta) for the models in NOSE_HEIGHT_MODELS, whose nose at height h meets the
    ball at sin(theta) = h/R - 1, else R (the cushion is a wall at the ball's equator).
    `radius` is a number or an array of radii. A ball no taller than the nose (h >= 2R) is
    refused before it gets here (check_on_table)."""
    if cushion not in NOSE_HEIGHT_MODELS:
        return radius
    if np.ndim(radius) == 0:
        sin_t = min(max(height / radius - 1.0, -1.0), 1.0)
        return radius * math.sqrt(1.0 - sin_t * sin_t)
    sin_t = np.clip(height / radius - 1.0, -1.0, 1.0)
    return radius * np.sqrt(1.0 - sin_t * sin_t)
