"""`Game`: one pool game as an object (state, `play`, `snapshot`/`restore`, `evaluate`), which every client drives."""

from __future__ import annotations

import copy

import numpy as np

from .. import rules
from ..physics import Balls, Physics, Table
from ..physics.randomize import Randomization, Sample
from .actions import LAYOUTS, ActionLayout, decode_action, decode_decision, encode_action, encode_decision
from .batch import simulate_struck
from .evaluation import JudgedShot, evaluate_shots
from .judging import shot_record
from .modes import Mode, mode_of
from .placement import placement_area
from .shot import Shot, noise_of
from .shot_record import GameSnapshot, ShotRecord, StruckShot
from .snapshots import check_snapshot, game_key, snapshot_of
from .snapshots import table_key as table_key  # re-exported: it was defined here
from .starting import check_calling, check_layout, check_state, objects_on, random_cue_start
from .striking import CALLING_RULES as CALLING_RULES  # re-exported: it was defined here
from .striking import check_can_shoot, shot_and_action, struck_encoded, struck_shot


class Game:
    """One pool game: "break" (the break shot alone), "run" (the shooter plays on until a
    scratch or the last ball), "nine_ball" or "eight_ball" (the WPA rules of `pool_env.rules`).

    ```python
    from pool_env.game import Game, Shot

    game = Game("nine_ball", seed=0)                        # racked, player 0 to break
    record = game.play(Shot.aimed((1.0, 0.0), 9.0, place=(0.5, 0.56)))
    print(record.pocketed, record.foul, game.shooter, game.ball_in_hand)
    ```

    State (read-only): `balls`, `state` (the rules' `GameState`; None without rules),
    `shooter` (0 or 1), `ball_in_hand`, `legal_targets`, `shots` (played), `winner`, `over`.
    `rng` is the noise generator (assignable, like an env's `np_random`).

    - `play(shot)`: one shot, all of it: ball-in-hand placement, the called pocket, the noise,
      the strike, the simulation, the rules' judgement and spotting. `shot` is a `Shot` or an
      action vector of the game's layout (`layout`, `decode`/`encode`). Returns a `ShotRecord`;
      a shot the simulator cannot finish (or whose balls the rules cannot put back) is recorded
      with its `error` and changes nothing.
    - `snapshot()` / `restore(snapshot)`: the whole state, the noise generator's included:
      restore, then play the same shot, and the record is bit-identical.
    - `evaluate(shots, draws=M, seed=...)`: K shots x M noise draws from the current state in
      one batched simulation, without changing the game: the K x M records in order (shot
      major), each equal to restoring a snapshot and playing that shot (see `evaluate`).
    - `strike(shot)` and `resolve(struck, result)`: `play`'s two halves, for callers that
      simulate many games' shots at once (`play_batch`).

    Options: `noise` None, "olympiad" or a dict of standard deviations (`shot.NOISE_PRESETS`);
    `layout` the action layout (`actions.LAYOUTS`; default the mode's: "cue" for break and run,
    "cue_spin" adds the tip); `randomize_cue` (break and run) starts the cue ball anywhere in
    x in [0.05 L, 0.25 L], y in [0.1 W, 0.9 W]; other keywords are the rule set's options
    (`NineBall(three_foul_rule=...)`, `EightBall(illegal_break=...)`).

    `randomize` (None, "default" or a dict: `physics.randomize.Randomization`) draws the physics,
    table and ball parameters afresh at every `reset`, from the game's generator (one draw of it,
    before the rack's; None draws nothing, so the games stay as without); `table` and `physics`
    are then the drawn ones, `base_table` and `base_physics` those given, `sample` the draw.
    """

    def __init__(self, mode: str = "nine_ball", table: Table | None = None, physics: Physics | None = None,
                 noise=None, seed=None, layout: str | None = None, randomize_cue: bool = False,
                 decisions: bool | None = None, randomize=None, **rule_options):
        self._mode: Mode = mode_of(mode)
        self.table = self._mode.table() if table is None else table
        if not isinstance(self.table, Table):
            raise TypeError(f"table must be pool_env.physics.Table, got {type(self.table).__name__}")
        self.physics = self._mode.physics() if physics is None else physics
        if not isinstance(self.physics, Physics):
            raise TypeError(f"physics must be pool_env.physics.Physics, got {type(self.physics).__name__}")
        self.noise = noise_of(noise)
        layout = self._mode.default_layout(rule_options) if layout is None else layout
        if layout not in LAYOUTS:
            raise ValueError(f"unknown action layout {layout!r}; choose one of {', '.join(LAYOUTS)}")
        self.layout: ActionLayout = LAYOUTS[layout]
        if self.layout.placement != self._mode.placement:
            raise ValueError(f"layout {layout!r} does not fit the {mode} mode")
        check_calling(self._mode, self.layout, rule_options)
        if randomize_cue and self._mode.rules is not None:
            raise ValueError("randomize_cue is for the break and run modes (the rules place the cue ball)")
        if rule_options and self._mode.rules is None:
            raise TypeError(f"the {mode} mode has no rules to take options {sorted(rule_options)}")
        self.randomize_cue = bool(randomize_cue)
        # With decisions, a choice the rules leave (`pending`) waits for `decide`; without, its default applies.
        self.decisions = bool(self.layout.decision) if decisions is None else bool(decisions)
        self.rule_options = dict(rule_options)
        if self._mode.rules is not None:
            rules.new_game(self._mode.rules, **self.rule_options)  # bad options raise here
        self.base_table, self.base_physics = self.table, self.physics
        self.randomization = None if randomize is None else Randomization(
            randomize, self.table, self.physics, self._mode.balls, self._mode.equipment)
        self.sample: Sample | None = None
        self.rng = np.random.default_rng(seed)
        self._balls, self._state, self._shots, self._over = None, None, 0, False
        self.reset()

    # --- read-only state ----------------------------------------------------------------------
    @property
    def mode(self) -> str:
        return self._mode.name

    @property
    def label(self) -> str:
        """The mode's name for people ("9-ball")."""
        return self._mode.label

    @property
    def n_balls(self) -> int:
        return self._mode.balls

    @property
    def has_rules(self) -> bool:
        return self._mode.rules is not None

    @property
    def balls(self) -> Balls:
        """The balls now, at rest (read-only arrays), ball k is number k."""
        return self._balls

    @property
    def state(self) -> rules.GameState | None:
        """The rules' state (`rules.GameState`, immutable); None in the break and run modes."""
        return self._state

    @property
    def shooter(self) -> int:
        return 0 if self._state is None else self._state.shooter

    @property
    def ball_in_hand(self) -> str | None:
        """None (the cue ball plays from where it lies), "anywhere" or "behind_head_string"."""
        return None if self._state is None or self._state.winner is not None else self._state.ball_in_hand

    @property
    def legal_targets(self) -> frozenset:
        """The object balls the shooter may hit first (without rules: any on the table)."""
        if self._state is None:
            return objects_on(self._balls)
        return frozenset() if self._state.winner is not None else rules.legal_targets(self._state)

    @property
    def pending(self):
        """The `rules.Decision` the shooter makes before he shoots (`decide`), or None. Only
        with `decisions` (a layout with the decision entry, or `Game(..., decisions=True)`);
        otherwise the decision's default applies as the shot before it is judged."""
        return getattr(self._state, "pending", None) if self._state is not None else None

    @property
    def may_push_out(self) -> bool:
        """The shooter may declare this shot a push out (`Shot.push_out`: WPA 2.4)."""
        return bool(getattr(self._state, "push_out", False)) and not self._over

    def decide(self, option: str):
        """The shooter takes `option` of the pending decision (`pending.options`); the new
        rules' state. A re-rack (8-ball, WPA 3.3(d)-(f)) racks the balls afresh from the
        game's generator. ValueError when no decision is pending or `option` is not one."""
        if self.pending is None:
            raise ValueError("no decision is pending: the shooter shoots (play)")
        state = rules.decide(self._state, option)
        if state.is_break and not self._state.is_break:
            self._balls = self._rack(int(self.rng.integers(2**63 - 1)))
        self._state = state
        return state

    @property
    def calls_pocket(self) -> bool:
        """The shooter must call a pocket (`Shot.pocket`) for this shot: every shot but the
        break in 10-ball and in 8-ball with called shots (WPA 1.6); with `calling="eight_only"`
        only shooting at the 8."""
        state = self._state
        if self._mode.rules == "ten_ball" or self.layout.called_ball:  # every shot but the break (Ten Ball 5, 1.6)
            return state.winner is None and not state.is_break
        return (self._mode.rules == "eight_ball" and state.winner is None and not state.is_break
                and self.legal_targets == frozenset({8}))

    @property
    def shots(self) -> int:
        """Shots played (a shot the simulator could not finish does not count)."""
        return self._shots

    @property
    def winner(self) -> int | None:
        return None if self._state is None else self._state.winner

    @property
    def over(self) -> bool:
        """The game has ended: a winner, or (without rules) the break played, a scratch, or the
        last object ball down on a table with pockets."""
        return self._over

    def placement_area(self, where: str | None = None):
        """(x_lo, x_hi, y_lo, y_hi) of the cue ball's centre with ball in hand `where` (default:
        the shooter's now); None when he has none."""
        where = self.ball_in_hand if where is None else where
        return None if where is None else placement_area(self.table, where, float(self._balls.radii[0]))

    # --- actions --------------------------------------------------------------------------------
    def decode(self, action) -> Shot:
        """The `Shot` an action vector of the game's layout means now (the ball-in-hand entries
        map onto the shooter's placement area). ValueError for a wrong shape or a non-finite entry."""
        return decode_action(self.layout, action, self.placement_area(), self.table.pockets.shape[0],
                             self._called_targets(), self.may_push_out)

    def decode_decision(self, action) -> str:
        """The option of the pending decision an action of a layout with the decision entry
        picks (`actions.decode_decision`). ValueError without a decision pending or the entry."""
        if self.pending is None:
            raise ValueError("no decision is pending: the action is a shot (decode)")
        return decode_decision(self.layout, action, self.pending.options)

    def encode_decision(self, option: str) -> np.ndarray:
        """The action (float32) that `decode_decision` reads back as `option` now."""
        if self.pending is None:
            raise ValueError("no decision is pending: the action is a shot (encode)")
        return encode_decision(self.layout, option, self.pending.options)

    def encode(self, shot: Shot) -> np.ndarray:
        """The action vector (float32) of the game's layout that `decode` reads back as `shot` now."""
        return encode_action(self.layout, shot, self.placement_area(), self.table.pockets.shape[0],
                             self._called_targets())

    @property
    def called_targets(self) -> tuple:
        """The balls an action's called-ball entry chooses among now, ascending (the first when
        a Shot names none): 8-ball the legal targets, 10-ball every ball on the table."""
        return self._called_targets()

    def _called_targets(self) -> tuple:
        """The balls an action's called-ball entry chooses among (a layout with one): the legal
        targets, ascending; none on the break (WPA 3.3: nothing is called)."""
        if not self.layout.called_ball or self._state is None or self._state.is_break:
            return ()
        if self._mode.rules == "ten_ball":  # any ball on the table may be called (WPA Ten Ball 5)
            return tuple(sorted(self._state.on_table))
        return tuple(sorted(self.legal_targets))

    # --- starting -------------------------------------------------------------------------------
    def reset(self, seed=None, *, rng=None, balls: Balls | None = None, breaker: int = 0,
              ball_in_hand: bool = False, state: rules.GameState | None = None) -> Game:
        """A new game: `seed` reseeds the noise generator (or `rng` replaces it); a rack drawn
        from it (with `randomize`, the equipment first, drawn from it; the cue ball's random start next,
        with `randomize_cue`, then the rack's seed, drawn even when `balls` is given, whose sizes
        stay theirs), `breaker` (0 or 1) to break. `balls` starts from a
        layout instead (`n_balls` balls at rest by number, the cue ball on the table; with rules
        an open table, the last ball on it, `ball_in_hand` anywhere if asked), `breaker` to
        shoot; or, with `state` (a `rules.GameState` of this game's rules whose `on_table` is
        the layout's), from that position of a game (a planner's)."""
        if rng is not None:
            self.rng = rng
        elif seed is not None:
            self.rng = np.random.default_rng(seed)
        if breaker not in (0, 1) or isinstance(breaker, (bool, np.bool_)):
            raise ValueError(f"breaker must be 0 or 1, got {breaker!r}")
        if self.randomization is not None:  # the equipment first: the rack stands on it
            self.sample = self.randomization.sample(self.rng)
            self.table, self.physics = self.sample.table, self.sample.physics
        cue_xy = random_cue_start(self.table, self.rng) if self.randomize_cue else None
        rack_seed = int(self.rng.integers(2**63 - 1))
        if balls is None:
            self._balls = self._rack(rack_seed, cue_xy)
            state = rules.new_game(self._mode.rules, breaker=breaker, **self.rule_options) if self.has_rules else None
        else:
            self._balls = check_layout(self._mode, balls, self.table, self.physics, position=state is not None)
            if state is not None:
                check_state(self._mode, state, balls)
            elif self.has_rules:
                state = rules.open_table(self._mode.rules, objects_on(balls), breaker, ball_in_hand,
                                         **self.rule_options)
        self._state, self._shots, self._over = state, 0, False
        return self

    def _rack(self, seed, cue_xy=None) -> Balls:
        """The mode's rack, its balls sized as drawn (with `randomize`). A drawn table is the
        base one's size (only its nose and mouths differ, far from the spots): the rack is laid on
        the base table, whose layout is checked once, not at every draw."""
        if self.sample is None:
            return self._mode.rack(self.table, seed, cue_xy)
        return self.sample.sized(self._mode.rack(self.base_table, seed, cue_xy))

    # --- playing ------------------------------------------------------------------------------
    def play(self, shot) -> ShotRecord:
        """Play one shot (a `Shot` or an action vector) from the state now; see the class."""
        struck = self.strike(shot)
        return self.resolve(struck, simulate_struck(struck, self.table, self.physics))

    def strike(self, shot, rng=None) -> StruckShot:
        """`play`'s first half: the shot checked, the cue ball placed (ball in hand), the noise
        drawn (from `rng`, default the game's generator) and the cue ball struck. Changes
        nothing but the generator. RuntimeError if the game is over, ValueError for a bad shot."""
        check_can_shoot(self)
        return struck_shot(self, self._mode, *shot_and_action(self, shot), rng)

    def strike_encoded(self, shot: Shot, rng=None) -> StruckShot:
        """`strike` of the action vector that `encode` makes of `shot` (`strike(encode(shot))`,
        the same StruckShot bit for bit: the shot as its float32 entries play it, and those
        entries its `action`), without building the vector: for players that decide from the
        game's state and hand it the Shot an env action of theirs would carry."""
        check_can_shoot(self)
        return struck_encoded(self, self._mode, shot, rng)

    def resolve(self, struck: StruckShot, result) -> ShotRecord:
        """`play`'s second half: apply the simulation's `Result` (or the SimulationError or
        ValueError it raised) of `struck` from this state, and return the record."""
        record = self.judge(struck, result)
        if record.error is None:
            self._balls, self._state, self._over = record.balls_after, record.state_after, record.over
            self._shots += 1
        else:  # the balls stay put (the cue ball where it was placed)
            self._balls = record.balls_before
        return record

    def judge(self, struck: StruckShot, result, rulings: dict | None = None) -> ShotRecord:
        """The record of `struck`'s simulation from this state, without changing the game
        (`rulings`: a cache of the rules' judgements from this state, by outcome and called pocket)."""
        return shot_record(struck, result, self._state, self.table, self._mode, self.decisions, rulings)

    # --- branching ------------------------------------------------------------------------------
    @property
    def key(self) -> tuple:
        """What a snapshot must match to be restored here: mode, table, physics, noise, rules, and
        whether choices wait for `decide` (a pending choice means nothing to a game that never waits)."""
        return game_key(self)

    def snapshot(self) -> GameSnapshot:
        """The whole state now, the noise generator's included."""
        return snapshot_of(self)

    def restore(self, snapshot: GameSnapshot) -> Game:
        """Put back a `snapshot` of this game (or of one made with the same mode, table, physics,
        noise, rules and decisions); the generator's state is set in place. ValueError for another game's."""
        check_snapshot(self, snapshot)
        self._balls, self._state, self._shots, self._over = snapshot.balls, snapshot.state, snapshot.shots, \
            snapshot.over
        self.rng.bit_generator.state = copy.deepcopy(snapshot.rng_state)
        return self

    def evaluate(self, shots, draws: int = 1, seed=None, threads: int | None = 1,
                 records: bool = True, common: bool = False) -> list[ShotRecord] | list[JudgedShot]:
        """K candidate `shots` (Shots or action vectors) x `draws` noise draws each, from the
        state now, simulated in one `simulate_batch` call (`threads` as there); the game does not
        change. Returns the K x draws records, shot major (record k * draws + j is draw j of
        shot k). The noise comes from one generator, drawn in that order: `seed` an int (or
        anything `numpy.random.default_rng` takes) seeds a new one; a `numpy.random.Generator`
        is used (and advanced); None copies the game's own (so with draws=1, record k equals
        `restore(snapshot)` then `play(shot k)`). Record k * draws + j equals restoring the
        snapshot, setting `rng` to that generator as it stands after the draws before it, and
        playing shot k. ValueError for no shots, draws < 1 or a bad shot (naming which).
        `common=True` gives every shot the same noise (common random numbers: draw j of each
        shot takes the same cue errors, drawn once from the generator as `draws` x 5 normals),
        so differences between shots are measured without the noise between their draws.

        `records=False` returns `JudgedShot`s instead (the records' outcome, ruling, state and
        balls after, without the physics `Result`): in the pool games the level shots are
        then simulated in compiled calls that each run many (`threads` of them at once) and
        each distinct outcome is judged once (`evaluation.judge_batch`): a shot's Python work
        is mostly gone."""
        return evaluate_shots(self, self._mode, shots, draws, seed, threads, records, common)
